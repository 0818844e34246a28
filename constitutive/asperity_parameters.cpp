// SPDX-License-Identifier: MIT
#include "asperity_parameters.hpp"

#include <cmath>

namespace rockjoint::constitutive
{

const std::vector<ParameterSpec>& AsperityParameters::parameter_specs()
{
  static const std::vector<ParameterSpec> specs{{"composite_modulus", "E*", "Pa", "GPa"},
                                                {"summit_density", "η", "1/m^2", "1/mm²"},
                                                {"summit_radius", "β", "m", "mm"},
                                                {"summit_height_std", "σ_s", "m", "mm"},
                                                {"sampling_interval", "h", "m", "mm"}};
  return specs;
}

void validate(const AsperityParameters& p, const std::string& owner)
{
  const auto& spec = AsperityParameters::parameter_specs();
  spec[0].check(owner, p.composite_modulus);
  spec[1].check(owner, p.summit_density);
  spec[2].check(owner, p.summit_radius);
  spec[3].check(owner, p.summit_height_std);
  if (!std::isnan(p.sampling_interval))
    spec[4].check(owner, p.sampling_interval);
}

} // namespace rockjoint::constitutive
