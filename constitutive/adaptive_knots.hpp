// SPDX-License-Identifier: MIT
#pragma once
/// @file adaptive_knots.hpp
/// Adaptive knot placement for a tabulated closure law (tabulated_law.hpp): bisect the
/// intervals (at their midpoint in t = √Δ, which spaces knots geometrically near Δ = 0) until
/// the monotone Hermite interpolant of monotone_hermite.hpp matches the source law's σ and k
/// to a requested relative error.

#include "closure_law.hpp"

#include <cstddef>
#include <vector>

namespace rockjoint::constitutive
{

/// Knots found by place_knots and what the builder measured.
struct KnotPlacement
{
  std::vector<double> closure;       ///< Δ_i [m], Δ_0 = 0
  std::vector<double> normal_stress; ///< σ_i [Pa] of the source law
  /// k_i [Pa/m]: the source's tangent limited to monotone; k_0 = k(0+) (0: Hertzian onset)
  std::vector<double> stiffness;
  double checked_error_stress = 0.0;    ///< max relative σ error over all check points
  double checked_error_stiffness = 0.0; ///< max relative k error over all check points
  std::size_t law_evaluations = 0;      ///< calls of the source law
};

/// Fraction of the tolerance the error at the check points must stay under, so that the
/// bound also holds between check points (the error is a smooth low-order function of τ on
/// each interval; its peaks, τ = 1/2 for σ and τ = 1/2 ± 1/(2√3) for k, are check points).
inline constexpr double knot_safety_factor = 0.5;

/// Place knots on [0, maximum_closure] for `law`.
///
/// Onset: k(0+) is probed at Δ_p = 1e-12 Δ_max and 4Δ_p: a ratio k(Δ_p)/k(4Δ_p) within 2 %
/// of 1 is a linear onset (k(0+) = k(Δ_p)), within 2 % of 1/2 a Hertzian one (k(0+) = 0);
/// any other behaviour is refused (std::domain_error).
/// Start: 16 equal intervals in t plus knots at Δ_max·10⁻² and Δ_max·10⁻⁴. Then repeatedly
/// limit the exact slopes (Fritsch-Carlson), evaluate the relative error of σ and k against
/// the law at 7 interior points of each interval whose data changed (τ = 0.1, 0.2113, 0.35,
/// 0.5, 0.65, 0.7887, 0.9 of the interval in Δ; of the first interval in t, plus τ = 0.01,
/// 0.05 there, where the relative error of a σ ~ Δ^{3/2} onset is largest as τ → 0) and
/// bisect every interval above knot_safety_factor × tolerance.
///
/// Throws std::invalid_argument for a bad tolerance/range, std::domain_error if the law is
/// not in contact, not finite or not strictly increasing inside the range, and
/// std::runtime_error if `maximum_knots` would be exceeded (the message names the worst
/// interval and its error) or an interval narrower than 1e-9 √Δ still fails (the law has a
/// kink or noise there: more knots would only add rounding error).
KnotPlacement place_knots(const ClosureLaw& law, double maximum_closure, double tolerance,
                          std::size_t maximum_knots);

} // namespace rockjoint::constitutive
