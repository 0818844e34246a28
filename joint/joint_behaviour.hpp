// SPDX-License-Identifier: MIT
#pragma once
/// @file joint_behaviour.hpp
/// Constitutive behaviour of a joint in its local frame: the closure law for the normal
/// traction, a shear stiffness for the tangential traction, an optional residual stiffness
/// and an optional shear strength (joint_strength.hpp). This is the "law" piece of the
/// cohesive-zone split; it knows nothing of meshes, frames or assembly. The path-dependent
/// response (slip, dilation) is joint_response() in joint_slip.hpp.
///
/// Local jump j = ([[u]]·n, [[u]]·t1[, [[u]]·t2]) [m], [[u]] = u_plus - u_minus, n from minus
/// into plus. With the plastic slip s and dilation d of the point state, the elastic closure is
/// Δ_e = -(j_n - d) (compression closes, theory §0). Local traction on the plus wall, tension +:
///   t_n = -(σ(Δ_e) + k_r Δ_e),       σ from the ClosureLaw (compression positive),
///   t_s = k_s (j_s - s)              joint in contact (Δ_e >= 0) or bonded in tension,
///         k_s = constant, or α (k(Δ_e) + k_r);
///   t_s = (k_open + k_r) (j_s - s)   joint open: no physical shear traction, only the
///                                    residual spring (k_open: a law's own opening branch);
///   t_s = k_r (j_s - s)              in contact where the strength is below that spring
///                                    (k_r |j_s - s| >= τ_y, near opening; slip frozen, no
///                                    dilation active): the residual floor, which keeps t_s
///                                    continuous at opening (joint_slip.cpp).
/// The residual stiffness k_r [Pa/m] is a linear spring in parallel with the law, in
/// compression and in tension; an open joint is an isotropic spring of that residual
/// stiffness in shear as well, so a block held only by an open joint is not a free body in
/// any direction (default 0: such a model is singular and the solver reports it). The
/// residual spring is a regularisation, not a strength: the tension cut-off does not act on
/// it. A law's own opening branch (TabulatedLaw: σ = k_res Δ for Δ <= 0, via
/// ClosureLaw::evaluate_open) acts on top of k_r.
///
/// Water in the joint (docs/flow.md, "Water that pushes back"): with a fluid pressure p at the
/// point, the law and the strength see the effective normal stress σ'_n = σ_n - α p (α the
/// effective-stress coefficient, 1 by default), and the water pushes both walls apart with α p,
/// as the contact does with σ' (the total normal stress is σ_n = σ' + α p):
///   t_n = -(σ(Δ_e) + k_r Δ_e + α p),
/// the tangent unchanged (p is given). The closure, the strength c + σ' tan φ, the tension
/// cut-off and a law's history all follow σ'; a joint whose p reaches the total normal stress
/// opens (hydraulic jacking), held by k_r only.

#include "joint_strength.hpp"

#include <rockjoint/constitutive/closure_law.hpp>

#include <array>
#include <memory>
#include <string>

