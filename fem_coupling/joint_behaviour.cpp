#include "joint_behaviour.hpp"

#include <rockjoint/constitutive/validation.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace rockjoint::fem
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
}

namespace
{
/// dk/dΔ by a central difference of the law's analytic tangent (one-sided near the
/// maximum closure). Needed only for the consistent tangent of the proportional shear model:
/// the ClosureLaw interface exposes σ and k, not k'.
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

} // namespace

LocalResponse local_response(const JointBehaviour& b, int gdim, const std::array<double, 3>& jump)
{
  LocalResponse r;
  r.closure = -jump[0];
  // Through the base interface: a law's own opening branch (TabulatedLaw's residual stiffness
  // k_res) comes in via the ClosureLaw::evaluate_open hook.
  const constitutive::ClosureResponse law = b.law->evaluate(r.closure);
  r.status = law.status;
  r.normal_stress = law.normal_stress + b.residual_stiffness * r.closure;
  double k = law.normal_stiffness;
  if (r.closure == 0.0)
  {
    // At the kink Δ = 0 (e.g. the untouched initial state) take the contact-side tangent
    // k(0+), an element of the generalized derivative: with k = 0 there, the first Newton
    // step of a column held by its joints would face a singular matrix.
    const double k0 = b.law->normal_stiffness(std::numeric_limits<double>::min());
    k = std::isfinite(k0) ? k0 : 0.0;
  }
  r.normal_stiffness = k + b.residual_stiffness;

  // t_n = -σ_total(Δ), Δ = -j_n  ⇒  ∂t_n/∂j_n = +k_total.
  r.traction[0] = -r.normal_stress;
  r.tangent[0][0] = r.normal_stiffness;

  double ks = b.shear_stiffness, dks_dclosure = 0.0;
  if (b.shear_model == ShearModel::proportional)
  {
    ks = b.shear_stiffness_ratio * r.normal_stiffness;
    dks_dclosure = b.shear_stiffness_ratio * stiffness_derivative(*b.law, r.closure);
  }
  for (int i = 1; i < gdim; ++i)
  {
    r.traction[i] = ks * jump[i];
    r.tangent[i][i] = ks;
    // ∂(k_s(Δ) j_s)/∂j_n = -k_s'(Δ) j_s (proportional model only; non-symmetric).
    r.tangent[i][0] = -dks_dclosure * jump[i];
  }
  return r;
}

} // namespace rockjoint::fem
