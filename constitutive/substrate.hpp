// SPDX-License-Identifier: MIT
#pragma once
/// @file substrate.hpp
/// Substrate deformation under one asperity (theory §4; Tang et al. 2014, the g of Eq. (6)
/// of Tang & Jiao 2018).
///
/// An asperity of radius β pressed by a total approach w [m] deforms partly as a Hertz
/// contact (approach g) and partly as the half-space under its base, a disk of radius r0
/// loaded by the Hertz load P = (4/3) E* β^½ g^{3/2}: w_s = c_s P/(E* r0) with c_s = 2/π
/// (uniform pressure, centre), 16/(3π²) (uniform pressure, mean) or 1/2 (rigid punch).
/// E* cancels and, with κ_s = (4/3) c_s,
///
///     w = g + κ_s √β g^{3/2} / r0.
///
/// With t = √g and the substrate compliance c = κ_s √β / r0 [m^-½] this is the cubic
/// c t³ + t² - w = 0, which has exactly one positive root for w > 0. κ_s = 0 (c = 0) is
/// plain Hertz/GW, g = w. Note that the base term partly overlaps the Hertz far field.
///
/// The functions are scale-free: any consistent length unit works (e.g. lengths in units
/// of σ_s with c√σ_s in place of c).

#include <numbers>

namespace rockjoint::constitutive::substrate
{

/// κ_s for a uniform load on the base disk, deflection at its centre: 8/(3π) (default).
inline constexpr double centre_deflection = 8.0 / (3.0 * std::numbers::pi);
/// κ_s for a uniform load on the base disk, mean deflection over it: 64/(9π²).
inline constexpr double mean_deflection = 64.0 / (9.0 * std::numbers::pi * std::numbers::pi);
/// κ_s for a rigid base disk: 2/3.
inline constexpr double rigid_base = 2.0 / 3.0;

/// The reduction factor τ(q) = t/√w in (0, 1]: the positive root of q τ³ + τ² = 1 with
/// q = c √w >= 0 (the cubic divided by w^{3/2}). τ(0) = 1, τ ≈ q^{-1/3} for q >> 1.
/// Two Halley steps and one Newton step from the upper bound (1+q)^{-1/3} (within 5.5 %
/// of the root for every q): accurate to rounding (tested against long-double bisection for
/// q = c √w over c = 0..1e8 m^-½, w = 1e-20..1 m).
/// q must be finite and >= 0 (q = +inf gives 0).
double reduction_factor(double q);

/// Hertz part of the approach of one asperity.
struct HertzApproach
{
  double root = 0.0;       ///< t = √g [m^½]
  double hertz_part = 0.0; ///< g = t² [m]
  double derivative = 0.0; ///< dg/dw = 1/(1 + 1.5 c √g) [-] (1 when c = 0)
};

/// g(w) and dg/dw for total approach w [m] and compliance c = κ_s √β/r0 [m^-½] (>= 0);
/// c = 0 returns g = w exactly.
/// w <= 0: zero (no contact).
HertzApproach hertz_approach(double total_approach, double compliance);

/// t_a³ - t_b³ without cancellation, for two roots t_a >= t_b >= 0 of the cubic whose
/// approaches differ by w_a - w_b = `approach_difference` >= 0 (known exactly, e.g. a
/// closure): subtracting the cubics, (t_a - t_b)[c(t_a² + t_a t_b + t_b²) + t_a + t_b] =
/// w_a - w_b. Used for the seated stress σ(d0 - Δ) - σ(d0) at tiny closures.
double cube_difference(double root_a, double root_b, double compliance, double approach_difference);

} // namespace rockjoint::constitutive::substrate
