// SPDX-License-Identifier: MIT
#include "interaction_cell.hpp"
#include "validation.hpp"

#include <gsl/gsl_sf_ellint.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace rockjoint::constitutive::interaction_cell
{

namespace
{
constexpr double pi = std::numbers::pi;

/// √(1-s²) without cancellation near s = 1.
double cosine(double s) { return std::sqrt((1.0 - s) * (1.0 + s)); }
} // namespace

double interaction_fraction(double s)
{
  if (!(s >= 0.0 && s <= 1.0))
    return std::numeric_limits<double>::quiet_NaN();
  if (s < 0.5)
  {
    // d/ds [arcsin s - s√(1-s²)] = 2s²/√(1-s²) = 2 Σ c_n s^{2n+2}, c_n = (2n)!/(4^n n!²):
    // integrate term by term. Terms fall like s² <= 1/4, so <= 30 terms reach 1e-17.
    const double s2 = s * s;
    double c = 1.0, power = s2 * s, sum = 0.0;
    for (int n = 0; n < 60; ++n)
    {
      const double term = c * power / (2 * n + 3);
      sum += term;
      if (term <= 1e-18 * sum)
        break;
      c *= (2.0 * n + 1.0) / (2.0 * n + 2.0);
      power *= s2;
    }
    return (4.0 / pi) * sum;
  }
  // No cancellation for s >= 1/2: 1-Q >= 0.1.
  return (2.0 / pi) * (std::asin(s) - s * cosine(s));
}

double load_fraction(double s)
{
  if (!(s >= 0.0 && s <= 1.0))
    return std::numeric_limits<double>::quiet_NaN();
  // Both terms are small and positive near s = 1: the direct form keeps relative accuracy.
  return s < 0.5 ? 1.0 - interaction_fraction(s) : (2.0 / pi) * (std::acos(s) + s * cosine(s));
}

double load_fraction_derivative(double s)
{
  return -(4.0 / pi) * s * s / cosine(s);
}

double effective_contact_radius(double radius, double summit_height_std)
{
  return 0.75 * std::sqrt(pi * radius * summit_height_std);
}

double annulus_half_chord(double contact_radius, double area_root)
{
  return contact_radius * cosine(area_root) / area_root;
}

double closure_shift(double nominal_stress, double composite_modulus, double contact_radius,
                     double area_root)
{
  if (area_root <= 0.0)
    return 0.0;
  return 2.0 * nominal_stress / composite_modulus
         * annulus_half_chord(contact_radius, area_root);
}

Cell::Cell(double composite_modulus, double radius, double contact_radius, double area_root)
    : _modulus(validation::positive("interaction_cell::Cell", "composite_modulus",
                                    composite_modulus, "Pa")),
      _radius(validation::positive("interaction_cell::Cell", "radius", radius, "m")),
      _a(validation::positive("interaction_cell::Cell", "contact_radius", contact_radius,
                              "m")),
      _s(validation::in_range("interaction_cell::Cell", "area_root", area_root, "", 0.0,
                              1.0)),
      _b(contact_radius / area_root)
{
}

double Cell::hertz_mean_pressure() const
{
  return 4.0 * _modulus * _a / (3.0 * pi * _radius);
}

double Cell::mean_pressure() const
{
  return hertz_mean_pressure() * _s * _s / load_fraction(_s);
}

double Cell::local_approach() const
{
  return _a * _a / _radius - closure_shift();
}

double Cell::closure_shift() const
{
  return interaction_cell::closure_shift(mean_pressure(), _modulus, _a, _s);
}

double Cell::hertz_load() const
{
  return (4.0 / 3.0) * _modulus * _a * _a * _a / _radius;
}

double Cell::interaction_load() const
{
  // 2p̄ [b² arcsin s - a√(b²-a²)] = 2p̄ b² [arcsin s - s√(1-s²)] = π b² p̄ (1-Q(s)).
  return pi * _b * _b * mean_pressure() * interaction_fraction(_s);
}

double Cell::pressure(double r) const
{
  r = std::abs(r);
  if (r >= _a)
    return 0.0;
  const double w2 = (_a - r) * (_a + r); // a² - r²
  const double c = annulus_half_chord(_a, _s);
  return 2.0 * _modulus / (pi * _radius) * std::sqrt(w2)
         + (2.0 * mean_pressure() / pi) * std::atan(std::sqrt(w2) / c);
}

double Cell::territory_displacement(double r) const
{
  r = std::abs(r);
  const double scale = 4.0 * mean_pressure() / (pi * _modulus);
  if (r == _b) // E(1) = 1; GSL rejects k = 1
    return scale * _b;
  if (r < _b)
    return scale * _b * gsl_sf_ellint_Ecomp(r / _b, GSL_PREC_DOUBLE);
  const double k = _b / r;
  return scale * r
         * (gsl_sf_ellint_Ecomp(k, GSL_PREC_DOUBLE)
            - (1.0 - k * k) * gsl_sf_ellint_Kcomp(k, GSL_PREC_DOUBLE));
}

} // namespace rockjoint::constitutive::interaction_cell
