// SPDX-License-Identifier: MIT
#include "summit_heights.hpp"
#include "validation.hpp"

#include <gsl/gsl_sf_erf.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>

namespace rockjoint::constitutive
{

const char* to_string(HeightDistribution distribution)
{
  switch (distribution)
  {
  case HeightDistribution::gaussian: return "gaussian";
  case HeightDistribution::exponential: return "exponential";
  case HeightDistribution::empirical: return "empirical";
  }
  return "unknown";
}

namespace summit_heights
{

double standard_density(HeightDistribution distribution, double s)
{
  constexpr double inv_sqrt_2pi = 0.5 * std::numbers::inv_sqrtpi * std::numbers::sqrt2;
  switch (distribution)
  {
  case HeightDistribution::gaussian: return inv_sqrt_2pi * std::exp(-0.5 * s * s);
  case HeightDistribution::exponential: return s >= 0.0 ? std::exp(-s) : 0.0;
  case HeightDistribution::empirical: break;
  }
  return 0.0;
}

double standard_mean(HeightDistribution distribution)
{
  return distribution == HeightDistribution::exponential ? 1.0 : 0.0;
}

double lower_cut(HeightDistribution distribution)
{
  return distribution == HeightDistribution::exponential ? 0.0 : -9.5;
}

double window_length(HeightDistribution distribution)
{
  return distribution == HeightDistribution::exponential ? 45.0 : 9.5;
}

double gaussian_survival(double h) { return 0.5 * std::erfc(h * std::numbers::sqrt2 * 0.5); }

double gaussian_first_moment(double h)
{
  const double phi = standard_density(HeightDistribution::gaussian, h);
  // φ(h) - h Q(h) loses ~log10(h²) digits to cancellation (φ - hQ ≈ φ/h²): harmless up to
  // h = 4 (16 ulp).
  if (h <= 4.0)
    return phi - h * gaussian_survival(h);
  // Laplace's continued fraction of the Mills ratio R = Q/φ = 1/(h + 1/(h + 2/(h + ...))).
  // With X = h + 2/(h + 3/(h + ...)), 1/R - h = 1/X, so φ - hQ = φ R (1/R - h) = φ R / X:
  // no subtraction. 50 terms converge to < 2e-16 for h >= 4 (checked against 40-digit
  // arithmetic).
  double x = h;
  for (int n = 50; n >= 2; --n)
    x = h + n / x;
  const double mills = 1.0 / (h + 1.0 / x);
  return phi * mills / x;
}

PartialMoments exponential_partial_moments(double h)
{
  constexpr double sqrt_pi = 1.0 / std::numbers::inv_sqrtpi;
  if (h >= 0.0)
  {
    const double e = std::exp(-h);
    return {e, 0.5 * sqrt_pi * e, e, 0.75 * sqrt_pi * e};
  }
  const double a = -h;
  const double ra = std::sqrt(a);
  // E(a) = e^a erfc(√a) ~ 1/√(πa): direct below a = 30 (e^30 ~ 1e13, erfc(5.5) ~ 7e-15, both
  // accurate); above, through log erfc, whose absolute error ~ε a enters M_{3/2} with weight
  // ~a^{-2}.
  const double scaled_erfc
      = a < 30.0 ? std::exp(a) * std::erfc(ra) : std::exp(a + gsl_sf_log_erfc(ra));
  return {1.0, ra + 0.5 * sqrt_pi * scaled_erfc, 1.0 + a,
          a * ra + 1.5 * ra + 0.75 * sqrt_pi * scaled_erfc};
}

} // namespace summit_heights

EmpiricalSummits::EmpiricalSummits(std::vector<double> heights, std::vector<double> radii,
                                   double area)
    : _area(validation::positive("EmpiricalSummits", "area", area, "m^2"))
{
  const std::string owner = "EmpiricalSummits";
  if (heights.empty())
    throw std::invalid_argument(owner
                                + ": parameter 'heights' is empty; it must list at "
                                  "least one summit height [m]");
  if (radii.size() != heights.size())
    throw std::invalid_argument(owner + ": parameter 'radii' has " + std::to_string(radii.size())
                                + " entries; it must have one per height ("
                                + std::to_string(heights.size()) + ")");
  for (std::size_t i = 0; i < heights.size(); ++i)
  {
    validation::finite(owner, "heights[" + std::to_string(i) + "]", heights[i], "m");
    validation::positive(owner, "radii[" + std::to_string(i) + "]", radii[i], "m");
  }

  // Sort by decreasing height (stable: equal heights keep their order).
  std::vector<std::size_t> order(heights.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return heights[a] > heights[b]; });
  _heights.reserve(order.size());
  _radii.reserve(order.size());
  _sqrt_radii.reserve(order.size());
  for (std::size_t i : order)
  {
    _heights.push_back(heights[i]);
    _radii.push_back(radii[i]);
    _sqrt_radii.push_back(std::sqrt(radii[i]));
  }

  const double n = static_cast<double>(size());
  _mean_radius = std::accumulate(_radii.begin(), _radii.end(), 0.0) / n;
  _mean_height = std::accumulate(_heights.begin(), _heights.end(), 0.0) / n;
  double ss = 0.0;
  for (double z : _heights)
    ss += (z - _mean_height) * (z - _mean_height);
  _height_std = std::sqrt(ss / n);
}

std::size_t EmpiricalSummits::count_above(double separation) const
{
  // Heights are decreasing: the first position whose height is <= d.
  auto it = std::partition_point(_heights.begin(), _heights.end(),
                                 [separation](double z) { return z > separation; });
  return static_cast<std::size_t>(it - _heights.begin());
}

} // namespace rockjoint::constitutive
