// SPDX-License-Identifier: MIT
#pragma once
/// @file greenwood_williamson.hpp
/// Greenwood-Williamson (1966) contact of a population of Hertzian summits (theory §2).
///
/// Per unit nominal area, at separation d = d0 - Δ of the reference planes:
///     σ_GW(d) = (4/3) E* η β^½ ∫_d^∞ (z-d)^{3/2} f(z) dz
///     k       = 2 E* η β^½ ∫_d^∞ (z-d)^{1/2} f(z) dz          (= dσ/dΔ, analytic)
///     A/A0    = π η β ∫_d^∞ (z-d) f(z) dz,   d(A/A0)/dΔ = π η β ∫_d^∞ f(z) dz.
/// The law returns σ(Δ) = σ_GW(d0 - Δ) - σ_GW(d0) (seating convention and reference choices:
/// summit_population_law.hpp). maximum_closure() = +∞.
///
/// Evaluation: exact closed forms where they exist — exponential heights (all integrals,
/// summit_heights::exponential_partial_moments), Gaussian area φ(h) - hQ(h) and rate Q(h);
/// Gaussian σ and k by adaptive Gauss-Kronrod after the substitution z = d + u² (which
/// removes the (z-d)^{1/2} endpoint behaviour), to `quadrature_tolerance` relative, over the
/// window where the density is not negligible (summit_heights::window_length); an empirical
/// list is an exact sum over its summits, each with its own radius.

#include "summit_population_law.hpp"

namespace rockjoint::constitutive
{

/// GW law on a Gaussian, exponential or empirical summit-height distribution.
class GreenwoodWilliamson : public SummitPopulationLaw
{
public:
  /// Parametric distribution.
  /// @param parameters E* [Pa], η [1/m²], β [m], σ_s [m], all finite and > 0
  /// @param distribution gaussian or exponential
  /// @param reference seating reference (default: d0 = mean summit height + 3.5 σ_s)
  /// @param quadrature_tolerance relative tolerance of the height quadrature, in (0, 1)
  ///        (values below 1.2e-14 act as 1.2e-14, GSL's floor)
  /// @throws std::invalid_argument naming the parameter
  GreenwoodWilliamson(const AsperityParameters& parameters,
                      HeightDistribution distribution = HeightDistribution::gaussian,
                      const SeatingReference& reference = SeatingReference::automatic(),
                      double quadrature_tolerance = default_quadrature_tolerance);

  /// Empirical list of summits (η = N/A0, β = mean radius, σ_s = std of heights; each summit
  /// keeps its own radius). Default reference: the highest summit (first contact).
  /// @param composite_modulus E* [Pa], finite and > 0
  /// @param summits the summits' heights [m], radii [m] and the scanned area [m²]
  /// @param reference seating reference (default: the highest summit)
  /// @throws std::invalid_argument naming the parameter
  GreenwoodWilliamson(double composite_modulus, EmpiricalSummits summits,
                      const SeatingReference& reference = SeatingReference::automatic());

  std::string name() const override { return "greenwood_williamson"; }
};

} // namespace rockjoint::constitutive
