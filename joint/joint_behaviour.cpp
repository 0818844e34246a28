// SPDX-License-Identifier: MIT
#include "joint_behaviour.hpp"

#include <rockjoint/constitutive/root_finding.hpp>
#include <rockjoint/constitutive/validation.hpp>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace rockjoint::joint
{

void validate(const JointBehaviour& behaviour, const std::string& label)
{
  const std::string owner = "joint '" + label + "'";
  if (!behaviour.law)
    throw std::invalid_argument(owner + ": no closure law given");
  namespace v = constitutive::validation;
  v::non_negative(owner, "shear_stiffness", behaviour.shear_stiffness, "Pa/m");
  v::non_negative(owner, "shear_stiffness_ratio", behaviour.shear_stiffness_ratio, "-");
  v::non_negative(owner, "residual_stiffness", behaviour.residual_stiffness, "Pa/m");
  v::in_range(owner, "effective_stress_coefficient", behaviour.effective_stress_coefficient, "-",
              0.0, 1.0, true);
  validate(behaviour.strength, owner);
}

namespace
{
/// The law's response at Δ after the converged Δ_m (a law without history ignores Δ_m).
constitutive::ClosureResponse law_response(const JointBehaviour& b, double closure,
                                           double maximum_closure, double* permanent = nullptr)
{
  if (!b.law->has_history())
    return b.law->evaluate(closure);
  const constitutive::HistoryResponse h = b.law->evaluate_with_history(closure, maximum_closure);
  if (permanent)
    *permanent = h.on_virgin_curve ? 0.0 : h.permanent_closure;
  return h.response;
}

/// dk/dΔ of the virgin law by a central difference of its analytic tangent (one-sided near the
/// maximum closure). Needed only for the consistent tangent of the proportional shear model: the
/// ClosureLaw interface exposes σ and k, not k'.
double stiffness_derivative(const constitutive::ClosureLaw& law, double closure)
{
  if (!(closure > 0.0))
    return 0.0;
  const double h = 1e-6 * closure;
  const double up = closure + h;
  if (up < law.maximum_closure())
    return (law.normal_stiffness(up) - law.normal_stiffness(closure - h)) / (2.0 * h);
  return (law.normal_stiffness(closure) - law.normal_stiffness(closure - h)) / h;
}

/// k(0+) + k_r: the contact-side tangent at Δ = 0 (finite, or 0 if the law has none).
double contact_side_stiffness(const JointBehaviour& b)
{
  const double k0 = b.law->normal_stiffness(std::numeric_limits<double>::min());
  return (std::isfinite(k0) ? k0 : 0.0) + b.residual_stiffness;
}
} // namespace

NormalResponse normal_response(const JointBehaviour& b, double closure, bool bonded,
                               double maximum_closure)
{
  NormalResponse r;
  // Through the base interface: a law's own opening branch (TabulatedLaw's residual stiffness
  // k_res) comes in via the ClosureLaw::evaluate_open hook (shifted by Δ_p on a hysteretic
  // branch: the joint opens at its permanent closure, normal_hysteresis.hpp (H3)).
  const constitutive::ClosureResponse law
      = law_response(b, closure, maximum_closure, &r.permanent_closure);
  r.status = law.status;
  r.stress = law.normal_stress + b.residual_stiffness * closure;
  r.stiffness = law.normal_stiffness + b.residual_stiffness;
  r.in_contact = closure >= r.permanent_closure || std::isnan(closure);
  // The kink at Δ = 0 and the tensile bond belong to the virgin joint; on an unloading branch
  // (Δ_p > 0) the joint simply opens below Δ_p.
  const bool virgin = r.permanent_closure == 0.0;
  if (virgin && closure == 0.0)
  {
    // At the kink Δ = 0 (e.g. the untouched initial state) take the contact-side tangent
    // k(0+), an element of the generalized derivative: with k = 0 there, the first Newton
    // step of a column held by its joints would face a singular matrix.
    r.stiffness = contact_side_stiffness(b);
  }
  else if (virgin && closure < 0.0 && bonded && reduced_tensile_strength(b.strength) > 0.0)
  {
    // Bonded joint in tension: the contact-side spring continued into tension (continuous
    // traction and tangent at Δ = 0) while its tension stays within T (tension cut-off).
    const double k0 = contact_side_stiffness(b);
    if (-k0 * closure <= reduced_tensile_strength(b.strength))
    {
      r.stress = k0 * closure;
      r.stiffness = k0;
      r.in_contact = true;
    }
    else
      r.bond_fails = true;
  }
  return r;
}

ShearStiffness shear_stiffness(const JointBehaviour& b, const NormalResponse& normal,
                               double closure)
{
  if (!normal.in_contact)
    return {normal.stiffness, 0.0}; // open: the isotropic residual spring k_open + k_r
  if (b.shear_model == ShearModel::proportional)
  {
    // On an unloading branch k_s follows the virgin law's k at the current closure: the branch's
    // own k jumps at Δ_m (stiff unloading, (H4)), which would make t_s = k_s (j_s - s) jump there
    // for a joint carrying shear; the virgin k is continuous and falls as the joint opens.
    const double k = normal.permanent_closure > 0.0
                         ? b.law->normal_stiffness(closure) + b.residual_stiffness
                         : normal.stiffness;
    const double slope = closure > 0.0 ? stiffness_derivative(*b.law, closure) : 0.0;
    return {b.shear_stiffness_ratio * k, b.shear_stiffness_ratio * slope};
  }
  return {b.shear_stiffness, 0.0};
}

double closure_at_normal_stress(const JointBehaviour& b, double target)
{
  if (!b.law)
    throw std::invalid_argument("closure_at_normal_stress: the joint behaviour has no closure law");
  auto refused = [&](const std::string& why)
  {
    std::ostringstream msg;
    msg << "joint normal stress " << target << " Pa (law " << b.law->name() << ", k_r "
        << b.residual_stiffness << " Pa/m) has no closure: " << why;
    return msg.str();
  };
  if (!(target >= 0.0) || std::isinf(target))
    throw std::invalid_argument(refused("it must be finite and >= 0 (compression positive)"));
  double upper = 0.0; // Δ_law: σ(Δ_law) = σ_t, so σ(Δ_law) + k_r Δ_law >= σ_t
  try
  {
    upper = b.law->closure_at_stress(target);
  }
  catch (const std::domain_error& e)
  {
    throw std::domain_error(refused(e.what()));
  }
  const double kr = b.residual_stiffness;
  if (kr == 0.0 || upper == 0.0)
    return upper;

  // r(Δ) = σ(Δ) + k_r Δ - σ_t, increasing: r(0) = -σ_t < 0 <= r(Δ_law) = k_r Δ_law. Newton from
  // Δ_law (the upper end: monotone convergence for a convex law such as Barton-Bandis).
  namespace rf = constitutive::root_finding;
  const rf::Root root = rf::find_root(
      [&](double x)
      {
        const constitutive::ClosureResponse r = b.law->evaluate(x);
        return rf::Residual{r.normal_stress + kr * x - target, r.normal_stiffness + kr};
      },
      0.0, upper, upper);
  if (!root.converged)
    throw std::runtime_error(refused("the root finder did not converge on [0, "
                                     + std::to_string(upper) + "] m"));
  return root.x;
}

} // namespace rockjoint::joint
