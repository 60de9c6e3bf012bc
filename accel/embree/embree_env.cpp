#include "accel/embree/embree_env.h"

namespace bvhlab {

void registerEmbreeKeys(EnvRegistry& r) {
    r.add(keys::Embree::quality);
    r.add(keys::Embree::robust);
    r.add(keys::Embree::threads);
}

}  // namespace bvhlab
