// SPDX-License-Identifier: MIT
#include "asperity_parameters.hpp"
#include "validation.hpp"

#include <cmath>

namespace rockjoint::constitutive
{

void validate(const AsperityParameters& p, const std::string& owner)
{
  validation::positive(owner, "composite_modulus", p.composite_modulus, "Pa");
  validation::positive(owner, "summit_density", p.summit_density, "1/m^2");
  validation::positive(owner, "summit_radius", p.summit_radius, "m");
  validation::positive(owner, "summit_height_std", p.summit_height_std, "m");
  if (!std::isnan(p.sampling_interval))
    validation::positive(owner, "sampling_interval", p.sampling_interval, "m");
}

} // namespace rockjoint::constitutive
