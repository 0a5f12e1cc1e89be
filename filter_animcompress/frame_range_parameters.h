// SPDX-License-Identifier: GPL-3.0-or-later
// The frames to load from an .ams file as MeshLab parameters, shared by the Import Compressed
// Animation filter and the .ams open dialog so both offer the same choice.
#pragma once
#include <common/filter_parameter/rich_parameter_list.h>

#include "layer_frames.h"

namespace animc::meshlab {

// FirstFrame (default 0) and LastFrame (default -1: the file's last frame).
void addFrameRangeParameters(RichParameterList& par);

// The range those parameters ask for; one missing from `par` keeps its default.
AmsImport frameRangeFrom(const RichParameterList& par);

}  // namespace animc::meshlab
