// SPDX-License-Identifier: MIT
#include "empirical_laws.hpp"

#include <cmath>
#include <stdexcept>

namespace rockjoint::constitutive
{

namespace
{
void check_stress(const char* law, double normal_stress)
{
  if (!(normal_stress >= 0.0) || std::isinf(normal_stress))
    throw std::invalid_argument(std::string(law) + ": normal stress "
                                + std::to_string(normal_stress)
                                + " Pa has no closure; it must be finite and >= 0");
}
} // namespace

const std::vector<ParameterSpec>& LogarithmicLaw::parameter_specs()
{
  static const std::vector<ParameterSpec> specs{{"closure_scale", "B", "m", "mm"},
                                                {"seating_stress", "σ0", "Pa", "MPa"}};
  return specs;
}

LogarithmicLaw::LogarithmicLaw(double closure_scale, double seating_stress)
    : _closure_scale(parameter_specs()[0].check("LogarithmicLaw", closure_scale)),
      _seating_stress(parameter_specs()[1].check("LogarithmicLaw", seating_stress))
{
}

std::vector<Parameter> LogarithmicLaw::parameters() const
{
  return {{"closure_scale", _closure_scale, "m"}, {"seating_stress", _seating_stress, "Pa"}};
}

ClosureResponse LogarithmicLaw::evaluate_contact(double closure) const
{
  const double x = closure / _closure_scale;
  // expm1 keeps σ accurate for Δ << B.
  const double stress = _seating_stress * std::expm1(x);
  const double stiffness = _seating_stress * std::exp(x) / _closure_scale;
  return {stress, stiffness, 0.0, 0.0, Status::contact};
}

double LogarithmicLaw::closure_at_stress(double normal_stress) const
{
  check_stress("logarithmic", normal_stress);
  return _closure_scale * std::log1p(normal_stress / _seating_stress);
}

const std::vector<ParameterSpec>& ExponentialLaw::parameter_specs()
{
  static const std::vector<ParameterSpec> specs{{"maximum_closure", "V_m", "m", "mm"},
                                                {"characteristic_stress", "σ_c", "Pa", "MPa"}};
  return specs;
}

ExponentialLaw::ExponentialLaw(double maximum_closure, double characteristic_stress)
    : _maximum_closure(parameter_specs()[0].check("ExponentialLaw", maximum_closure)),
      _characteristic_stress(parameter_specs()[1].check("ExponentialLaw", characteristic_stress))
{
}

std::vector<Parameter> ExponentialLaw::parameters() const
{
  return {{"maximum_closure", _maximum_closure, "m"},
          {"characteristic_stress", _characteristic_stress, "Pa"}};
}

ClosureResponse ExponentialLaw::evaluate_contact(double closure) const
{
  if (closure >= _maximum_closure)
    return beyond_maximum_closure();
  const double x = closure / _maximum_closure;
  return {-_characteristic_stress * std::log1p(-x),
          _characteristic_stress / (_maximum_closure - closure), 0.0, 0.0, Status::contact};
}

double ExponentialLaw::closure_at_stress(double normal_stress) const
{
  check_stress("exponential", normal_stress);
  return -_maximum_closure * std::expm1(-normal_stress / _characteristic_stress);
}

} // namespace rockjoint::constitutive
