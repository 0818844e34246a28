// SPDX-License-Identifier: MIT
#pragma once
/// @file barton_bandis.hpp
/// Barton-Bandis hyperbolic closure law (Bandis, Lumsden & Barton 1983), theory §6.
///
///   σ = K_ni Δ / (1 - Δ/V_m),   Δ(σ) = σ V_m / (K_ni V_m + σ),
///   k = dσ/dΔ = K_ni / (1 - Δ/V_m)² = K_ni (1 + σ/(K_ni V_m))².
/// K_ni: initial normal stiffness [Pa/m]; V_m: maximum closure [m].

#include "closure_law.hpp"
#include "parameter_spec.hpp"

namespace rockjoint::constitutive
{

/// Empirical coefficients of V_m = A + B·JRC + C·(JCS/a_j)^D [mm] (JCS in MPa, a_j in mm).
/// Defaults: Barton, Bandis & Bakhtar (1985), first loading cycle of fresh joints.
struct MaximumClosureCoefficients
{
  double A = -0.1032; ///< constant term [mm]
  double B = -0.0074; ///< coefficient of JRC [mm]
  double C = 1.1350;  ///< coefficient of (JCS/a_j)^D [mm]
  double D = -0.2510; ///< exponent of JCS/a_j [-]
};

/// The Barton-Bandis hyperbola σ = K_ni Δ / (1 - Δ/V_m) [Pa] at closure Δ [m] (file comment:
/// the formulas, Bandis et al. 1983); K_ni > 0 [Pa/m] and V_m > 0 [m], std::invalid_argument
/// naming the parameter otherwise.
class BartonBandis : public ClosureLaw
{
public:
  /// @param initial_normal_stiffness K_ni [Pa/m], > 0
  /// @param maximum_closure V_m [m], > 0
  BartonBandis(double initial_normal_stiffness, double maximum_closure);

  /// Bandis et al. (1983) estimates from the joint roughness coefficient JRC [-], the joint
  /// wall compressive strength JCS [Pa] and the initial aperture a_j [m]:
  /// K_ni = -7.15 + 1.75 JRC + 0.02 JCS/a_j [MPa/mm], V_m from `coefficients` [mm].
  /// Throws if an estimate is not positive (outside the correlation's range).
  static BartonBandis from_joint_properties(double jrc, double jcs, double initial_aperture,
                                            MaximumClosureCoefficients coefficients = {});

  /// K_ni and V_m: the constructor's arguments, their units and ranges (checked there).
  static const std::vector<ParameterSpec>& parameter_specs();

  std::string name() const override { return "barton_bandis"; }
  std::vector<Parameter> parameters() const override;
  double maximum_closure() const override { return _maximum_closure; }
  /// Closed form Δ = σ V_m / (K_ni V_m + σ).
  double closure_at_stress(double normal_stress) const override;

  /// K_ni = dσ/dΔ at Δ = 0 [Pa/m].
  double initial_normal_stiffness() const { return _initial_normal_stiffness; }

protected:
  ClosureResponse evaluate_contact(double closure) const override;

private:
  double _initial_normal_stiffness;
  double _maximum_closure;
};

} // namespace rockjoint::constitutive
