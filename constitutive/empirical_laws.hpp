// SPDX-License-Identifier: MIT
#pragma once
/// @file empirical_laws.hpp
/// Logarithmic and exponential empirical closure laws, theory §6.

#include "closure_law.hpp"
#include "parameter_spec.hpp"

namespace rockjoint::constitutive
{

/// Logarithmic law (Swan 1983; the GW-exponential closed form): Δ = B ln(σ_t/σ0), where
/// σ_t is the total stress and σ0 the seating stress at Δ = 0. Returned: the stress in
/// excess of seating, σ = σ0 (e^{Δ/B} - 1), k = σ0 e^{Δ/B} / B = (σ + σ0)/B, so σ(0) = 0.
class LogarithmicLaw : public ClosureLaw
{
public:
  /// @param closure_scale B [m], > 0
  /// @param seating_stress σ0 [Pa], > 0
  LogarithmicLaw(double closure_scale, double seating_stress);
  /// B and σ0: the constructor's arguments, their units and ranges (checked there).
  static const std::vector<ParameterSpec>& parameter_specs();
  std::string name() const override { return "logarithmic"; }
  std::vector<Parameter> parameters() const override;
  double seating_stress() const override { return _seating_stress; }
  /// Closed form Δ = B ln(1 + σ/σ0).
  double closure_at_stress(double normal_stress) const override;

protected:
  ClosureResponse evaluate_contact(double closure) const override;

private:
  double _closure_scale;
  double _seating_stress;
};

/// Exponential law (Malama & Kulatilake 2003 style): Δ = V_m (1 - exp(-σ/σ_c)), so
/// σ = -σ_c ln(1 - Δ/V_m), k = σ_c / (V_m - Δ).
class ExponentialLaw : public ClosureLaw
{
public:
  /// @param maximum_closure V_m [m], > 0
  /// @param characteristic_stress σ_c [Pa], > 0
  ExponentialLaw(double maximum_closure, double characteristic_stress);
  /// V_m and σ_c: the constructor's arguments, their units and ranges (checked there).
  static const std::vector<ParameterSpec>& parameter_specs();
  std::string name() const override { return "exponential"; }
  std::vector<Parameter> parameters() const override;
  double maximum_closure() const override { return _maximum_closure; }
  /// Closed form Δ = V_m (1 - exp(-σ/σ_c)).
  double closure_at_stress(double normal_stress) const override;

protected:
  ClosureResponse evaluate_contact(double closure) const override;

private:
  double _maximum_closure;
  double _characteristic_stress;
};

} // namespace rockjoint::constitutive
