// The watertight triangle test is part of the plugin API (<bvhlab/triangle.h>); this header adds
// GLM's functions for bvhlab's own code around it.
#pragma once

#include "framework/core/math.h"

#include <bvhlab/triangle.h>
