// SPDX-License-Identifier: MIT
#include "greenwood_williamson.hpp"

namespace rockjoint::constitutive
{

GreenwoodWilliamson::GreenwoodWilliamson(const AsperityParameters& parameters,
                                         HeightDistribution distribution,
                                         const SeatingReference& reference,
                                         double quadrature_tolerance)
    : SummitPopulationLaw("GreenwoodWilliamson", parameters, distribution, 0.0, std::nullopt,
                          reference, quadrature_tolerance)
{
}

GreenwoodWilliamson::GreenwoodWilliamson(double composite_modulus, EmpiricalSummits summits,
                                         const SeatingReference& reference)
    : SummitPopulationLaw("GreenwoodWilliamson", composite_modulus, std::move(summits), 0.0,
                          std::nullopt, reference, default_quadrature_tolerance)
{
}

} // namespace rockjoint::constitutive
