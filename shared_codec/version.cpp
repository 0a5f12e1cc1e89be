// SPDX-License-Identifier: Apache-2.0
#include "animc/animc.h"

namespace animc {

const char* animcVersion() { return ANIMC_VERSION_STRING; }

}  // namespace animc
