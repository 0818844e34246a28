// SPDX-License-Identifier: MIT
#pragma once
/// @file root_finding.hpp
/// The project's one bracketed root finder: safeguarded Newton for an increasing residual.
///
/// Every inverse in the library is a 1D root of a monotone function on a known bracket: Δ(σ)
/// of a law, the seating separation of a summit population, the internal closure of variant
/// I2, the validity limits of Tang & Jiao, the fringe pressure of the numeric interaction cell
/// and the inverse of a table segment. They differ only in the step they can afford (an
/// analytic slope, a secant through the bracket, or none) and in what they stop on, so one
/// routine serves them all:
///   - the step is Newton's when the residual comes with a finite, non-zero slope; otherwise
///     Illinois (modified regula falsi through the bracket values) when `Options::secant` is
///     set, otherwise bisection;
///   - a step that leaves the open bracket (or is not finite) is replaced by bisection, so the
///     iterate never leaves the bracket and convergence is guaranteed for a continuous residual;
///   - it stops when the residual is exactly zero or |r| <= residual_tolerance, when the
///     bracket is narrower than the tolerance, or when a Newton/secant step is smaller than it.
#include <algorithm>
#include <cmath>
#include <limits>

namespace rockjoint::constitutive::root_finding
{

/// Value r(x) of the residual and its slope r'(x) (NaN when the caller has none).
struct Residual
{
  double value; ///< r(x)
  double slope = std::numeric_limits<double>::quiet_NaN(); ///< r'(x), NaN if unknown
};

/// Stopping rules and the step used without a slope.
struct Options
{
  /// Width of the bracket or size of a step, relative to max(|x|, absolute_scale), at which
  /// the root is taken as found.
  double relative_tolerance = 1e-15;
  /// Scale below which |x| does not shrink the tolerance (roots near 0), in units of x.
  double absolute_scale = 0.0;
  /// |r(x)| at or below this is a root (0: only an exact zero).
  double residual_tolerance = 0.0;
  int maximum_iterations = 400; ///< iteration limit
  /// Without a slope: Illinois steps through the bracket values (true) or bisection (false).
  bool secant = false;
};

/// The last evaluated iterate, the final bracket (lo: r <= 0 side, hi: r >= 0 side) and the
/// number of residual evaluations. `converged` is false if maximum_iterations ran out or the
/// bracket was refused; `bracketed` is false (and x NaN, no evaluation made) if lo > hi, an
/// end is not finite, or a given end residual has the wrong sign (r_lo > 0 or r_hi < 0).
struct Root
{
  double x; ///< last iterate (the root if converged)
  double lo; ///< bracket end with r <= 0
  double hi; ///< bracket end with r >= 0
  int evaluations = 0; ///< residual evaluations
  bool converged = false; ///< a stopping rule was met
  bool bracketed = true; ///< the initial bracket was valid
};

/// Next trial end when a bracket is grown upwards from x > 0 towards `limit`: x doubled
/// when the limit is +∞, otherwise the distance to the limit halved (the limit itself once
/// within 1e-15 relative of it, so the growth ends in finitely many steps).
inline double grow_towards(double x, double limit)
{
  if (!std::isfinite(limit))
    return 2.0 * x;
  const double next = 0.5 * (x + limit);
  return limit - next <= 1e-15 * limit ? limit : next;
}

/// Root of an increasing residual on [lo, hi] with r(lo) <= 0 <= r(hi), starting from x0 (a
/// point of the closed bracket, e.g. an end whose residual the caller has at hand; NaN or a
/// point outside: the first point comes from the bracket as a later step would). `r_lo`,
/// `r_hi`: the residual at the ends if known (NaN otherwise; the secant needs both; a known
/// end of the wrong sign is reported as not bracketed). `residual(x)` returns a Residual.
/// Never throws.
template <class F>
Root find_root(F&& residual, double lo, double hi, double x0, const Options& options = {},
               double r_lo = std::numeric_limits<double>::quiet_NaN(),
               double r_hi = std::numeric_limits<double>::quiet_NaN())
{
  Root out{x0, lo, hi};
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo <= hi) || r_lo > 0.0 || r_hi < 0.0)
  {
    out.x = std::numeric_limits<double>::quiet_NaN();
    out.bracketed = false;
    return out;
  }
  int side = 0; // which end moved last (Illinois halves the stale end's value)
  auto tolerance = [&](double x)
  { return options.relative_tolerance * std::max(std::abs(x), options.absolute_scale); };
  auto secant_point = [&]
  {
    return options.secant && std::isfinite(r_lo) && std::isfinite(r_hi) && r_hi != r_lo
               ? (out.lo * r_hi - out.hi * r_lo) / (r_hi - r_lo)
               : std::numeric_limits<double>::quiet_NaN();
  };
  double x = x0;
  if (!(x >= out.lo && x <= out.hi))
  {
    x = secant_point();
    if (!(x > out.lo && x < out.hi))
      x = 0.5 * (out.lo + out.hi);
  }
  for (int it = 0; it < options.maximum_iterations; ++it)
  {
    out.x = x;
    const Residual r = residual(x);
    ++out.evaluations;
    if (r.value == 0.0 || std::abs(r.value) <= options.residual_tolerance)
    {
      if (r.value == 0.0)
        out.lo = out.hi = x; // both sides' conditions hold at an exact root
      out.converged = true;
      return out;
    }
    if (r.value < 0.0)
    {
      out.lo = x;
      r_lo = r.value;
      if (side == -1)
        r_hi *= 0.5;
      side = -1;
    }
    else
    {
      out.hi = x;
      r_hi = r.value;
      if (side == 1)
        r_lo *= 0.5;
      side = 1;
    }
    const bool newton = std::isfinite(r.slope) && r.slope != 0.0;
    double next = newton ? x - r.value / r.slope : secant_point();
    const bool interpolated = next > out.lo && next < out.hi; // NaN compares false
    if (!interpolated)
      next = 0.5 * (out.lo + out.hi);
    const double tol = tolerance(next);
    if ((interpolated && std::abs(next - x) <= tol) || out.hi - out.lo <= tol
        || next <= out.lo || next >= out.hi)
    {
      out.converged = true;
      return out;
    }
    x = next;
  }
  return out;
}

} // namespace rockjoint::constitutive::root_finding
