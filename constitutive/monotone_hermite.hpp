// SPDX-License-Identifier: MIT
#pragma once
/// @file monotone_hermite.hpp
/// The interpolant of a tabulated closure law (see tabulated_law.hpp for why this form) and
/// its exact derivative. Knots (Δ_i, σ_i, k_i), Δ_0 = 0, σ_0 = 0, k_0 = k(0+).
///
/// * Segments i >= 1, [Δ_i, Δ_{i+1}]: cubic Hermite in Δ with end values σ and end slopes
///   k = dσ/dΔ; with h = Δ_{i+1} - Δ_i and τ = (Δ - Δ_i)/h ∈ [0, 1]:
///     p(τ) = c0 + c1 τ + c2 τ² + c3 τ³,  c0 = σ0, c1 = h k0,
///     c2 = 3(σ1 - σ0) - h(2 k0 + k1),    c3 = 2(σ0 - σ1) + h(k0 + k1),
///   and k = p'(τ)/h. Slopes are limited to the Fritsch-Carlson disc so σ is monotone.
/// * Segment 0, [0, Δ_1]: a quartic in t = √Δ, τ = t/t1 (t1 = √Δ_1):
///     p(τ) = c2 τ² + c3 τ³ + c4 τ⁴,  c2 = k(0+) t1²,  p(1) = σ1,  dp/dτ(1) = 2 t1² k1,
///   so k = dσ/dΔ = p'(τ)/(2 t t1) = (2c2 + 3c3 τ + 4c4 τ²)/(2 t1²), finite at Δ → 0. It
///   reproduces σ = k0 Δ (+ O(Δ²)) and σ = c Δ^{3/2} (+ O(Δ^{5/2})) to relative O(Δ1) at
///   every Δ down to 0, which no cubic in Δ does for the Hertzian Δ^{3/2} onset.
/// Header-only: the builder and the table evaluate through the same code, so the error the
/// builder checks is the error of the table that is shipped.
///
/// The same cubic segments interpolate sampled data without known slopes (the geometric
/// overlap curve of Eq. (2), a measured or computed closure curve): data_slopes gives them
/// monotone slopes from the data alone.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>

