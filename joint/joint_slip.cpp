// SPDX-License-Identifier: MIT
#include "joint_slip.hpp"

#include <rockjoint/constitutive/root_finding.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockjoint::joint
{

namespace
{
/// Everything at one trial slip increment Δλ of the return mapping.
struct SlipPoint
{
  double closure;           ///< elastic closure Δ_e = -j_n + d_n + opening(Δλ) [m]
  DilationIncrement dilation;
  NormalResponse normal;
  ShearStiffness shear;
  ShearStrength strength;
};

SlipPoint slip_point(const JointBehaviour& b, double trial_closure, const JointPointState& converged,
                     double increment, bool bonded)
{
  SlipPoint s;
  s.dilation = dilation_increment(b.strength, converged.accumulated_slip, increment);
  s.closure = trial_closure + s.dilation.opening;
  s.normal = normal_response(b, s.closure, bonded, converged.maximum_closure);
  s.shear = shear_stiffness(b, s.normal, s.closure);
  s.strength = shear_strength(b.strength, s.normal.stress, bonded);
  return s;
}

void set_normal(LocalResponse& r, const NormalResponse& n)
{
  r.normal_stress = n.stress;
  r.normal_stiffness = n.stiffness;
  r.status = n.status;
  // t_n = -σ(Δ_e), Δ_e = -j_n + d  ⇒  ∂t_n/∂j_n = +k (elastic; the slip branch corrects it).
  r.traction[0] = -n.stress;
  r.tangent[0][0] = n.stiffness;
}
} // namespace

namespace
{
LocalResponse effective_response(const JointBehaviour& b, int gdim, const std::array<double, 3>& jump,
                                 const JointPointState& converged, JointPointState& trial);
} // namespace

LocalResponse joint_response(const JointBehaviour& b, int gdim, const std::array<double, 3>& jump,
                             const JointPointState& converged, JointPointState& trial,
                             double pore_pressure)
{
  // The law, the strength and the history see σ'_n; the water pushes the walls apart with α p as
  // the contact does with σ': the total normal stress is σ' + α p (t_n = -σ_n, tension
  // positive), a given load: the tangent is the effective one.
  LocalResponse r = effective_response(b, gdim, jump, converged, trial);
  r.traction[0] -= b.effective_stress_coefficient * pore_pressure;
  return r;
}

namespace
{
LocalResponse effective_response(const JointBehaviour& b, int gdim, const std::array<double, 3>& jump,
                                 const JointPointState& converged, JointPointState& trial)
{
  trial = converged;
  LocalResponse r;
  r.closure = -jump[0];
  const int shear_components = gdim - 1;

  // Elastic predictor at the converged slip and dilation.
  bool bonded = !converged.bond_broken;
  const double trial_closure = r.closure + converged.dilation;
  NormalResponse normal = normal_response(b, trial_closure, bonded, converged.maximum_closure);
  // Δ_m follows the elastic closure, for every law (the slip branch below updates it again):
  // the law's history if it has one, the transmissivity's in any case (joint_point_state.hpp).
  trial.maximum_closure = std::max(converged.maximum_closure, trial_closure);
  if (normal.bond_fails)
  {
    trial.bond_broken = true; // tension cut-off: the bond (c, T) is lost for good
    bonded = false;
  }
  set_normal(r, normal);
  const ShearStiffness ks = shear_stiffness(b, normal, trial_closure);
  std::array<double, 2> elastic_slip{};
  double e = 0.0;
  for (int i = 0; i < shear_components; ++i)
  {
    elastic_slip[i] = jump[i + 1] - converged.slip[i];
    e += elastic_slip[i] * elastic_slip[i];
  }
  e = std::sqrt(e);

  const ShearStrength strength = shear_strength(b.strength, normal.stress, bonded);
  const double yield = ks.value * e - strength.strength; // f(τ_tr)
  // Residual floor: where the strength has fallen below what the residual spring alone would
  // carry (k_r e >= τ_y, σ_n within k_r e / tanφ of zero), the joint carries that spring,
  // k_r (j_s - s) with its slip frozen, as an open joint does. The shear traction is then
  // continuous at opening (it would otherwise jump from τ_y → 0 to k_r e there) and across
  // the floor (|τ| = τ_y = k_r e on both sides, along the same trial direction). Only where
  // slip does not dilate (ψ = 0 or past the dilation limit): a dilating return mapping would
  // open the joint by tanψ Δλ on one side of the floor and not on the other. Newton's
  // iterations cycled at the jump at opening wherever a smeared set opens and closes
  // (docs/equivalent-continuum.md, "Robustness").
  if (normal.in_contact && yield > 0.0 && b.residual_stiffness > 0.0
      && b.residual_stiffness * e >= strength.strength
      && dilation_increment(b.strength, converged.accumulated_slip, 0.0).rate == 0.0)
  {
    r.shear_state = ShearState::slip;
    for (int i = 0; i < shear_components; ++i)
    {
      r.traction[i + 1] = b.residual_stiffness * elastic_slip[i];
      r.tangent[i + 1][i + 1] = b.residual_stiffness;
    }
    return r;
  }
  if (!normal.in_contact || !(yield > 0.0))
  {
    // A point whose elastic shear traction sits on its strength (to round-off) is sliding: it
    // slid in the step just committed and is re-evaluated from that state with a zero
    // increment. Labelled by where τ is, not by whether this evaluation moved the slip, so
    // that every re-evaluation of a converged state (stage results, output) reads the same.
    // (No strength model: τ_y = +∞, never on it.)
    const bool on_strength = std::isfinite(strength.strength) && strength.strength > 0.0
                             && yield >= -1e-9 * strength.strength;
    r.shear_state = !normal.in_contact ? ShearState::open
                    : on_strength      ? ShearState::slip
                                       : ShearState::stick;
    for (int i = 0; i < shear_components; ++i)
    {
      r.traction[i + 1] = ks.value * elastic_slip[i];
      r.tangent[i + 1][i + 1] = ks.value;
      // ∂(k_s(Δ_e) (j_s - s))/∂j_n = -k_s'(Δ_e) (j_s - s) (proportional model; unsymmetric).
      r.tangent[i + 1][0] = -ks.closure_derivative * elastic_slip[i];
    }
    return r;
  }

  // Return mapping: G(Δλ) = τ_y(σ_n(Δ_e(Δλ))) - k_s(Δ_e(Δλ)) (e - Δλ) = 0 on [0, e],
  // G(0) = -f < 0 <= G(e) = τ_y; G' = μ k β - k_s' β (e - Δλ) + k_s with μ = dτ_y/dσ_n,
  // k = dσ_n/dΔ_e, β = d(dilation)/dΔλ.
  auto slope = [&](const SlipPoint& s, double increment)
  {
    return s.strength.slope * s.normal.stiffness * s.dilation.rate
           - s.shear.closure_derivative * s.dilation.rate * (e - increment) + s.shear.value;
  };
  auto residual = [&](double increment)
  {
    const SlipPoint s = slip_point(b, trial_closure, converged, increment, bonded);
    return constitutive::root_finding::Residual{
        s.strength.strength - s.shear.value * (e - increment), slope(s, increment)};
  };
  constitutive::root_finding::Options options;
  options.absolute_scale = e;
  options.residual_tolerance = 1e-14 * ks.value * e;
  const double top = residual(e).value;
  const auto root = constitutive::root_finding::find_root(residual, 0.0, e,
                                                          std::min(yield / ks.value, e), options,
                                                          -yield, top);
  const double increment = root.bracketed ? root.x : std::numeric_limits<double>::quiet_NaN();
  const SlipPoint s = slip_point(b, trial_closure, converged, increment, bonded);

  r.shear_state = ShearState::slip;
  set_normal(r, s.normal);
  const double remaining = e - increment; // |j_s - s| after the return [m]
  // |τ| on the cone: τ_y itself rather than k_s (e - Δλ), which cancels digits when the
  // strength is small against the trial stress (c = 0, σ_n → 0).
  const double shear = s.strength.strength;
  std::array<double, 2> m{};                       // slip direction = trial shear direction
  for (int i = 0; i < shear_components; ++i)
  {
    m[i] = elastic_slip[i] / e;
    trial.slip[i] = converged.slip[i] + increment * m[i];
    r.traction[i + 1] = shear * m[i];
  }
  trial.dilation = converged.dilation + s.dilation.opening;
  trial.maximum_closure = std::max(converged.maximum_closure, s.closure);
  trial.accumulated_slip = converged.accumulated_slip + increment;

  // Consistent tangent by implicit differentiation of G(Δλ; j_n, e) = 0:
  //   ∂G/∂j_n = -(μ k - k_s' (e - Δλ)),  ∂G/∂e = -k_s,
  //   dΔ_e/dj_n = -1 + β dΔλ/dj_n,  dΔ_e/de = β dΔλ/de,  d|τ| = μ k dΔ_e (on the cone).
  const double mu_k = s.strength.slope * s.normal.stiffness;
  const double g_increment = slope(s, increment);
  const double dincrement_dn = (mu_k - s.shear.closure_derivative * remaining) / g_increment;
  const double dincrement_de = s.shear.value / g_increment;
  const double dclosure_dn = -1.0 + s.dilation.rate * dincrement_dn;
  const double dclosure_de = s.dilation.rate * dincrement_de;
  r.tangent[0][0] = -s.normal.stiffness * dclosure_dn;
  for (int i = 0; i < shear_components; ++i)
  {
    r.tangent[0][i + 1] = -s.normal.stiffness * dclosure_de * m[i];
    r.tangent[i + 1][0] = mu_k * dclosure_dn * m[i];
    for (int k = 0; k < shear_components; ++k)
      r.tangent[i + 1][k + 1] = mu_k * dclosure_de * m[i] * m[k]
                                + (shear / e) * ((i == k ? 1.0 : 0.0) - m[i] * m[k]);
  }
  return r;
}
} // namespace

LocalResponse local_response(const JointBehaviour& behaviour, int gdim,
                             const std::array<double, 3>& jump)
{
  JointPointState trial;
  return joint_response(behaviour, gdim, jump, JointPointState{}, trial);
}

} // namespace rockjoint::joint
