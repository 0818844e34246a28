// SPDX-License-Identifier: MIT
#pragma once
/// @file hertz.hpp
/// Hertz contact of one paraboloidal asperity of radius R on a flat, theory §1.
/// The reference solution every asperity model reduces to; header-only.

#include <cmath>
#include <numbers>

namespace rockjoint::constitutive::hertz
{

/// Load P = (4/3) E* R^½ w^{3/2} [N] at interference w [m] (w <= 0: 0).
inline double load(double composite_modulus, double radius, double interference)
{
  return interference > 0.0 ? (4.0 / 3.0) * composite_modulus * std::sqrt(radius)
                                  * interference * std::sqrt(interference)
                            : 0.0;
}

/// dP/dw = 2 E* R^½ w^{1/2} [N/m].
inline double stiffness(double composite_modulus, double radius, double interference)
{
  return interference > 0.0
             ? 2.0 * composite_modulus * std::sqrt(radius) * std::sqrt(interference)
             : 0.0;
}

/// Contact radius a = √(R w) [m].
inline double contact_radius(double radius, double interference)
{
  return interference > 0.0 ? std::sqrt(radius * interference) : 0.0;
}

/// Contact area π R w [m²].
inline double contact_area(double radius, double interference)
{
  return interference > 0.0 ? std::numbers::pi * radius * interference : 0.0;
}

/// Mean contact pressure 4 E* a / (3 π R) [Pa] at contact radius a.
inline double mean_pressure(double composite_modulus, double radius, double contact_radius)
{
  return 4.0 * composite_modulus * contact_radius / (3.0 * std::numbers::pi * radius);
}

} // namespace rockjoint::constitutive::hertz
