// SPDX-License-Identifier: MIT
#pragma once
/// @file tang_substrate.hpp
/// GW with substrate deformation under each asperity (Tang et al. 2014; the f3 of Eq. (7)
/// and the g of Eq. (6) of Tang & Jiao 2018; theory §4).
///
/// Each summit at total approach w = z - d carries (4/3) E* β^½ g(w)^{3/2}, where g solves
/// w = g + κ_s √β g^{3/2} / r0 (substrate.hpp). Per unit nominal area:
///     f3(d)   = (4/3) E* η β^½ ∫_d^∞ g^{3/2} f dz
///     k       = 2 E* η β^½ ∫_d^∞ g^{1/2} (dg/dw) f dz,   dg/dw = 1/(1 + 1.5 c √g)
///     A/A0    = π η β ∫_d^∞ g f dz,   d(A/A0)/dΔ = π η β ∫_d^∞ (dg/dw) f dz,
/// c = κ_s √β / r0 (per summit, c_i = κ_s √β_i / r0, for an empirical list). κ_s = 0 gives
/// GreenwoodWilliamson exactly (same code path and closed forms). Seating convention and
/// reference (computed with this substrate law): summit_population_law.hpp.
///
/// Choices: κ_s defaults to 8/(3π) (uniform load on the base, centre deflection); r0, the
/// base radius, is not given by the paper and defaults to half the summit spacing,
/// r0 = 1/(2√η). The base term partly overlaps the Hertz far field of each contact.
/// All integrals use the quadrature of GreenwoodWilliamson (z = d + u², adaptive GK61).

#include "substrate.hpp"
#include "summit_population_law.hpp"

#include <optional>

namespace rockjoint::constitutive
{

/// Substrate parameters of the Tang law.
struct SubstrateParameters
{
  /// κ_s [-], finite and >= 0: substrate::centre_deflection (8/(3π), default),
  /// substrate::mean_deflection (64/(9π²)) or substrate::rigid_base (2/3); 0 gives GW.
  double deflection_coefficient = substrate::centre_deflection;
  /// r0 [m], finite and > 0; empty: 1/(2√η), half the mean summit spacing.
  std::optional<double> base_radius;
};

/// Tang substrate-corrected GW law (f3).
class TangSubstrate : public SummitPopulationLaw
{
public:
  /// Parametric distribution; see GreenwoodWilliamson for the common arguments.
  TangSubstrate(const AsperityParameters& parameters,
                HeightDistribution distribution = HeightDistribution::gaussian,
                const SubstrateParameters& substrate = {},
                const SeatingReference& reference = SeatingReference::automatic(),
                double quadrature_tolerance = default_quadrature_tolerance);

  /// Empirical list of summits (each with its own radius and c_i = κ_s √β_i / r0).
  TangSubstrate(double composite_modulus, EmpiricalSummits summits,
                const SubstrateParameters& substrate = {},
                const SeatingReference& reference = SeatingReference::automatic());

  std::string name() const override { return "tang_substrate"; }
  std::vector<Parameter> parameters() const override;

  /// κ_s [-].
  double deflection_coefficient() const { return substrate_deflection_coefficient(); }
  /// r0 [m] (the default 1/(2√η) resolved).
  double base_radius() const { return substrate_base_radius(); }
};

} // namespace rockjoint::constitutive
