// SPDX-License-Identifier: GPL-3.0-or-later
// "Compress Animation Layers": the document's layers are the frames of one animation; encode
// them to an .ams file, optionally add the decoder's frames as layers and colour by error.
#pragma once
#include <string>

#include <cstdint>

#include "meshlab_compat.h"
#include "plugin_support.h"

namespace animc::meshlab {

void addCompressParameters(const MeshDocument& md, RichParameterList& par);

// The figures of a successful compression, which MeshLab 2022+ hands to PyMeshLab's caller.
struct CompressFigures {
  double ratio = 0;
  double bpvf = 0;
  double kg_error = 0;  // percent
  double psnr = 0;
  double max_error = 0;  // mesh units
  uint64_t bytes = 0;
};

// Returns an empty string on success, else why nothing was written, added or changed (the
// layers' quality and colours included). `figures` (may be null) gets the file's figures.
std::string compressLayers(MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb,
                           const LogFn& log, CompressFigures* figures = nullptr);

}  // namespace animc::meshlab
