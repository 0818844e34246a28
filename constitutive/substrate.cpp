// SPDX-License-Identifier: MIT
#include "substrate.hpp"

#include <cmath>

namespace rockjoint::constitutive::substrate
{

double reduction_factor(double q)
{
  if (!(q > 0.0))
    return 1.0;
  if (std::isinf(q))
    return 0.0;
  // F(τ) = q τ³ + τ² - 1 is increasing and convex on τ > 0. Start from y = (1+q)^{-1/3}:
  // with q = y^{-3} - 1, F(y) = y²(1-y) >= 0, so y is an upper bound, exact to leading order
  // for q -> 0 and q -> ∞, and within 5.5 % of the root for every q (worst near q = 2).
  // Two Halley steps (cubic convergence: relative error ε -> about ε³/2 for every q)
  // take 4e-2 to < 1e-12, and a final Newton step squares that below rounding: a fixed,
  // branch-free sequence (the cubic solve dominates the cost of the substrate law).
  double tau = 1.0 / std::cbrt(1.0 + q);
  for (int it = 0; it < 2; ++it)
  {
    const double qt = q * tau;
    const double f = (qt + 1.0) * tau * tau - 1.0;
    const double df = (3.0 * qt + 2.0) * tau;
    const double d2f = 6.0 * qt + 2.0;
    tau -= f * df / (df * df - 0.5 * f * d2f);
  }
  const double f = (q * tau + 1.0) * tau * tau - 1.0;
  tau -= f / ((3.0 * q * tau + 2.0) * tau);
  return tau;
}

HertzApproach hertz_approach(double w, double c)
{
  if (!(w > 0.0))
    return {};
  const double sw = std::sqrt(w);
  if (c == 0.0) // plain Hertz: keep g = w exactly
    return {sw, w, 1.0};
  const double t = sw * reduction_factor(c * sw);
  return {t, t * t, 1.0 / (1.0 + 1.5 * c * t)};
}

double cube_difference(double ta, double tb, double c, double dw)
{
  const double s2 = ta * ta + ta * tb + tb * tb;
  const double denominator = c * s2 + ta + tb;
  if (!(denominator > 0.0))
    return 0.0;
  return dw / denominator * s2;
}

} // namespace rockjoint::constitutive::substrate
