#pragma once
/// @file joint_behaviour.hpp
/// Constitutive behaviour of a joint in its local frame: the closure law for the normal
/// traction, a shear stiffness for the tangential traction, and an optional residual
/// stiffness. This is the "law" piece of the cohesive-zone split; it knows nothing of
/// meshes, frames or assembly.
///
/// Local jump j = ([[u]]·n, [[u]]·t1[, [[u]]·t2]) [m], [[u]] = u_plus - u_minus, n from minus
/// into plus. Closure Δ = -j_n (compression closes, theory §0). Local traction on the plus
/// wall, tension positive:
///   t_n = -(σ(Δ) + k_r Δ),                 σ from the ClosureLaw (compression positive),
///   t_s = k_s j_s,                         k_s constant, or k_s = α (k(Δ) + k_r).
/// The residual stiffness k_r [Pa/m] is a linear spring in parallel with the law, in
/// compression and in tension: it keeps a block held only by an open joint from being a
/// free body (default 0: such a model is singular and the solver reports it). A law's own
/// opening branch (TabulatedLaw: σ = k_res Δ for Δ <= 0, via ClosureLaw::evaluate_open) acts
/// on top of k_r.

#include <rockjoint/constitutive/closure_law.hpp>

#include <array>
#include <memory>

namespace rockjoint::fem
{

/// How the shear stiffness is defined.
enum class ShearModel : int
{
  constant = 0,     ///< k_s [Pa/m] fixed; acts whether the joint is open or closed (Goodman 1968)
  proportional = 1, ///< k_s = α k_n(Δ): follows the normal stiffness, zero when open
};

/// Everything needed to evaluate one joint family (one joint tag).
struct JointBehaviour
{
  std::shared_ptr<const constitutive::ClosureLaw> law; ///< normal-closure law σ(Δ)
  ShearModel shear_model = ShearModel::constant;
  double shear_stiffness = 0.0;       ///< k_s [Pa/m] (ShearModel::constant), >= 0
  double shear_stiffness_ratio = 0.0; ///< α [-] (ShearModel::proportional), >= 0
  double residual_stiffness = 0.0;    ///< k_r [Pa/m], >= 0
};

/// Throw std::invalid_argument (naming the joint `label`, the parameter, value and range)
/// if `behaviour` has no law or a negative/non-finite stiffness.
void validate(const JointBehaviour& behaviour, const std::string& label);

/// Local traction, its consistent tangent and the state at one point.
struct LocalResponse
{
  std::array<double, 3> traction{};                ///< (t_n, t_s1[, t_s2]) [Pa], tension +
  std::array<std::array<double, 3>, 3> tangent{}; ///< ∂t/∂j [Pa/m]
  double closure = 0.0;                            ///< Δ [m]
  double normal_stress = 0.0;                      ///< σ(Δ) + k_r Δ [Pa], compression +
  double normal_stiffness = 0.0;                   ///< k(Δ) + k_r [Pa/m]
  constitutive::Status status = constitutive::Status::open;
};

/// Response at local jump `jump` (gdim components). At Δ = 0 exactly the tangent is the
/// contact-side one, k(0+) (semismooth Newton from an untouched joint). Never throws; past the law's maximum
/// closure the traction is infinite (status beyond_maximum_closure), which the Newton
/// solver treats as a failed trial.
LocalResponse local_response(const JointBehaviour& behaviour, int gdim,
                             const std::array<double, 3>& jump);

} // namespace rockjoint::fem
