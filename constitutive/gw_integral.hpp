// SPDX-License-Identifier: MIT
#pragma once
/// @file gw_integral.hpp
/// The Greenwood-Williamson integrals of a parametric summit population (theory §2), with
/// Tang's substrate correction (theory §4) when μ > 0.
///
/// Lengths are in units of σ_s: standardised summit heights s = z/σ_s with density p(s)
/// (summit_heights.hpp), separation h = d/σ_s, approach w = s - h of a summit. Each summit
/// carries the Hertz load of its Hertz approach g(w), the positive root of the substrate
/// cubic μ t³ + t² = w with t = √g and μ = κ_s √(β σ_s)/r0 (g = w when μ = 0: plain GW).
/// Per unit nominal area, up to the dimensional scales the law applies:
///   stress    ∫_h^∞ g(s-h)^{3/2} p(s) ds    (σ: × (4/3) E* η β^½ σ_s^{3/2})
///   stiffness ∫_h^∞ g^{1/2} g'(s-h) p(s) ds (k = dσ/dΔ: × 2 E* η β^½ σ_s^{1/2})
///   area      ∫_h^∞ g(s-h) p(s) ds          (A/A0: × π η β σ_s)
///   rate      ∫_h^∞ g'(s-h) p(s) ds         (d(A/A0)/dΔ: × π η β)
/// Closed forms where they exist (plain GW: exponential all four, Gaussian area and rate);
/// otherwise adaptive quadrature with the u² substitution at the (z-d)^{1/2} endpoint
/// (population_quadrature.hpp). Seated (h_ref finite): the stress is the increase from the
/// seating separation h_ref to h = h_ref - δ, formed without cancellation.

#include "summit_heights.hpp"

namespace rockjoint::constitutive::gw
{

/// The four dimensionless integrals and whether every quadrature met its tolerance.
struct Moments
{
  double stress = 0;    ///< ∫_h^∞ g^{3/2} p ds [-] (file comment: its scale)
  double stiffness = 0; ///< ∫_h^∞ g^{1/2} g' p ds [-]
  double area = 0;      ///< ∫_h^∞ g p ds [-]
  double rate = 0;      ///< ∫_h^∞ g' p ds [-]
  bool converged = true; ///< every quadrature met its tolerance
};

/// The integrals at h for height distribution `dist` and substrate parameter `mu` (0: GW);
/// seated at h_ref when finite (then δ = h_ref - h exactly, passed to avoid cancellation);
/// `tol` is the relative quadrature tolerance.
Moments population_moments(HeightDistribution dist, double mu, double h, double h_ref,
                           double delta, double tol);

} // namespace rockjoint::constitutive::gw
