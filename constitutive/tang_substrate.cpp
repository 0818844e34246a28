// SPDX-License-Identifier: MIT
#include "tang_substrate.hpp"

namespace rockjoint::constitutive
{

TangSubstrate::TangSubstrate(const AsperityParameters& parameters, HeightDistribution distribution,
                             const SubstrateParameters& substrate,
                             const SeatingReference& reference, double quadrature_tolerance)
    : SummitPopulationLaw("TangSubstrate", parameters, distribution,
                          substrate.deflection_coefficient, substrate.base_radius, reference,
                          quadrature_tolerance)
{
}

TangSubstrate::TangSubstrate(double composite_modulus, EmpiricalSummits summits,
                             const SubstrateParameters& substrate,
                             const SeatingReference& reference)
    : SummitPopulationLaw("TangSubstrate", composite_modulus, std::move(summits),
                          substrate.deflection_coefficient, substrate.base_radius, reference,
                          default_quadrature_tolerance)
{
}

std::vector<Parameter> TangSubstrate::parameters() const
{
  std::vector<Parameter> p = SummitPopulationLaw::parameters();
  p.push_back({"deflection_coefficient", deflection_coefficient(), ""});
  p.push_back({"base_radius", base_radius(), "m"});
  return p;
}

} // namespace rockjoint::constitutive
