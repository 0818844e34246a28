// SPDX-License-Identifier: MIT
#pragma once
// Reference computations for the GW / Tang tests, independent of the production code:
// long-double tanh-sinh quadrature, a long-double bisection for the substrate cubic and the
// Gaussian partial moments through parabolic cylinder functions built from GSL's Bessel K.
#include <gsl/gsl_sf_bessel.h>

#include <cmath>
#include <functional>
#include <numbers>

namespace rockjoint::testing
{

/// ∫_a^b f(x) dx by tanh-sinh in long double, refined until two levels agree to 1e-17
/// relative (f analytic inside, any endpoint behaviour).
inline long double tanh_sinh(const std::function<long double(long double)>& f, long double a,
                             long double b)
{
  const long double c = 0.5L * (a + b), r = 0.5L * (b - a);
  const long double half_pi = std::numbers::pi_v<long double> / 2;
  auto term = [&](long double t) -> long double
  {
    const long double s = half_pi * std::sinh(t);
    const long double ch = std::cosh(s);
    // Distance to the nearer endpoint, 1 - tanh|s| = 2/(e^{2|s|} + 1), without cancellation.
    const long double gap = 2.0L / (std::exp(2.0L * std::fabs(s)) + 1.0L);
    if (gap == 0.0L)
      return 0.0L;
    const long double x = s > 0 ? b - r * gap : a + r * gap;
    const long double w = r * half_pi * std::cosh(t) / (ch * ch);
    return w * f(x);
  };
  const long double tmax = 4.5L;
  long double h = 0.5L;
  long double sum = term(0.0L);
  for (long double t = h; t <= tmax; t += h)
    sum += term(t) + term(-t);
  long double estimate = h * sum;
  for (int level = 0; level < 12; ++level)
  {
    h *= 0.5L;
    for (long double t = h; t <= tmax; t += 2 * h)
      sum += term(t) + term(-t);
    const long double next = h * sum;
    if (std::fabs(next - estimate) <= 1e-17L * std::fabs(next))
      return next;
    estimate = next;
  }
  return estimate;
}

inline long double phi_ld(long double s)
{
  return std::exp(-0.5L * s * s) / std::sqrt(2.0L * std::numbers::pi_v<long double>);
}

/// ∫_h^∞ (s-h)^n φ(s) ds by tanh-sinh after s = h + u² (Gaussian summit heights).
inline long double gaussian_moment_quadrature(long double n, long double h)
{
  const long double top = std::sqrt(std::max(h, 0.0L) + 16.0L - h); // φ falls by e^{-128}
  return tanh_sinh([&](long double u)
                   { return 2.0L * std::pow(u, 2.0L * n + 1.0L) * phi_ld(h + u * u); },
                   0.0L, top);
}

/// ∫_h^∞ (s-h)^n φ(s) ds = Γ(n+1)/√(2π) e^{-h²/4} D_{-n-1}(h) for n = 1/2, 3/2 and h > 0,
/// with D_{-1/2}(z) = √(z/2π) K_{1/4}(z²/4), D_{1/2}(z) = z^{3/2}/(2√(2π)) (K_{1/4} + K_{3/4})
/// (DLMF 12.7.10-11) and the recurrence D_{ν+1} - z D_ν + ν D_{ν-1} = 0 (DLMF 12.8.1).
inline double gaussian_moment_parabolic_cylinder(double n, double h)
{
  const double x = 0.25 * h * h;
  // Scaled Bessel functions e^x K(x): the factor e^{-x} joins e^{-h²/4}.
  const double k14 = gsl_sf_bessel_Knu_scaled(0.25, x), k34 = gsl_sf_bessel_Knu_scaled(0.75, x);
  const double two_pi = 2.0 * std::numbers::pi;
  const double d_m12 = std::sqrt(h / two_pi) * k14;
  const double d_p12 = h * std::sqrt(h) / (2.0 * std::sqrt(two_pi)) * (k14 + k34);
  const double d_m32 = 2.0 * (d_p12 - h * d_m12);         // ν = -1/2
  const double d_m52 = (2.0 / 3.0) * (d_m12 - h * d_m32); // ν = -3/2
  const double d = n == 0.5 ? d_m32 : d_m52;
  return std::tgamma(n + 1.0) / std::sqrt(two_pi) * std::exp(-2.0 * x) * d;
}

/// Positive root t of c t³ + t² = w by bisection in long double (200 halvings).
inline long double cubic_root_bisection(long double w, long double c)
{
  long double lo = 0.0L, hi = std::sqrt(w);
  for (int i = 0; i < 200; ++i)
  {
    const long double mid = 0.5L * (lo + hi);
    if (c * mid * mid * mid + mid * mid > w)
      hi = mid;
    else
      lo = mid;
  }
  return 0.5L * (lo + hi);
}

} // namespace rockjoint::testing

namespace rockjoint::testing
{
/// Positive root t of c t³ + t² = w by Newton in long double from the upper bound √w
/// (the cubic is increasing and convex: the iterates decrease monotonically to the root).
inline long double cubic_root_newton(long double w, long double c)
{
  if (!(w > 0))
    return 0.0L;
  long double t = std::sqrt(w);
  for (int i = 0; i < 200; ++i)
  {
    const long double step = (c * t * t * t + t * t - w) / (3 * c * t * t + 2 * t);
    if (!(step > 0))
      break;
    t -= step;
  }
  return t;
}
} // namespace rockjoint::testing