namespace rockjoint::joint
{

/// How the shear stiffness of a joint in contact is defined.
enum class ShearModel : int
{
  constant = 0,     ///< k_s [Pa/m] fixed while in contact (Goodman 1968)
  proportional = 1, ///< k_s = α (k_n(Δ) + k_r): follows the normal stiffness
};

/// Everything needed to evaluate one joint family (one joint tag).
struct JointBehaviour
{
  /// Normal-closure law σ(Δ). A law with history (has_history(): NormalHysteresis,
  /// docs/hysteresis.md) unloads and reloads on branches set by the largest closure reached,
  /// kept per point (JointPointState::maximum_closure); its in-situ pre-closure follows the
  /// virgin curve.
  std::shared_ptr<const constitutive::ClosureLaw> law;
  ShearModel shear_model = ShearModel::constant; ///< how k_s is set
  double shear_stiffness = 0.0;       ///< k_s [Pa/m] (ShearModel::constant), >= 0
  double shear_stiffness_ratio = 0.0; ///< α [-] (ShearModel::proportional), >= 0
  double residual_stiffness = 0.0;    ///< k_r [Pa/m], >= 0
  JointStrength strength{};           ///< shear strength (default none: elastic joint)
  /// α [-] of σ'_n = σ_n - α p, in [0, 1] (1: Terzaghi's effective stress, the default)
  double effective_stress_coefficient = 1.0;
};

/// Throw std::invalid_argument (naming the joint `label`, the parameter, value and range)
/// if `behaviour` has no law, a negative/non-finite stiffness or invalid strength parameters.
void validate(const JointBehaviour& behaviour, const std::string& label);

/// Closure Δ >= 0 [m] at which the joint carries the total normal stress `normal_stress` [Pa]
/// (compression positive): σ(Δ) + k_r Δ = σ_t, the law's inverse when k_r = 0. Used for the
/// pre-closure of a joint by an in-situ stress. The total stress increases in Δ and
/// k_r Δ >= 0, so the root lies in [0, Δ_law] with Δ_law = law.closure_at_stress(σ_t); it is
/// found there by root_finding::find_root (safeguarded Newton). Throws std::invalid_argument
/// for a NaN, infinite or negative target and std::domain_error for one the law alone cannot
/// carry (beyond its admissible range; its own message names the limit), both naming the
/// target. Such a target is refused even if k_r Δ would make up the difference: the law would
/// have to be evaluated near or past its validity limit.
double closure_at_normal_stress(const JointBehaviour& behaviour, double normal_stress);

/// Whether a point sticks, slips or is open (for counting in the FE layer).
enum class ShearState : int
{
  stick = 0, ///< in contact (or bonded), inside the strength: elastic shear
  slip = 1,  ///< on the strength (|τ| = τ_y to round-off): sliding
  open = 2,  ///< open: only the residual spring acts
};

/// Local traction, its consistent tangent and the state at one point.
struct LocalResponse
{
  std::array<double, 3> traction{};                ///< (t_n, t_s1[, t_s2]) [Pa], tension +
  std::array<std::array<double, 3>, 3> tangent{}; ///< ∂t/∂j [Pa/m]
  double closure = 0.0;                            ///< Δ [m]
  double normal_stress = 0.0;                      ///< σ(Δ_e) + k_r Δ_e [Pa], compression +
  double normal_stiffness = 0.0;                   ///< k(Δ_e) + k_r [Pa/m]
  constitutive::Status status = constitutive::Status::open; ///< status of the closure law at Δ_e
  ShearState shear_state = ShearState::open; ///< stick, slip or open
};

/// Normal part of the response at elastic closure Δ_e.
struct NormalResponse
{
  double stress = 0.0;                 ///< σ(Δ_e) + k_r Δ_e [Pa], compression +
  double stiffness = 0.0;              ///< dσ/dΔ_e [Pa/m]
  constitutive::Status status = constitutive::Status::open; ///< status of the closure law at Δ_e
  bool in_contact = false;             ///< Δ_e >= 0, or bonded in tension: carries shear
  bool bond_fails = false;             ///< the tension exceeded the tensile strength here
  double permanent_closure = 0.0;      ///< Δ_p of the hysteretic branch in force (0: virgin) [m]
};

/// Normal response at elastic closure Δ_e; `bonded`: the tensile bond is still intact;
/// `maximum_closure`: the converged Δ_m of a law with history (ignored without). At
/// Δ_e = 0 exactly the tangent is the contact-side one, k(0+) (semismooth Newton from an
/// untouched joint). A bonded joint (tensile strength T > 0) in tension is a spring of that
/// contact-side stiffness until its tension reaches T; past it the bond fails and the joint
/// is open.
NormalResponse normal_response(const JointBehaviour& behaviour, double elastic_closure,
                               bool bonded, double maximum_closure = 0.0);

/// Shear stiffness k_s [Pa/m] and dk_s/dΔ_e [Pa/m²] for a normal response at Δ_e (on the
/// unloading branch of a hysteretic law the proportional model follows the virgin law's k,
/// which is continuous at Δ_m where the branch's k jumps).
struct ShearStiffness
{
  double value = 0.0; ///< k_s [Pa/m]
  double closure_derivative = 0.0; ///< dk_s/dΔ_e [Pa/m²]
};
/// k_s and dk_s/dΔ_e of `behaviour` at elastic closure Δ_e [m] with normal response `normal`.
ShearStiffness shear_stiffness(const JointBehaviour& behaviour, const NormalResponse& normal,
                               double elastic_closure);

} // namespace rockjoint::joint
