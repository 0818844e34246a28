// SPDX-License-Identifier: MIT
#pragma once
/// @file equivalent_continuum.hpp
/// Jointed rock mass as an equivalent continuum (Amadei & Goodman 1981; the ubiquitous-joint
/// model): isotropic rock elasticity plus joint sets of spacing s, each set a family of parallel
/// joints evaluated by joint::joint_response() in the set's local frame, exactly as the discrete
/// joint element evaluates one joint (docs/equivalent-continuum.md).
///
/// Strain split (Voigt, engineering shear):  ε = C_r⁻¹ σ + Σ_k B_k j_k,  B_k = (1/s_k) P(n_k) Q_kᵀ,
/// where j_k is the local jump of set k (normal, t1[, t2]) [m], Q_k its frame (rows n, t1, t2)
/// and P(n) g the Voigt vector of sym(n ⊗ g). Traction continuity on every set:
///   Q_k σ n_k = s_k B_kᵀ σ = t_k(j_k; converged state of set k).
/// The jumps are found by Newton (residual r_k = B_kᵀ σ - t_k/s_k, Jacobian -A with
/// A = Bᵀ D B + diag(T_k / s_k), T_k = ∂t_k/∂j_k); the consistent tangent follows by static
/// condensation: C = D - D B A⁻¹ Bᵀ D.
///
/// Voigt order: 2D plane strain (xx, yy, xy); 3D (xx, yy, zz, yz, xz, xy); shear strains are
/// engineering (γ = 2 ε_ij), stresses tension positive.

#include <rockjoint/joint/joint_behaviour.hpp>
#include <rockjoint/joint/joint_point_state.hpp>

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace rockjoint::continuum
{

/// One joint set: parallel joints of unit normal `normal` at spacing `spacing`.
struct JointSet
{
  std::array<double, 3> normal{0.0, 1.0, 0.0}; ///< unit normal [-] (z ignored in 2D)
  double spacing = 1.0;                        ///< s [m], > 0
  joint::JointBehaviour behaviour;              ///< normal law, shear stiffness, strength
  std::string label = "set";                   ///< named in error messages
};

/// State of one set at one material point: the joint's path-dependent state and the local jump
/// it carries (the jump is the start of the next local Newton solve, not history).
struct SetState
{
  rockjoint::joint::JointPointState joint{}; ///< the joint's path-dependent state (qualified: the
                                            ///< member's own name would hide namespace joint)
  std::array<double, 3> jump{}; ///< (j_n, j_t1[, j_t2]) [m], opening positive
};

/// Stress, consistent tangent and status at one point.
struct PointResponse
{
  std::array<double, 6> stress{};   ///< σ (Voigt, strain_size() entries) [Pa]
  std::array<double, 36> tangent{}; ///< dσ/dε, row major strain_size()² [Pa]
  int iterations = 0;               ///< local Newton iterations
  bool converged = false;           ///< false: a failed trial (the global step must be cut)
};

/// Jointed rock as an equivalent continuum: isotropic rock elasticity (E [Pa], ν [-]) plus
/// smeared joint sets (file comment: the strain split and the local Newton solve).
class EquivalentContinuum
{
public:
  /// `gdim` 2 (plane strain) or 3; rock Young's modulus [Pa] > 0, Poisson ratio in (-1, 0.5).
  /// Throws std::invalid_argument naming the set and parameter for a spacing <= 0, a normal
  /// that is not of unit length (|1 - |n|| > 1e-8) or not in the plane in 2D, or an invalid
  /// joint behaviour.
  EquivalentContinuum(int gdim, double young, double poisson, std::vector<JointSet> sets);

  /// Geometric dimension, 2 or 3.
  int gdim() const { return _gdim; }
  /// Number of Voigt components: 3 (2D) or 6 (3D).
  int strain_size() const { return _gdim == 2 ? 3 : 6; }
  /// Number of joint sets.
  std::size_t num_sets() const { return _sets.size(); }
  /// The joint sets.
  const std::vector<JointSet>& sets() const { return _sets; }
  /// Young's modulus E of the rock [Pa].
  double young() const { return _young; }
  /// Poisson's ratio ν of the rock [-].
  double poisson() const { return _poisson; }

  /// Response at total strain `strain` (strain_size() entries) from the `converged` states
  /// (num_sets() entries); writes the trial states into `trial` (same size). The local solve
  /// starts from the converged jumps; only if it fails there is it retried from the jumps `trial`
  /// holds on entry (the last iterate's), so a solution found from the converged start depends
  /// on (strain, converged) alone.
  /// Throws std::invalid_argument for a non-finite strain or wrong sizes.
  PointResponse evaluate(std::span<const double> strain, std::span<const SetState> converged,
                         std::span<SetState> trial) const;

  /// Strain at which the mass carries the stress `stress` (Voigt) from the virgin state, with
  /// the matching set states written into `states`: each set's jump solves t_k(j_k) = Q_k σ n_k
  /// (used to start a staged analysis from an in-situ stress). Throws std::domain_error if a
  /// set cannot carry its traction (tension on an open joint, shear beyond the strength).
  std::vector<double> strain_at_stress(std::span<const double> stress,
                                       std::span<SetState> states) const;

  /// Isotropic rock stiffness D (row major strain_size()²) [Pa].
  std::vector<double> rock_stiffness() const;

private:
  int _gdim;
  double _young, _poisson;
  std::vector<JointSet> _sets;
  std::vector<std::array<std::array<double, 3>, 3>> _frames; // rows n, t1, t2 per set
};

/// Batch over `n` points (Python/DOLFINx entry): strain (n × strain_size()), converged and
/// trial states (n × num_sets(), point major), stress (n × strain_size()) and tangent
/// (n × strain_size()²) outputs. Returns the number of points whose local solve failed (their
/// stress is NaN). Throws std::invalid_argument naming the point for a non-finite strain.
std::size_t evaluate_points(const EquivalentContinuum& material, std::span<const double> strain,
                            std::span<const SetState> converged, std::span<SetState> trial,
                            std::span<double> stress, std::span<double> tangent);

} // namespace rockjoint::continuum
