// Spheres and cones and their tests are part of the plugin API (<bvhlab/quadric_shape.h>); this
// header adds GLM's functions for bvhlab's own code around them.
#pragma once

#include "framework/core/math.h"

#include <bvhlab/quadric_shape.h>
