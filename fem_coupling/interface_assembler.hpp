// SPDX-License-Identifier: MIT
#pragma once
/// @file interface_assembler.hpp
/// Zero-thickness (Goodman-type) joint elements between matched facet pairs.
///
/// The boundary is plain arrays: explicit unrolled dof indices of every pair into a
/// process-local, ghosted displacement array (the caller's dofmap decides the layout; nothing
/// here depends on DOLFINx), the minus-facet vertex coordinates and a point inside each minus
/// cell. Per pair and quadrature point: jump [[u]] = u_plus - u_minus → local frame Q → local
/// jump j = j0 + Q [[u]] (j0: initial jump, the in-situ state) → joint_response (law + point
/// state) → rotate back → ±N assembly (MOOSE cohesive-zone split).
///
/// Residual convention (internal minus external force): the joint adds
///   R_plus,a += w N_a T,  R_minus,a -= w N_a T,  T = Qᵀ t_local,
/// and the consistent Jacobian ∂R/∂u with D = Qᵀ (∂t/∂j) Q.
///
/// Frames: n per pair (minus → plus), t1 from the joint's reference direction (one per joint
/// tag, see set_tangents / joint_reference_direction in local_frame.hpp), t2 = n × t1.
///
/// Point state: a converged and a trial joint::JointPointState per point; every evaluation computes
/// the trial state from the converged one; commit_state() / revert_state() move between them.

#include "facet_quadrature.hpp"
#include <rockjoint/joint/joint_behaviour.hpp>
#include <rockjoint/joint/joint_point_state.hpp>
#include "local_frame.hpp"

#include <cmath>
#include <cstdint>
#include <map>
#include <span>
#include <vector>

namespace rockjoint::fem_coupling
{

class InterfaceAssembler
{
public:
  /// @param gdim geometric dimension (2 or 3) = displacement block size
  /// @param degree Lagrange degree of the displacement (1, or 2 with the nodal rule)
  /// @param rule quadrature rule on the facets
  /// @param pair_dofs (num_pairs, 2 · num_facet_nodes · gdim) unrolled local dof indices:
  ///        minus-facet nodes then plus-facet nodes, node-major, component-minor (node a,
  ///        component c at a·gdim + c); the plus facet permuted so that its node a coincides
  ///        with node a of the minus facet
  /// @param vertex_coordinates (num_pairs, gdim, gdim) minus-facet vertex coordinates [m]
  /// @param minus_interior_points (num_pairs, gdim) a point inside each minus cell [m]
  /// @param joint_tags (num_pairs) joint tag of every pair
  /// @param behaviours behaviour per joint tag; every tag in `joint_tags` must have one
  /// The tangents start from each joint's reference direction computed from this process's
  /// pairs (normal_moments()); in parallel call set_reference_directions with the all-rank one.
  InterfaceAssembler(int gdim, int degree, QuadratureRule rule,
                     std::span<const std::int32_t> pair_dofs,
                     std::span<const double> vertex_coordinates,
                     std::span<const double> minus_interior_points,
                     std::span<const std::int32_t> joint_tags,
                     std::map<std::int32_t, joint::JointBehaviour> behaviours);

  int gdim() const { return _gdim; }
  std::int32_t num_pairs() const { return static_cast<std::int32_t>(_tags.size()); }
  int num_facet_nodes() const { return _quadrature.num_nodes; }
  /// Quadrature points per pair.
  int num_points_per_pair() const { return _quadrature.num_points(); }
  /// Rows/columns of one pair matrix: 2 × facet nodes × gdim (minus nodes first).
  int pair_size() const { return 2 * _quadrature.num_nodes * _gdim; }

  /// Unrolled local dof indices of pair p (minus nodes, then plus nodes; node-major), as given
  /// to the constructor.
  void pair_dofs(std::int32_t p, std::span<std::int32_t> dofs) const;
  /// Entries a local (ghosted, unrolled) array must have at least: largest pair dof + 1.
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

