// SPDX-License-Identifier: MIT
#pragma once
/// @file summit_population_law.hpp
/// The common machinery of the GW-type laws (theory §2, §4): a population of Hertzian
/// summits with a height distribution, an optional substrate compliance (Tang), the seating
/// convention and the reference separation. GreenwoodWilliamson and TangSubstrate are thin
/// named front ends of this class.
///
/// Seating convention (project rule: every law is continuous at Δ = 0). The separation of
/// the reference planes is d = d0 - Δ, with d0 the reference (seating) separation. The law
/// returns the stress in excess of seating,
///     σ(Δ) = σ_model(d0 - Δ) - σ_model(d0),   seating_stress() = σ_model(d0),
/// and k = k_model(d0 - Δ), A/A0 = A_model(d0 - Δ), contact_area_rate = d(A/A0)/dΔ.
/// The difference is evaluated without cancellation (the per-summit loads are subtracted
/// inside the integral, see substrate::cube_difference), so σ keeps full relative accuracy
/// down to Δ = 1e-15 m and Δ(σ(Δ)) = Δ holds to 1e-10 there (tested).
///
/// Evaluation never throws. Parametric distributions are integrated by
/// population_quadrature.hpp (GK61 after z = d + u², CQUAD fallback); if neither rule meets
/// the tolerance (not observed for these smooth integrands) the best estimate is returned
/// with status contact, as Status has no value for it.
///
/// Reference separation d0 (SeatingReference):
///  - automatic (default): mean summit height + 3.5 σ_s, i.e. d0 = 3.5 σ_s (Gaussian, mean 0)
///    and 4.5 σ_s (exponential, mean σ_s); for an empirical list, the highest summit (exact
///    first contact, seating stress 0). (The theory §7 example test fixes its own d0.)
///  - a separation d0 [m] given directly;
///  - a seating stress σ_seat [Pa]: d0 solves σ_model(d0) = σ_seat (computed with the law's
///    own model, substrate included).

#include "asperity_parameters.hpp"
#include "summit_heights.hpp"

#include <optional>
#include <string>
#include <vector>

namespace rockjoint::constitutive
{

/// How the reference (seating) separation d0 of a GW-type law is chosen.
struct SeatingReference
{
  /// How d0 is given.
  enum class Kind : int
  {
    automatic = 0,  ///< mean summit height + 3.5 σ_s; highest summit of an empirical list
    separation = 1, ///< d0 [m] given
    stress = 2,     ///< σ_model(d0) = σ_seat [Pa] given
  };
  Kind kind = Kind::automatic; ///< how d0 is chosen
  double value = 0.0; ///< d0 [m] or σ_seat [Pa]; unused for automatic

  /// d0 = mean summit height + 3.5 σ_s (the default).
  static SeatingReference automatic() { return {}; }
  /// d0 [m], finite (in the height datum of the distribution: mean 0 Gaussian, etc.).
  static SeatingReference at_separation(double reference_separation)
  {
    return {Kind::separation, reference_separation};
  }
  /// σ_seat [Pa], finite and > 0.
  static SeatingReference at_stress(double seating_stress)
  {
    return {Kind::stress, seating_stress};
  }
};

/// Default relative tolerance of the height quadrature.
inline constexpr double default_quadrature_tolerance = 1e-10;

/// A population of Hertzian summits, optionally on a compliant substrate (theory §4):
/// each summit at total approach w = z - d carries (4/3) E* β^½ g^{3/2} with
/// w = g + c g^{3/2}, c = κ_s √β / r0 (c = 0: GW). Per unit nominal area,
///     σ_model(d) = (4/3) E* η β^½ ∫_d^∞ g^{3/2} f dz,
///     k(d)       = 2 E* η β^½ ∫_d^∞ g^{1/2} (dg/dw) f dz,
///     A/A0(d)    = π η β ∫_d^∞ g f dz,   d(A/A0)/dΔ = π η β ∫_d^∞ (dg/dw) f dz;
/// for an empirical list, η f dz -> (1/A0) Σ_i and β -> β_i (per-summit radius and c_i).
class SummitPopulationLaw : public AsperityLaw
{
public:
  AsperityParameters asperity_parameters() const override { return _parameters; }
  double seating_stress() const override { return _seating_stress; }
  std::vector<Parameter> parameters() const override;

