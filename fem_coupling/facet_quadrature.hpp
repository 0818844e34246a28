// SPDX-License-Identifier: MIT
#pragma once
/// @file facet_quadrature.hpp
/// Quadrature rules on a joint facet for Lagrange displacement fields.
///
/// Nodal (vertex / Lobatto-type) integration is the default: each quadrature point sits on a
/// facet node, so the joint acts as independent node-to-node springs and very stiff joints
/// give smooth tractions (Goodman oscillation with Gauss points: docs/fem.md,
/// pitfall 8). Gauss integration is offered for comparison.

#include <vector>

namespace rockjoint::fem_coupling
{

/// Where the interface law is sampled.
enum class QuadratureRule : int
{
  nodal = 0, ///< points on the facet nodes, weights = facet measure share of each node
  gauss = 1, ///< Gauss points inside the facet (P1 only)
};

/// Quadrature on one facet: point q has weight weights[q] × facet measure and the facet
/// node shape functions take the values shape[q * num_nodes + a] there.
struct FacetQuadrature
{
  int num_nodes = 0;           ///< facet nodes (P1: gdim; P2: 3 in 2D, 6 in 3D)
  std::vector<double> weights; ///< fractions of the facet measure, sum 1 [-]
  std::vector<double> shape;   ///< (num_points, num_nodes) row major [-]
  /// (num_points, gdim) barycentric coordinates of the points w.r.t. the facet vertices [-]
  std::vector<double> barycentric;
  int num_points() const { return static_cast<int>(weights.size()); }
};

/// The rule for a facet of a degree-`degree` Lagrange field in `gdim` dimensions.
/// Facet node order: vertices first, then edge midpoints (P2; on a triangle the midpoint of
/// edge (v1, v2), then (v0, v2), then (v0, v1), as in basix).
/// Nodal P1: weights 1/gdim (trapezoid / vertex rule). Nodal P2: Simpson (1/6, 1/6, 2/3) on a
/// segment; on a triangle (0, 0, 0, 1/3, 1/3, 1/3), the positive vertex-free rule exact for
/// quadratics. Gauss P1: 2 points on a segment, 3 interior points on a triangle (both exact
/// for the quadratic integrand u·v). Throws std::invalid_argument for other combinations.
FacetQuadrature make_facet_quadrature(QuadratureRule rule, int gdim, int degree);

} // namespace rockjoint::fem_coupling
