// SPDX-License-Identifier: MIT
#pragma once
/// @file plane.hpp
/// Least-squares mean plane z = a + b x + c y of the valid points of one or more surfaces.

#include "surface.hpp"

#include <vector>

namespace rockjoint::topography
{

/// z = offset + slope_x·x + slope_y·y, x = j·spacing_x, y = i·spacing_y [m].
struct Plane
{
  double offset = 0.0;  ///< [m]
  double slope_x = 0.0; ///< [-]
  double slope_y = 0.0; ///< [-]
  /// z [m] at (x, y) [m].
  double at(double x, double y) const { return offset + slope_x * x + slope_y * y; }
};

/// Least-squares plane through the valid points of all `grids` taken together (one set of
/// normal equations), on a common lattice with spacings dx, dy [m]. Throws
/// std::invalid_argument if fewer than 3 non-collinear valid points exist.
Plane fit_plane(const std::vector<const HeightGrid*>& grids, double spacing_x,
                double spacing_y);

/// z - plane at every point (NaN stays NaN).
void subtract_plane(HeightGrid& heights, const Plane& plane, double spacing_x,
                    double spacing_y);

} // namespace rockjoint::topography
