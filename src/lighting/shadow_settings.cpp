#include "lighting/shadow_settings.h"

namespace zs {

const char* to_string(DepthSelect s) { return s == DepthSelect::Max ? "max" : "min"; }
const char* to_string(ShadowMode m) { return m == ShadowMode::Map ? "map" : "exact"; }

}  // namespace zs
