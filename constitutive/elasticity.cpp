// SPDX-License-Identifier: MIT
#include "elasticity.hpp"
#include "validation.hpp"

namespace rockjoint::constitutive
{

double composite_modulus(double young1, double poisson1, double young2, double poisson2)
{
  namespace v = validation;
  const std::string who = "composite_modulus";
  v::positive(who, "young1", young1, "Pa");
  v::positive(who, "young2", young2, "Pa");
  v::in_range(who, "poisson1", poisson1, "", -1.0, 0.5, true);
  v::in_range(who, "poisson2", poisson2, "", -1.0, 0.5, true);
  if (poisson1 == -1.0 || poisson2 == -1.0)
    v::fail(who, "poisson", -1.0, "", "in (-1, 0.5]");
  return 1.0 / ((1.0 - poisson1 * poisson1) / young1 + (1.0 - poisson2 * poisson2) / young2);
}

double composite_modulus(double young, double poisson)
{
  return composite_modulus(young, poisson, young, poisson);
}

} // namespace rockjoint::constitutive
