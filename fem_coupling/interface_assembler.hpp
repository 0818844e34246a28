#pragma once
/// @file interface_assembler.hpp
/// Zero-thickness (Goodman-type) joint elements between matched facet pairs.
///
/// The boundary is plain arrays: node (block) indices into a process-local, ghosted
/// displacement array with block size gdim (DOLFINx's local vector layout, but nothing here
/// depends on DOLFINx), the minus-facet vertex coordinates and a point inside each minus
/// cell. Per pair and quadrature point: jump [[u]] = u_plus - u_minus → local frame →
/// JointBehaviour → rotate back → ±N assembly (MOOSE cohesive-zone split).
///
/// Residual convention (internal minus external force): the joint adds
///   R_plus,a += w N_a T,  R_minus,a -= w N_a T,  T = Qᵀ t_local,
/// and the consistent Jacobian ∂R/∂u with D = Qᵀ (∂t/∂j) Q.

#include "facet_quadrature.hpp"
#include "joint_behaviour.hpp"
#include "local_frame.hpp"

#include <cmath>
#include <cstdint>
#include <map>
#include <span>
#include <vector>

namespace rockjoint::fem
{

class InterfaceAssembler
{
public:
  /// @param gdim geometric dimension (2 or 3) = displacement block size
  /// @param degree Lagrange degree of the displacement (1, or 2 with the nodal rule)
  /// @param rule quadrature rule on the facets
  /// @param minus_nodes (num_pairs, num_facet_nodes) local node indices of the minus facets
  /// @param plus_nodes same for the plus facets, permuted so that node a of the plus facet
  ///        coincides with node a of the minus facet
  /// @param vertex_coordinates (num_pairs, gdim, gdim) minus-facet vertex coordinates [m]
  /// @param minus_interior_points (num_pairs, gdim) a point inside each minus cell [m]
  /// @param joint_tags (num_pairs) joint tag of every pair
  /// @param behaviours behaviour per joint tag; every tag in `joint_tags` must have one
  InterfaceAssembler(int gdim, int degree, QuadratureRule rule,
                     std::span<const std::int32_t> minus_nodes,
                     std::span<const std::int32_t> plus_nodes,
                     std::span<const double> vertex_coordinates,
                     std::span<const double> minus_interior_points,
                     std::span<const std::int32_t> joint_tags,
                     std::map<std::int32_t, JointBehaviour> behaviours);

  int gdim() const { return _gdim; }
  std::int32_t num_pairs() const { return static_cast<std::int32_t>(_tags.size()); }
  int num_facet_nodes() const { return _quadrature.num_nodes; }
  /// Quadrature points per pair.
  int num_points_per_pair() const { return _quadrature.num_points(); }
  /// Rows/columns of one pair matrix: 2 × facet nodes × gdim (minus nodes first).
  int pair_size() const { return 2 * _quadrature.num_nodes * _gdim; }

  /// Unrolled local dof indices of pair p (minus nodes, then plus nodes; node-major).
  void pair_dofs(std::int32_t p, std::span<std::int32_t> dofs) const;
  /// Entries a local (ghosted, unrolled) array must have at least: (largest node index + 1)·gdim.
  std::size_t minimum_local_size() const { return _minimum_local_size; }
  /// Throw std::invalid_argument naming `who`, `array` and both sizes unless `size` >=
  /// minimum_local_size(). Every public method that reads or writes a local array calls it once
  /// (API boundary; nothing is checked inside the loops).
  void check_local_array(const char* who, const char* array, std::size_t size) const;

  /// Add the interface residual at displacement `u` into `residual` (both local, unrolled,
  /// ghosts included; call before the reverse ghost update) and refresh the point state.
  /// Returns false if a traction is not finite (closure past the law's maximum): a failed
  /// trial, not an exception.
  bool assemble_residual(std::span<const double> u, std::span<double> residual);

  /// Dense consistent Jacobian of pair p at `u`, pair_size()² row major.
  void pair_matrix(std::int32_t p, std::span<const double> u, std::span<double> matrix) const;

  /// Largest Δ / Δ_max over all points at `u` (Δ_max = the law's maximum closure; laws
  /// without one contribute 0). The Newton step limiter keeps it below a safety fraction.
  double maximum_closure_ratio(std::span<const double> u) const;

  /// Largest α in (0, 1] such that every point of a law with a finite maximum closure Δ_max
  /// keeps Δ(u + α du) <= Δ(u) + fraction (Δ_max - Δ(u)) (fraction-to-the-boundary rule):
  /// the closure-limiting Newton step for stiffening laws. Δ is linear in α, so this is exact.
  double admissible_step_length(std::span<const double> u, std::span<const double> du,
                                double fraction) const;

  /// Refresh the point state at `u` without assembling.
  void update_state(std::span<const double> u);

  // ---- point state (num_pairs × num_points_per_pair points, pair-major) -------------------
  const std::vector<double>& closure() const { return _closure; }             ///< Δ [m]
  const std::vector<double>& normal_stress() const { return _normal_stress; } ///< [Pa], compression +
  /// (points, gdim-1) shear traction components along t1[, t2] [Pa]
  const std::vector<double>& shear_traction() const { return _shear_traction; }
  const std::vector<std::int32_t>& status() const { return _status; } ///< constitutive::Status
  /// (points, gdim) quadrature point coordinates [m]
  const std::vector<double>& point_coordinates() const { return _point_coordinates; }
  /// (pairs, gdim) unit normals, minus → plus
  std::vector<double> normals() const;
  /// Joint tag of every point.
  std::vector<std::int32_t> point_tags() const;
  /// Facet measure of every pair [m] or [m²].
  std::vector<double> measures() const;

private:
  /// Local jump (gdim components, frame axes) at point q of pair p.
  std::array<double, 3> local_jump(std::int32_t p, int q, std::span<const double> u) const;
  const JointBehaviour& behaviour(std::int32_t p) const { return *_pair_behaviour[p]; }
  /// Call f(p, q, Δ_max) at every point of the pairs whose law has a finite maximum closure
  /// Δ_max (the points the closure limit of Newton's step concerns).
  template <typename F>
  void for_each_limited_point(F&& f) const
  {
    const int nq = _quadrature.num_points();
    for (std::int32_t p = 0; p < num_pairs(); ++p)
    {
      const double limit = behaviour(p).law->maximum_closure();
      if (std::isfinite(limit))
        for (int q = 0; q < nq; ++q)
          f(p, q, limit);
    }
  }

  int _gdim;
  std::size_t _minimum_local_size = 0;
  FacetQuadrature _quadrature;
  std::vector<std::int32_t> _minus_nodes, _plus_nodes, _tags;
  std::vector<LocalFrame> _frames;
  std::map<std::int32_t, JointBehaviour> _behaviours;
  std::vector<const JointBehaviour*> _pair_behaviour;

  std::vector<double> _closure, _normal_stress, _shear_traction, _point_coordinates;
  std::vector<std::int32_t> _status;
};

} // namespace rockjoint::fem
