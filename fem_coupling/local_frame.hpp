#pragma once
/// @file local_frame.hpp
/// Local frame of a flat joint facet: unit normal n (from the minus side into the plus side)
/// and unit tangents t1 (2D, 3D) and t2 (3D), plus the facet measure. Rows of the frame are
/// (n, t1[, t2]); the local jump is Q [[u]] and the global traction is Qᵀ t_local (the
/// rotation of MOOSE's cohesive-zone split: jump → local frame → law → rotate back).

#include <array>
#include <span>

namespace rockjoint::fem
{

/// Orthonormal frame of one facet. Unused entries (3D components in 2D) are zero.
struct LocalFrame
{
  /// rows: normal, tangent 1, tangent 2 (3D only); columns: x, y, z components [-]
  std::array<std::array<double, 3>, 3> axes{};
  /// facet measure: length [m] in 2D, area [m²] in 3D
  double measure = 0.0;
};

/// Frame of the flat facet through `vertices` (gdim vertices of gdim coordinates each, row
/// major: a segment in 2D, a triangle in 3D). The normal is oriented away from
/// `minus_interior_point` (any point inside the minus cell, e.g. its centroid), so it points
/// from the minus into the plus side whatever the vertex order.
/// Throws std::invalid_argument for a degenerate facet (zero measure) or an interior point
/// lying in the facet's plane.
LocalFrame facet_frame(int gdim, std::span<const double> vertices,
                       std::span<const double> minus_interior_point);

} // namespace rockjoint::fem
