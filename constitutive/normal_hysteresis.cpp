// SPDX-License-Identifier: MIT
#include "normal_hysteresis.hpp"


#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rockjoint::constitutive
{

const std::vector<ParameterSpec>& NormalHysteresis::parameter_specs()
{
  // r in [0, 1): a permanent closure below the largest closure reached; m >= 1: an unloading
  // branch at least as stiff as the virgin curve (docs/hysteresis.md, H1-H2).
  static const std::vector<ParameterSpec> specs{
      {"permanent_fraction", "r", "-", "-", 0.0, true, 1.0, false},
      {"unloading_exponent", "m", "-", "-", 1.0, true}};
  return specs;
}

NormalHysteresis::NormalHysteresis(std::shared_ptr<const ClosureLaw> virgin,
                                   double permanent_fraction, double unloading_exponent)
    : _virgin(std::move(virgin)), _r(permanent_fraction), _m(unloading_exponent)
{
  if (!_virgin)
    throw std::invalid_argument("NormalHysteresis: no virgin closure law given");
  if (_virgin->has_history())
    throw std::invalid_argument("NormalHysteresis: the virgin law '" + _virgin->name()
                                + "' has history itself; give its own virgin law");
  const std::string owner = "NormalHysteresis(" + _virgin->name() + ")";
  parameter_specs()[0].check(owner, _r);
  parameter_specs()[1].check(owner, _m);
}

HistoryResponse NormalHysteresis::evaluate_with_history(double closure,
                                                       double maximum_closure) const
{
  HistoryResponse h;
  if (std::isnan(closure) || std::isnan(maximum_closure))
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    h.response = {nan, nan, nan, nan, Status::invalid_closure};
    h.maximum_closure = nan;
    h.permanent_closure = nan;
    return h;
  }
  const double dm = std::max(maximum_closure, 0.0);
  if (closure >= dm || dm == 0.0)
  {
    // Loading past every earlier closure (or a virgin joint): the virgin curve, and Δ_m follows.
    h.response = _virgin->evaluate(closure);
    h.maximum_closure = std::max(dm, closure);
    h.permanent_closure = permanent_closure(h.maximum_closure);
    return h;
  }
  h.on_virgin_curve = false;
  h.maximum_closure = dm;
  h.permanent_closure = permanent_closure(dm);
  const double span = dm - h.permanent_closure; // > 0: r < 1
  if (closure <= h.permanent_closure)
  {
    // (H3) open below the permanent closure: the law's own opening branch, shifted by Δ_p.
    h.response = _virgin->evaluate(std::min(closure - h.permanent_closure, 0.0));
    h.response.contact_area_ratio = 0.0;
    h.response.contact_area_rate = 0.0;
    return h;
  }
  const ClosureResponse top = _virgin->evaluate(dm);
  const double x = (closure - h.permanent_closure) / span;
  h.response.normal_stress = top.normal_stress * std::pow(x, _m);            // (H2)
  h.response.normal_stiffness = _m * top.normal_stress * std::pow(x, _m - 1.0) / span;
  h.response.status = top.status == Status::contact ? Status::contact : top.status;
  // The branch is a history state of the walls, not a contact-area model: A/A0 is not given
  // there (the virgin law's area belongs to first loading only).
  return h;
}

std::vector<double> NormalHysteresis::closure_path(std::span<const double> stress,
                                                   double maximum_closure) const
{
  std::vector<double> closure(stress.size());
  double dm = std::max(maximum_closure, 0.0);
  double top = dm > 0.0 ? _virgin->normal_stress(dm) : 0.0; // σ_v(Δ_m)
  for (std::size_t i = 0; i < stress.size(); ++i)
  {
    const double s = stress[i];
    if (!(s >= 0.0) || std::isinf(s))
      throw std::invalid_argument("NormalHysteresis::closure_path: stress[" + std::to_string(i)
                                  + "] = " + std::to_string(s)
                                  + " Pa; it must be finite and >= 0 (compression positive)");
    if (s >= top)
    {
      closure[i] = _virgin->closure_at_stress(s); // loading on the virgin curve
      dm = std::max(dm, closure[i]);
      top = s;
      continue;
    }
    const double dp = permanent_closure(dm);
    closure[i] = dp + (dm - dp) * std::pow(s / top, 1.0 / _m);
  }
  return closure;
}

std::vector<Parameter> NormalHysteresis::parameters() const
{
  std::vector<Parameter> p = _virgin->parameters();
  p.push_back({"permanent_fraction", _r, "-"});
  p.push_back({"unloading_exponent", _m, "-"});
  return p;
}

} // namespace rockjoint::constitutive
