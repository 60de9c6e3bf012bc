// The 3D-DDA of Amanatides and Woo (1987) over the grid's cells, in double precision: the cells
// a ray's interval crosses, in the order it crosses them, each with its t-range. No mailboxes
// (as Havran): a primitive referenced by several cells is tested in each of them.
#pragma once

#include "accel/grid/grid_cells.h"

#include <bvhlab/ray.h>

#include <cmath>

namespace bvhlab::grid {

// Calls visit(cellIndex, tExit) for each cell from the one holding the ray's entry point, in
// order, while visit returns true and the interval [tmin, tmax] of the ray reaches the cell.
// tExit is the t at which the ray leaves the cell (tmax in the last one). Returns false when
// the ray's interval misses the grid's box.
template <typename Visit>
bool walkCells(const GridCells& g, const Ray& ray, Visit&& visit) {
    double t0 = 0.0, t1 = 0.0;
    if (!clipToBox(ray, g.lower, g.upper, t0, t1)) return false;
    const DVec3 org(ray.org), dir(ray.dir);
    DVec3 inv;
    for (int a = 0; a < 3; ++a) inv[a] = dir[a] == 0.0 ? 0.0 : 1.0 / dir[a];

    int cell[3], step[3], end[3];
    double next[3];
    for (int a = 0; a < 3; ++a) {
        const double p = org[a] + t0 * dir[a];
        double c = std::floor((p - g.lower[a]) * g.inverseCellSize[a]);
        if (!(c >= 0.0)) c = 0.0;  // rounding at the box's face, or NaN
        cell[a] = int(std::min(c, double(g.res[a] - 1)));
        if (dir[a] > 0.0) {
            step[a] = 1;
            end[a] = g.res[a];
        } else if (dir[a] < 0.0) {
            step[a] = -1;
            end[a] = -1;
        } else {
            step[a] = 0;
            end[a] = 0;
        }
    }
    auto boundary = [&](int a) {  // t of the face through which the ray leaves cell[a] on axis a
        if (step[a] == 0) return double(kInfinity);
        const int face = cell[a] + (step[a] > 0 ? 1 : 0);
        return (g.lower[a] + face * g.cellSize[a] - org[a]) * inv[a];
    };
    for (int a = 0; a < 3; ++a) next[a] = boundary(a);

    for (;;) {
        const int a = next[0] <= next[1] ? (next[0] <= next[2] ? 0 : 2) : (next[1] <= next[2] ? 1 : 2);
        const double exit = std::min(next[a], t1);
        if (!visit(g.cellIndex(cell[0], cell[1], cell[2]), exit)) return true;
        if (!(next[a] < t1)) return true;  // the interval ends in this cell
        cell[a] += step[a];
        if (cell[a] == end[a] || step[a] == 0) return true;
        next[a] = boundary(a);
    }
}

}  // namespace bvhlab::grid
