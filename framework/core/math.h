// Vec3 and Bounds3 are part of the plugin API (<bvhlab/math.h>); bvhlab's own code has all of
// GLM besides.
#pragma once

#include <bvhlab/math.h>

#include <glm/glm.hpp>
