// SPDX-License-Identifier: GPL-3.0-or-later
// "Animation Reconstruction Error": compares two equally long runs of layers (originals and
// reconstructions), stores per-vertex error as quality on the reconstructions, colours them on
// one scale for all frames, and logs per-frame and whole-animation figures.
#pragma once
#include "meshlab_compat.h"

#include "plugin_support.h"

namespace animc::meshlab {

void addErrorParameters(const MeshDocument& md, RichParameterList& par);

// Returns an empty string on success, else why nothing was changed.
std::string measureReconstructionError(MeshDocument& md, const RichParameterList& par,
                                       vcg::CallBackPos* cb, const LogFn& log);

}  // namespace animc::meshlab