  /// Reference separation d0 [m] (in the height datum of the distribution).
  double reference_separation() const { return _reference_separation; }
  /// The summit-height distribution.
  HeightDistribution distribution() const { return _distribution; }
  /// The measured summits, or nullptr for a parametric distribution.
  const EmpiricalSummits* empirical_summits() const { return _summits ? &*_summits : nullptr; }
  /// Relative tolerance of the height quadrature [-].
  double quadrature_tolerance() const { return _tolerance; }

  /// Diagnostic: true if every height integral at closure Δ [m] met quadrature_tolerance()
  /// (always true for closed forms and empirical lists). evaluate() never reports it: the
  /// best estimate is returned with status contact either way.
  bool quadrature_converged(double closure) const;

  /// Un-seated model response at separation d [m]: σ_model(d) [Pa], k(d) [Pa/m],
  /// A/A0(d) [-], d(A/A0)/dΔ [1/m]; status contact, or open if no summit touches.
  ClosureResponse response_at_separation(double separation) const;

protected:
  /// Parametric distribution (Gaussian or exponential) with statistics `parameters`.
  /// Substrate: κ_s = deflection_coefficient (0: GW) and r0 = base_radius (empty:
  /// 1/(2√η)); the substrate compliance of a summit of radius β is c = κ_s √β / r0.
  SummitPopulationLaw(const std::string& owner, const AsperityParameters& parameters,
                      HeightDistribution distribution, double deflection_coefficient,
                      std::optional<double> base_radius, const SeatingReference& reference,
                      double quadrature_tolerance);
  /// Empirical list of summits; η, β, σ_s derived from it.
  SummitPopulationLaw(const std::string& owner, double composite_modulus, EmpiricalSummits summits,
                      double deflection_coefficient, std::optional<double> base_radius,
                      const SeatingReference& reference, double quadrature_tolerance);

  /// κ_s [-].
  double substrate_deflection_coefficient() const { return _deflection_coefficient; }
  /// r0 [m] (default resolved).
  double substrate_base_radius() const { return _base_radius; }

  ClosureResponse evaluate_contact(double closure) const override;

private:
  /// Empirical sums at closure Δ from d_ref (seated) or, if !seated, at separation d.
  ClosureResponse empirical_response(double separation, bool seated, double closure) const;
  /// Response of the parametric population at h = d/σ_s (seated at h_ref when finite, δ =
  /// Δ/σ_s): the GW integrals of gw_integral.hpp times this law's scales.
  ClosureResponse parametric_response(double h, double h_ref, double delta) const;
  void set_reference(const std::string& owner, const SeatingReference& reference);
  void check_common(const std::string& owner, std::optional<double> base_radius);

  AsperityParameters _parameters;
  HeightDistribution _distribution;
  std::optional<EmpiricalSummits> _summits;
  double _deflection_coefficient;  // κ_s [-]
  double _base_radius = 0.0;       // r0 [m]
  double _compliance_factor = 0.0; // κ_s / r0 [1/m]
  double _tolerance;
  double _reference_separation = 0.0;
  double _seating_stress = 0.0;
  // Parametric scales: (4/3)E*ηβ^½σ_s^{3/2}, 2E*ηβ^½σ_s^{1/2}, πηβσ_s, πηβ, and the
  // dimensionless substrate compliance μ = c √σ_s.
  double _stress_scale = 0, _stiffness_scale = 0, _area_scale = 0, _rate_scale = 0, _mu = 0;
};

} // namespace rockjoint::constitutive
