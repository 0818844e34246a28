// SPDX-License-Identifier: MIT
#pragma once
/// @file summit_heights.hpp
/// Summit-height distributions f(z) of the composite topography (theory §2).
///
/// Parametric shapes are written in the standardised height s = z/σ_s (σ_s [m] the standard
/// deviation of summit heights), f(z) dz = p(s) ds:
///  - Gaussian:    p(s) = φ(s) = e^{-s²/2}/√(2π), mean 0 (the classic GW surface);
///  - exponential: p(s) = e^{-s} for s >= 0, mean 1 (f = e^{-z/σ_s}/σ_s, z >= 0).
/// An empirical distribution is a list of measured summits (height z_i, radius β_i) over a
/// scanned area A0: the GW integrals become sums over summits, each with its own radius.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace rockjoint::constitutive
{

/// Which summit-height distribution an asperity law integrates over.
enum class HeightDistribution : int
{
  gaussian = 0,    ///< p(s) = φ(s), mean 0
  exponential = 1, ///< p(s) = e^{-s}, s >= 0, mean 1
  empirical = 2,   ///< a list of measured summits (EmpiricalSummits)
};

/// "gaussian", "exponential" or "empirical".
const char* to_string(HeightDistribution distribution);

namespace summit_heights
{
/// Standardised density p(s) of a parametric distribution [-] (not for `empirical`).
double standard_density(HeightDistribution distribution, double s);

/// Mean of the standardised height s [-]: 0 (Gaussian) or 1 (exponential).
double standard_mean(HeightDistribution distribution);

/// Lower end of the region the quadrature integrates over [-]: 0 for the exponential (its
/// support starts there); -9.5 for the Gaussian, whose mass below it, Q(9.5) ≈ 1e-21, is
/// negligible against any integrand of O(1) that reaches down there.
double lower_cut(HeightDistribution distribution);

/// Length L of the integration window above max(lower end, mode = 0) [-]. The neglected tail
/// must stay far below the finest relative tolerance (1.2e-14):
///  - Gaussian, L = 9.5: beyond the window the density has fallen by
///    φ(h+L)/φ(h) = e^{-hL - L²/2} <= e^{-45}; with the weight (s-h)^{3/2} <= 30 and, for
///    h > 0, an integral ≈ φ(h) Γ(5/2) h^{-5/2}, the relative tail is < 1e-20 for every h;
///  - exponential, L = 45: relative tail <= e^{-L} (L+1)^{3/2} / Γ(5/2) ≈ 7e-18.
double window_length(HeightDistribution distribution);

/// Gaussian survival function Q(h) = ∫_h^∞ φ(s) ds (accurate in the upper tail).
double gaussian_survival(double h);

/// Gaussian partial first moment ∫_h^∞ (s-h) φ(s) ds = φ(h) - h Q(h), evaluated without
/// the cancellation of that form for large h (continued fractions of Laplace for h > 4).
double gaussian_first_moment(double h);

/// Partial moments M_n(h) = ∫_h^∞ (s-h)^n p(s) ds of a standardised density [-].
struct PartialMoments
{
  double order0 = 0.0;   ///< M_0: fraction of summits above h
  double order1_2 = 0.0; ///< M_{1/2}: the GW stiffness integral
  double order1 = 0.0;   ///< M_1: the GW area integral
  double order3_2 = 0.0; ///< M_{3/2}: the GW stress integral
};

/// Closed-form partial moments of the exponential density p = e^{-s}, s >= 0 (exact):
/// h >= 0: M_n = Γ(n+1) e^{-h}; h < 0, a = -h: M_n = e^{a} Γ(n+1, a), i.e.
/// M_0 = 1, M_1 = 1 + a, M_{1/2} = √a + (√π/2) E(a), M_{3/2} = a^{3/2} + (3/2)√a + (3√π/4) E(a)
/// with E(a) = e^{a} erfc(√a) evaluated without overflow.
PartialMoments exponential_partial_moments(double h);
} // namespace summit_heights

/// A measured list of summits: heights z_i [m] (any datum), radii of curvature β_i [m] and the
/// scanned nominal area A0 [m²]. Validated at construction; stored sorted by decreasing
/// height so that the summits in contact at a separation are a prefix.
/// Derived statistics: η = N/A0, β = mean radius, σ_s = standard deviation of the heights
/// (0 for a single summit: a list may describe one asperity, e.g. to reproduce Hertz).
class EmpiricalSummits
{
public:
  /// @param heights summit heights z_i [m], finite, at least one
  /// @param radii summit radii β_i [m], finite and > 0, one per height
  /// @param area scanned nominal area A0 [m²], finite and > 0
  /// @throws std::invalid_argument naming the offending entry
  EmpiricalSummits(std::vector<double> heights, std::vector<double> radii, double area);

  /// Number of summits.
  std::size_t size() const { return _heights.size(); }
  /// Heights [m], sorted decreasing.
  std::span<const double> heights() const { return _heights; }
  /// Radii [m], in the order of heights().
  std::span<const double> radii() const { return _radii; }
  /// √β_i [m^½], in the order of heights().
  std::span<const double> sqrt_radii() const { return _sqrt_radii; }
  /// A0 [m²].
  double area() const { return _area; }
  /// η = N/A0 [1/m²].
  double summit_density() const { return static_cast<double>(size()) / _area; }
  /// Mean radius β [m].
  double mean_radius() const { return _mean_radius; }
  /// Mean height [m].
  double mean_height() const { return _mean_height; }
  /// Standard deviation of the heights σ_s [m] (population form, 1/N).
  double height_std() const { return _height_std; }
  /// Highest summit [m]: the separation of first contact.
  double highest() const { return _heights.front(); }
  /// Number of summits strictly above the separation d [m] (those in contact).
  std::size_t count_above(double separation) const;

private:
  std::vector<double> _heights, _radii, _sqrt_radii;
  double _area, _mean_radius, _mean_height, _height_std;
};

} // namespace rockjoint::constitutive
