#include "accel/verify/verify_keys.h"

#include "accel/registry.h"
#include "framework/config/common_keys.h"
#include "framework/render/render_keys.h"

namespace bvhlab::verify {

const EnvRegistry& verifyKeys() {
    static const EnvRegistry registry = [] {
        EnvRegistry r;
        registerCommonKeys(r);
        registerRenderKeys(r);
        registerAcceleratorKeys(r);
        return r;
    }();
    return registry;
}

}  // namespace bvhlab::verify