namespace rockjoint::constitutive::hermite
{

/// One segment, one cache line.
struct alignas(64) Segment
{
  double x0 = 0.0;    ///< left end Δ_i [m] (0 for the first segment)
  double inv_h = 0.0; ///< 1/(Δ_{i+1} - Δ_i) [1/m]; first segment: 1/t1 [m^-½]
  double c0 = 0.0; ///< coefficient of τ⁰ of p(τ) [Pa]
  double c1 = 0.0; ///< coefficient of τ¹ [Pa]
  double c2 = 0.0; ///< coefficient of τ² [Pa]
  double c3 = 0.0; ///< coefficient of τ³ [Pa]
  double c4 = 0.0; ///< coefficient of τ⁴ [Pa] (first segment only, in √Δ)
};

/// Cubic Hermite segment [x0, x1] in Δ from end values σ and slopes k = dσ/dΔ [Pa/m].
inline Segment make_segment(double x0, double x1, double sigma0, double sigma1, double k0,
                            double k1)
{
  Segment s;
  const double h = x1 - x0;
  s.x0 = x0;
  s.inv_h = 1.0 / h;
  s.c0 = sigma0;
  s.c1 = h * k0;
  s.c2 = 3.0 * (sigma1 - sigma0) - h * (2.0 * k0 + k1);
  s.c3 = 2.0 * (sigma0 - sigma1) + h * (k0 + k1);
  return s;
}

/// First segment [0, Δ1]: quartic in t = √Δ with k(0+) = `initial_stiffness` [Pa/m] and
/// σ(Δ1) = σ1, k(Δ1) = k1.
inline Segment make_first_segment(double closure1, double sigma1, double k1,
                                  double initial_stiffness)
{
  Segment s;
  const double t1 = std::sqrt(closure1);
  const double slope = 2.0 * t1 * t1 * k1; // dp/dτ at τ = 1
  s.inv_h = 1.0 / t1;
  s.c2 = initial_stiffness * t1 * t1;
  s.c4 = slope - 3.0 * sigma1 + s.c2;
  s.c3 = 4.0 * sigma1 - slope - 2.0 * s.c2;
  return s;
}

/// σ [Pa] and k = dσ/dΔ [Pa/m] at Δ in segment i >= 1 (cubic in Δ).
inline void evaluate(const Segment& s, double closure, double& sigma, double& stiffness)
{
  const double tau = (closure - s.x0) * s.inv_h;
  sigma = s.c0 + tau * (s.c1 + tau * (s.c2 + tau * s.c3));
  stiffness = (s.c1 + tau * (2.0 * s.c2 + tau * (3.0 * s.c3))) * s.inv_h;
}

/// σ [Pa] and k [Pa/m] at 0 < Δ <= Δ1 in the first segment (quartic in √Δ).
inline void evaluate_first(const Segment& s, double closure, double& sigma, double& stiffness)
{
  const double tau = std::sqrt(closure) * s.inv_h;
  const double q = s.c2 + tau * (s.c3 + tau * s.c4);
  sigma = tau * tau * q;
  // p'(τ)/(2 t t1) with p'(τ) = τ(2c2 + 3c3 τ + 4c4 τ²) and τ/t = 1/t1: no division by t.
  stiffness = (2.0 * s.c2 + tau * (3.0 * s.c3 + tau * (4.0 * s.c4))) * (0.5 * s.inv_h * s.inv_h);
}

/// True if the first segment is increasing: p'(τ) = τ q(τ), q = 2c2 + 3c3 τ + 4c4 τ² >= 0 on
/// [0, 1] (q(0) = 2 k(0+) t1² >= 0, q(1) = 2 t1² k1 > 0; only an interior minimum can fail).
inline bool first_segment_is_monotone(const Segment& s)
{
  if (!(s.c2 >= 0.0) || !(2.0 * s.c2 + 3.0 * s.c3 + 4.0 * s.c4 > 0.0))
    return false;
  if (s.c4 > 0.0)
  {
    const double vertex = -3.0 * s.c3 / (8.0 * s.c4);
    if (vertex > 0.0 && vertex < 1.0)
      return 2.0 * s.c2 - 9.0 * s.c3 * s.c3 / (16.0 * s.c4) >= 0.0;
  }
  return true;
}

/// Segment i of a table with knots (Δ, σ, k).
inline Segment make_table_segment(std::span<const double> closure, std::span<const double> sigma,
                                  std::span<const double> stiffness, std::size_t i)
{
  return i == 0 ? make_first_segment(closure[1], sigma[1], stiffness[1], stiffness[0])
                : make_segment(closure[i], closure[i + 1], sigma[i], sigma[i + 1], stiffness[i],
                               stiffness[i + 1]);
}

/// Fritsch & Carlson (1980) limiting on every interval but the first (the quartic, checked
/// by first_segment_is_monotone): with secant δ = Δσ/ΔΔ > 0, scale the end slopes so that
/// (α, β) = (k0/δ, k1/δ) lies in the disc α² + β² <= 9, a sufficient condition for a
/// monotone cubic; a slope shared by two intervals ends with the smaller limited value
/// (shrinking a slope keeps the other interval inside the disc). Slopes must be >= 0 and
/// the data strictly increasing.
inline void limit_slopes(std::span<const double> closure, std::span<const double> sigma,
                         std::span<double> stiffness)
{
  for (std::size_t i = 1; i + 1 < closure.size(); ++i)
  {
    const double delta = (sigma[i + 1] - sigma[i]) / (closure[i + 1] - closure[i]);
    const double a = stiffness[i] / delta, b = stiffness[i + 1] / delta;
    const double r2 = a * a + b * b;
    if (r2 > 9.0)
    {
      // A little inside the circle so that rounding cannot put p' below zero.
      const double scale = 3.0 * (1.0 - 1e-14) / std::sqrt(r2);
      stiffness[i] = a * scale * delta;
      stiffness[i + 1] = b * scale * delta;
    }
  }
}

/// True if an interval (i >= 1) satisfies the condition limit_slopes enforces (δ > 0,
/// slopes >= 0, α² + β² <= 9 up to rounding).
inline bool is_monotone(double x0, double x1, double sigma0, double sigma1, double k0, double k1)
{
  if (!(x1 > x0) || !(sigma1 > sigma0) || !(k0 >= 0.0) || !(k1 >= 0.0))
    return false;
  const double delta = (sigma1 - sigma0) / (x1 - x0);
  const double a = k0 / delta, b = k1 / delta;
  return a * a + b * b <= 9.0 * (1.0 + 1e-12);
}

/// Monotone C¹ slopes for non-decreasing data (x_i, y_i) without known derivatives: the
/// PCHIP of Fritsch & Carlson (1980) as given by Moler — weighted harmonic means of the
/// adjacent secants inside (Fritsch & Butland 1984; zero at a plateau or an extremum) and
/// shape-preserving three-point formulas at the ends. With them make_segment gives a
/// monotone interpolant that is exact on plateaus. x strictly increasing, n >= 2.
inline void data_slopes(std::span<const double> x, std::span<const double> y,
                        std::span<double> slopes)
{
  const std::size_t n = x.size();
  auto secant = [&](std::size_t i) { return (y[i + 1] - y[i]) / (x[i + 1] - x[i]); };
  std::fill(slopes.begin(), slopes.end(), 0.0);
  if (n == 2)
  {
    slopes[0] = slopes[1] = secant(0);
    return;
  }
  for (std::size_t i = 1; i + 1 < n; ++i)
  {
    const double d0 = secant(i - 1), d1 = secant(i);
    if (d0 > 0.0 && d1 > 0.0)
    {
      const double h0 = x[i] - x[i - 1], h1 = x[i + 1] - x[i];
      const double w1 = 2.0 * h1 + h0, w2 = h1 + 2.0 * h0;
      slopes[i] = (w1 + w2) / (w1 / d0 + w2 / d1);
    }
  }
  auto end_slope = [](double h0, double h1, double d0, double d1)
  {
    double m = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if (m < 0.0 || d0 == 0.0)
      m = 0.0;
    return std::min(m, 3.0 * d0);
  };
  slopes[0] = end_slope(x[1] - x[0], x[2] - x[1], secant(0), secant(1));
  slopes[n - 1]
      = end_slope(x[n - 1] - x[n - 2], x[n - 2] - x[n - 3], secant(n - 2), secant(n - 3));
}

} // namespace rockjoint::constitutive::hermite
