#include "framework/config/common_keys.h"

namespace bvhlab {

void registerCommonKeys(EnvRegistry& registry) { registry.add(keys::SetRayTracing::threads); }

}  // namespace bvhlab
