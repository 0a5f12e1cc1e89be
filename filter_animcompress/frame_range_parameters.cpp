// SPDX-License-Identifier: GPL-3.0-or-later
#include "frame_range_parameters.h"

namespace animc::meshlab {

void addFrameRangeParameters(RichParameterList& par) {
  par.addParam(RichInt("FirstFrame", 0, "First frame", "First frame to load as a layer (0 = the first)."));
  par.addParam(RichInt("LastFrame", -1, "Last frame", "Last frame to load; -1 = the last frame of the file."));
}

AmsImport frameRangeFrom(const RichParameterList& par) {
  AmsImport range;
  if (par.hasParameter("FirstFrame")) range.first_frame = par.getInt("FirstFrame");
  if (par.hasParameter("LastFrame")) range.last_frame = par.getInt("LastFrame");
  return range;
}

}  // namespace animc::meshlab
