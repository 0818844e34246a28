// SPDX-License-Identifier: MIT
#pragma once
/// @file exact_law.hpp
/// "The exact elastic law of this joint": a boundary-element closure curve (elastic_contact.hpp)
/// turned into a TabulatedLaw that the FE coupling uses like any table.
#include "elastic_contact.hpp"

#include <rockjoint/constitutive/tabulated_law.hpp>

#include <span>

namespace rockjoint::contact
{

/// Description of the contact problem a curve came from (recorded in the table's header).
struct ContactSource
{
  double composite_modulus; ///< E* [Pa]
  double spacing;           ///< grid step h [m] (max of the two directions)
  double rows; ///< grid rows
  double cols; ///< grid columns
  Kernel kernel; ///< periodic or non-periodic half-space
  double tolerance; ///< solver tolerance of the curve
};

/// Monotone C¹ table through (0, 0) and the (closure, σ) points of `curve` (increasing σ):
/// cubic Hermite segments with the data slopes of monotone_hermite.hpp (PCHIP), limited to the
/// Fritsch-Carlson disc; the first segment is the table's quartic in √Δ with k(0+) =
/// `initial_stiffness` [Pa/m] (default 0: contact starts at one summit, a Hertzian onset; a
/// positive seating stiffness, at most the first secant σ1/Δ1, changes σ below the first load
/// only, and gives a FE model's first linearisation at zero closure a stiffness). The tangent is the exact derivative of that
/// interpolant. Beyond the last point the table's linear continuation applies (status
/// validity_limit), below 0 its opening branch with `residual_stiffness` [Pa/m] (NaN: the
/// default 1e-6 σ_max/Δ_max). Throws std::invalid_argument if a state did not converge or the
/// closures are not strictly increasing (names the offending load).
constitutive::TabulatedLaw exact_elastic_law(std::span<const ContactState> curve,
                                             const ContactSource& source,
                                             double residual_stiffness,
                                             double initial_stiffness = 0.0);

} // namespace rockjoint::contact
