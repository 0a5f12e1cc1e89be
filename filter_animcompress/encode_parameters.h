// The encoder settings as MeshLab parameters, shared by the Compress filter and the .ams save
// dialog so both offer the same choices, defaults and limits as `animc encode`.
#pragma once
#include <common/filter_parameter/rich_parameter_list.h>

#include "api.h"

namespace animc::meshlab {

// Codec, Profile, MaxErrorPercent, Bits, IFrameInterval. MaxErrorPercent is the CLI's
// --max-error times 100 (percent of the root cube's side, as the paper writes ME).
void addEncodeParameters(RichParameterList& par);

// Reads and validates what addEncodeParameters declared.
Result<EncodeSettings> encodeSettingsFrom(const RichParameterList& par);

}  // namespace animc::meshlab
