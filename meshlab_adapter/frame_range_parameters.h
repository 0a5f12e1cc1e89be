// SPDX-License-Identifier: GPL-3.0-or-later
// The frames to load from an .ams file as MeshLab parameters, shared by the Import Compressed
// Animation filter and the .ams open dialog so both offer the same choice.
#pragma once
#include "meshlab_compat.h"

#include "layer_frames.h"

namespace animc::meshlab {

// FirstFrame (default 0) and LastFrame (default -1: the file's last frame).
void addFrameRangeParameters(RichParameterList& par);

// MemoryLimitMB, the most the new layers may take, and WorkLimitMVF, the most decoding them may
// cost (millions of vertex-frames, DecoderLimits::max_vertex_frames). Only the .ams open dialog
// offers them: a new parameter of a filter would break every .mlx script that names the filter
// (meshlabserver 2020.09 aborts on a script that does not list every parameter).
void addLimitParameters(RichParameterList& par);

// $ANIMC_MEMORY_LIMIT_MB and $ANIMC_MAX_VERTEX_FRAMES when they are positive integers (how
// scripts and filters raise the limits), else AmsImport's defaults.
int64_t defaultMemoryLimitMegabytes();
uint64_t defaultMaxVertexFrames();

// The range those parameters ask for; one missing from `par` keeps its default.
AmsImport frameRangeFrom(const RichParameterList& par);

}  // namespace animc::meshlab