  // ---- frames and initial jump ----------------------------------------------------------
  /// Area-weighted normal moment Σ A n nᵀ (3×3 row major) of this process's pairs per joint
  /// tag (3D; zero z entries in 2D). Sum over ranks, then joint_reference_direction.
  std::map<std::int32_t, std::array<double, 9>> normal_moments() const;
  /// Rebuild t1, t2 of every pair from its joint's reference direction (3D; 2D frames do not
  /// depend on it). Tags not in the map keep their tangents. Invalidates the cached responses.
  void set_reference_directions(const std::map<std::int32_t, std::array<double, 3>>& directions);
  /// Frame rows (n, t1[, t2]) of pair p, global components.
  const LocalFrame& frame(std::int32_t p) const { return _frames.at(p); }
  /// Initial local jump j0 (num_points, gdim), components (n, t1[, t2]) [m]; the law sees
  /// j = j0 + Q [[u]] (a joint pre-closed to Δ0 has j0_n = -Δ0). Throws std::invalid_argument
  /// for a wrong size or a non-finite entry.
  void set_initial_jump(std::span<const double> initial_jump);
  const std::vector<double>& initial_jump() const { return _initial_jump; }
  /// Fluid pressure p [Pa] in the joint at every point (num_points; 0: dry, the default): the
  /// law and the strength see σ'_n = σ_n - α p and the water pushes the walls apart with α p
  /// (joint/joint_behaviour.hpp). Throws std::invalid_argument for a wrong size or a
  /// non-finite entry. Invalidates the cached responses.
  void set_pore_pressure(std::span<const double> pressure);
  const std::vector<double>& pore_pressure() const { return _pore_pressure; } ///< p [Pa] per point

  // ---- path-dependent point state ---------------------------------------------------------
  /// Accept the trial state (after a converged load step): converged ← trial.
  void commit_state();
  /// Discard the trial state (after a failed step): trial ← converged.
  void revert_state();
  /// Back to the virgin state (no slip, no dilation, bonds intact) at every point: a new
  /// analysis from zero displacement.
  void reset_state();
  /// Set the largest closure reached Δ_m [m] of every point (num_points, pair-major), converged
  /// and trial: a staggered coupling puts back the Δ_m of its last accepted state before each
  /// iterate, so that only the accepted iterate adds to it (fem.water.coupled). Throws
  /// std::invalid_argument for a wrong size or a non-finite entry. Invalidates the cached responses.
  void set_maximum_closure(std::span<const double> maximum_closure);
  /// Point states (num_points), pair-major.
  const std::vector<joint::JointPointState>& converged_state() const { return _converged; }
  const std::vector<joint::JointPointState>& trial_state() const { return _trial; }
  /// Law evaluations (joint_response calls) since construction: one per point per residual,
  /// none more for the Jacobian at the u of the last residual.
  std::size_t num_law_evaluations() const { return _num_law_evaluations; }

  // ---- point state (num_pairs × num_points_per_pair points, pair-major) -------------------
  const std::vector<double>& closure() const { return _closure; }             ///< Δ [m]
  const std::vector<double>& normal_stress() const { return _normal_stress; } ///< [Pa], compression +
  /// (points, gdim-1) shear traction components along t1[, t2] [Pa]
  const std::vector<double>& shear_traction() const { return _shear_traction; }
  const std::vector<std::int32_t>& status() const { return _status; } ///< constitutive::Status
  /// joint::ShearState (stick 0, slip 1, open 2) of every point at the last residual.
  const std::vector<std::int32_t>& shear_state() const { return _shear_state; }
  /// (points, gdim) quadrature point coordinates [m]
  const std::vector<double>& point_coordinates() const { return _point_coordinates; }
  /// (pairs, gdim) unit normals, minus → plus
  std::vector<double> normals() const;
  /// Joint tag of every point.
  std::vector<std::int32_t> point_tags() const;
  /// Facet measure of every pair [m] or [m²].
  std::vector<double> measures() const;

private:
  /// Local jump Q [[u]] (gdim components, frame axes) at point q of pair p, with the initial
  /// jump j0 added if `with_initial` (false for an increment du).
  std::array<double, 3> local_jump(std::int32_t p, int q, std::span<const double> u,
                                   bool with_initial = true) const;
  std::size_t point_index(std::int32_t p, int q) const
  {
    return static_cast<std::size_t>(p) * _quadrature.num_points() + q;
  }
  const joint::JointBehaviour& behaviour(std::int32_t p) const { return *_pair_behaviour[p]; }
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
  std::vector<std::int32_t> _pair_dofs, _tags;
  std::vector<LocalFrame> _frames;
  std::map<std::int32_t, joint::JointBehaviour> _behaviours;
  std::vector<const joint::JointBehaviour*> _pair_behaviour;

  std::vector<double> _closure, _normal_stress, _shear_traction, _point_coordinates;
  std::vector<std::int32_t> _status, _shear_state;
  std::vector<double> _initial_jump;                ///< (points, gdim) j0 [m]
  std::vector<double> _pore_pressure;               ///< (points) p [Pa]
  std::vector<joint::JointPointState> _converged, _trial;  ///< per point
  // Responses and jumps of the last residual (one law evaluation per point per iteration).
  std::vector<joint::LocalResponse> _cached_response;
  std::vector<std::array<double, 3>> _cached_jump;
  bool _cache_valid = false;
  mutable std::size_t _num_law_evaluations = 0;
};

} // namespace rockjoint::fem_coupling
