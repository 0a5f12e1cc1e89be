// SPDX-License-Identifier: GPL-3.0-or-later
// The encoder settings as MeshLab parameters, shared by the Compress filter and the .ams save
// dialog so both offer the same choices, defaults and limits as `animc encode`.
#pragma once
#include "meshlab_compat.h"

#include "api.h"

namespace animc::meshlab {

// Codec, Profile, MaxErrorPercent, Bits, WaveletStepPercent, WaveletBitsPerVertex,
// WaveletTargetKG, WaveletFrames, IFrameInterval. MaxErrorPercent is the CLI's --max-error
// times 100 (percent of the root cube's side, as the paper writes ME), WaveletStepPercent its
// --step times 100. Every
// parameter is always there (a script must name them all); those of the codec not chosen
// are ignored.
void addEncodeParameters(RichParameterList& par);

// Reads and validates what addEncodeParameters declared.
Result<EncodeSettings> encodeSettingsFrom(const RichParameterList& par);

}  // namespace animc::meshlab
