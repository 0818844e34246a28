// SPDX-License-Identifier: MIT
#pragma once
/// @file local_frame.hpp
/// Local frame of a flat joint facet: unit normal n (from the minus side into the plus side)
/// and unit tangents t1 (2D, 3D) and t2 (3D), plus the facet measure. Rows of the frame are
/// (n, t1[, t2]); the local jump is Q [[u]] and the global traction is Qᵀ t_local (the
/// rotation of MOOSE's cohesive-zone split: jump → local frame → law → rotate back).

#include <array>
#include <span>

namespace rockjoint::fem_coupling
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
/// from the minus into the plus side whatever the vertex order. Tangents: see set_tangents
/// (`reference` is the joint's reference direction; used in 3D only).
/// Throws std::invalid_argument for a degenerate facet (zero measure) or an interior point
/// lying in the facet's plane.
LocalFrame facet_frame(int gdim, std::span<const double> vertices,
                       std::span<const double> minus_interior_point,
                       const std::array<double, 3>& reference = {1.0, 0.0, 0.0});

/// Set the tangents of `frame` from its normal n (kept):
/// - 2D: t1 = n rotated by -90°, (n_y, -n_x) (a horizontal joint with n = +y has t1 = +x);
///   one rule for every facet, so t1 is continuous along a joint whose normals are.
/// - 3D: t1 = the projection of `reference` on the facet plane, normalised; t2 = n × t1, so
///   (n, t1, t2) is right-handed. Every facet of a joint gets the joint's one reference
///   direction, so t1 is identical on the facets of a planar joint and continuous on a curved
///   one. A facet whose normal lies within 1e-3 rad of `reference` (only possible on a
///   strongly curved joint) uses the coordinate axis least aligned with n instead.
void set_tangents(LocalFrame& frame, int gdim, const std::array<double, 3>& reference);

/// Reference tangent direction of a 3D joint: the strike of its mean plane. The mean normal
/// axis m is the principal eigenvector of the area-weighted normal moment M = Σ A n nᵀ
/// (`normal_moment`, 3×3 row major, summed over every facet of the joint on every rank): for a
/// planar joint m = ±n, and unlike Σ A n it is independent of the facets' minus/plus
/// orientation and does not cancel on a closed joint. m is taken upward (m_z > 0; for a
/// vertical joint the first non-zero of m_x, m_y positive) and the strike is e_z × m,
/// normalised: the right-hand-rule strike, with the dip direction to its right seen from
/// above. A horizontal joint (|(m_x, m_y)| < 1e-10) gets the x axis. Throws
/// std::invalid_argument for a moment that is not finite or is zero.
std::array<double, 3> joint_reference_direction(const std::array<double, 9>& normal_moment);

} // namespace rockjoint::fem_coupling
