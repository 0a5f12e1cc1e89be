// SPDX-License-Identifier: GPL-3.0-or-later
// "Compress Animation Layers": the document's layers are the frames of one animation; encode
// them to an .ams file, optionally add the decoder's frames as layers and colour by error.
#pragma once
#include <string>

#include <common/filter_parameter/rich_parameter_list.h>
#include <common/meshmodel.h>

#include "plugin_support.h"

namespace animc::meshlab {

void addCompressParameters(const MeshDocument& md, RichParameterList& par);

// Returns an empty string on success, else why nothing was written, added or changed (the
// layers' quality and colours included).
std::string compressLayers(MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb,
                           const LogFn& log);

}  // namespace animc::meshlab
