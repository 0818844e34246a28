// SPDX-License-Identifier: MIT
#pragma once
/// @file population_quadrature.hpp
/// Adaptive quadrature of integrals over a summit-height density with an algebraic endpoint
/// singularity (theory §2: the GW integrands behave like (z-d)^{1/2} at z = d).
///
/// ∫_lo^hi F(s - s*) p(s) ds with lo >= s*, where F(w) ~ w^{n/2} near w = 0. When the
/// singular point s* is near the interval (lo - s* <= hi - lo) the substitution s = s* + u²
/// turns the integrand into 2u F(u²) p(s* + u²), smooth in u; otherwise the integrand is
/// smooth on [lo, hi] and is integrated in s directly (which also keeps s - s* exact when
/// s* is far below the window, e.g. a 1 m closure on a 0.1 µm roughness).
///
/// Rule: GSL's adaptive Gauss-Kronrod (qag, 61 points: the integrands are smooth after the
/// substitution and one panel usually suffices) to a relative tolerance; if it reports
/// a failure (round-off, too many subdivisions), the doubly adaptive CQUAD rule is tried and
/// the estimate with the smaller error bound is kept. Nothing throws: the caller gets the
/// best estimate and a flag. GSL's abort-on-error handler is switched off once per process.
/// Workspaces are thread_local (one per nesting level), so concurrent calls from several
/// threads are safe, and so is an integrand that itself evaluates a law.

#include <cmath>
#include <gsl/gsl_math.h>
#include <utility>

namespace rockjoint::constitutive::quadrature
{

/// Result of one integration.
struct Result
{
  double value = 0.0;    ///< estimate of the integral
  double error = 0.0;    ///< GSL's error bound
  bool converged = true; ///< false if neither rule met the tolerance (value: best estimate)
};

/// Smallest relative tolerance GSL accepts with a zero absolute tolerance (50 ε, rounded up).
inline constexpr double minimum_tolerance = 1.2e-14;

/// Turn GSL's abort-on-error handler off (idempotent, thread-safe).
void disable_gsl_abort();

/// ∫_a^b f(x) dx for a gsl_function, relative tolerance `tolerance` (clamped to
/// minimum_tolerance), zero absolute tolerance. Empty interval (b <= a): 0.
Result integrate(const gsl_function& f, double a, double b, double tolerance);

/// ∫_lo^hi integrand(w, s) ds, w = s - s* >= 0 computed exactly, with the substitution
/// described in the file comment. `integrand(w, s)` must be finite for w >= 0.
template <class Integrand>
Result integrate_from_singularity(const Integrand& integrand, double singular_point, double lo,
                                  double hi, double tolerance)
{
  if (!(hi > lo))
    return {};
  const double s0 = singular_point;
  if (lo - s0 <= hi - lo)
  {
    auto f = [](double u, void* params) -> double
    {
      const auto& p = *static_cast<const std::pair<const Integrand*, double>*>(params);
      const double w = u * u;
      return 2.0 * u * (*p.first)(w, p.second + w);
    };
    std::pair<const Integrand*, double> params{&integrand, s0};
    gsl_function F{f, &params};
    return integrate(F, std::sqrt(lo - s0), std::sqrt(hi - s0), tolerance);
  }
  auto f = [](double s, void* params) -> double
  {
    const auto& p = *static_cast<const std::pair<const Integrand*, double>*>(params);
    return (*p.first)(s - p.second, s);
  };
  std::pair<const Integrand*, double> params{&integrand, s0};
  gsl_function F{f, &params};
  return integrate(F, lo, hi, tolerance);
}

} // namespace rockjoint::constitutive::quadrature
