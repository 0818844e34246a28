// SPDX-License-Identifier: MIT
#include "barton_bandis.hpp"
#include "validation.hpp"

#include <cmath>
#include <stdexcept>

namespace rockjoint::constitutive
{

const std::vector<ParameterSpec>& BartonBandis::parameter_specs()
{
  static const std::vector<ParameterSpec> specs{
      {"initial_normal_stiffness", "K_ni", "Pa/m", "MPa/mm"},
      {"maximum_closure", "V_m", "m", "mm"}};
  return specs;
}

BartonBandis::BartonBandis(double initial_normal_stiffness, double maximum_closure)
    : _initial_normal_stiffness(
          parameter_specs()[0].check("BartonBandis", initial_normal_stiffness)),
      _maximum_closure(parameter_specs()[1].check("BartonBandis", maximum_closure))
{
}

BartonBandis BartonBandis::from_joint_properties(double jrc, double jcs,
                                                 double initial_aperture,
                                                 MaximumClosureCoefficients c)
{
  namespace v = validation;
  const std::string who = "BartonBandis.from_joint_properties";
  v::in_range(who, "jrc", jrc, "", 0.0, 20.0, true);
  v::positive(who, "jcs", jcs, "Pa");
  v::positive(who, "initial_aperture", initial_aperture, "m");
  // The correlations are in MPa and mm.
  const double ratio = (jcs * 1e-6) / (initial_aperture * 1e3);
  const double kni_mpa_per_mm = -7.15 + 1.75 * jrc + 0.02 * ratio;
  const double vm_mm = c.A + c.B * jrc + c.C * std::pow(ratio, c.D);
  if (!(kni_mpa_per_mm > 0.0))
    v::fail(who, "initial_normal_stiffness (estimated)", kni_mpa_per_mm, "MPa/mm",
            "> 0: JRC/JCS/a_j are outside the Bandis correlation's range");
  if (!(vm_mm > 0.0))
    v::fail(who, "maximum_closure (estimated)", vm_mm, "mm",
            "> 0: JRC/JCS/a_j are outside the Bandis correlation's range");
  return BartonBandis(kni_mpa_per_mm * 1e9, vm_mm * 1e-3);
}

std::vector<Parameter> BartonBandis::parameters() const
{
  return {{"initial_normal_stiffness", _initial_normal_stiffness, "Pa/m"},
          {"maximum_closure", _maximum_closure, "m"}};
}

ClosureResponse BartonBandis::evaluate_contact(double closure) const
{
  if (closure >= _maximum_closure)
    return beyond_maximum_closure();
  const double free = 1.0 - closure / _maximum_closure; // remaining closure fraction
  return {_initial_normal_stiffness * closure / free,
          _initial_normal_stiffness / (free * free), 0.0, 0.0, Status::contact};
}

double BartonBandis::closure_at_stress(double normal_stress) const
{
  if (!(normal_stress >= 0.0) || std::isinf(normal_stress))
    throw std::invalid_argument("barton_bandis: normal stress "
                                + std::to_string(normal_stress)
                                + " Pa has no closure; it must be finite and >= 0");
  return normal_stress * _maximum_closure
         / (_initial_normal_stiffness * _maximum_closure + normal_stress);
}

} // namespace rockjoint::constitutive
