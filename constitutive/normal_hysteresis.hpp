// SPDX-License-Identifier: MIT
#pragma once
/// @file normal_hysteresis.hpp
/// Normal closure with history: the joint that does not spring back (docs/hysteresis.md).
///
/// Loading past the largest closure reached so far, Δ_m, follows the virgin curve σ_v(Δ) (any
/// ClosureLaw, e.g. a table of the Tang & Jiao model). Below Δ_m the joint unloads and reloads on
/// one branch set by Δ_m (Bandis et al. 1983: unloading curves lie above the virgin curve, end
/// at a permanent closure, and reloading retraces them up to the previous maximum):
///   Δ_p(Δ_m) = r Δ_m                                  permanent closure, 0 <= r < 1      (H1)
///   σ_u(Δ; Δ_m) = σ_v(Δ_m) x^m,  x = (Δ - Δ_p)/(Δ_m - Δ_p),  Δ_p < Δ < Δ_m, m >= 1     (H2)
///   σ_u = law's opening branch at Δ - Δ_p (0 for most laws) for Δ <= Δ_p (joint open).  (H3)
/// The branch meets the virgin curve at Δ_m (continuous σ) with the tangent
///   k_u(Δ_m) = m σ_v(Δ_m) / ((1 - r) Δ_m),                                            (H4)
/// so m sets how much stiffer unloading is than loading at the top of a cycle (lab: 2-4 times
/// for fresh granite joints loaded to ~10 MPa, with r = 0.2-0.3; Bandis et al. 1983). The
/// consistent tangent is ∂σ/∂Δ at the converged Δ_m (the trial Δ_m = max(converged, Δ)).

#include "closure_law.hpp"
#include "parameter_spec.hpp"

#include <memory>
#include <span>
#include <vector>

namespace rockjoint::constitutive
{

/// A virgin closure law with Bandis-type unloading/reloading branches (H1-H4): a closure law
/// with history. As a ClosureLaw without history (evaluate(Δ), closure_at_stress, a joint's
/// in-situ pre-closure) it is the virgin curve, the first loading of an untouched joint;
/// evaluate_with_history(Δ, Δ_m) adds the branches. Its key is "normal_hysteresis".
class NormalHysteresis final : public ClosureLaw
{
public:
  /// r and m, the history's own parameters (beside its virgin law's): units and ranges (H1-H2
  /// of docs/hysteresis.md), checked by the constructor.
  static const std::vector<ParameterSpec>& parameter_specs();

  /// `virgin`: the loading curve (a law without history); `permanent_fraction` r in [0, 1);
  /// `unloading_exponent` m >= 1 (m = 1: straight unloading lines to Δ_p). Throws
  /// std::invalid_argument naming the bad one.
  NormalHysteresis(std::shared_ptr<const ClosureLaw> virgin, double permanent_fraction,
                   double unloading_exponent);

  std::string name() const override { return "normal_hysteresis"; }
  /// The virgin law's parameters followed by r [-] and m [-].
  std::vector<Parameter> parameters() const override;
  bool provides_contact_area() const override { return _virgin->provides_contact_area(); }
  double maximum_closure() const override { return _virgin->maximum_closure(); }
  double seating_stress() const override { return _virgin->seating_stress(); }
  /// The virgin curve's inverse (first loading).
  double closure_at_stress(double normal_stress) const override
  {
    return _virgin->closure_at_stress(normal_stress);
  }

  bool has_history() const override { return true; }
  /// Response at closure Δ [m] given the largest closure reached before, Δ_m [m] (>= 0; the
  /// converged history): (H1-H4). Never throws: a NaN Δ or Δ_m gives status invalid_closure.
  HistoryResponse evaluate_with_history(double closure, double maximum_closure) const override;

  /// Closures [m] along a path of normal stresses σ_i >= 0 [Pa] (load cycles, stress-controlled
  /// as in the laboratory), starting with largest closure `maximum_closure`: above σ_v(Δ_m) the
  /// virgin inverse (and Δ_m follows), below it (H2) inverted,
  ///   Δ = Δ_p + (Δ_m - Δ_p) (σ / σ_v(Δ_m))^(1/m),  Δ <= Δ_p at σ = 0.
  /// Throws std::invalid_argument for a NaN or negative stress (naming its index).
  std::vector<double> closure_path(std::span<const double> stress,
                                   double maximum_closure = 0.0) const;

  /// Δ_p(Δ_m) = r Δ_m [m] (H1).
  double permanent_closure(double maximum_closure) const { return _r * maximum_closure; }

  /// The virgin (first-loading) law.
  const ClosureLaw& virgin() const { return *_virgin; }
  /// The virgin law, shared.
  const std::shared_ptr<const ClosureLaw>& virgin_law() const { return _virgin; }
  /// r [-] in [0, 1): Δ_p = r Δ_m (H1).
  double permanent_fraction() const { return _r; }
  /// m [-] > 0, exponent of the unloading branch (H2).
  double unloading_exponent() const { return _m; }

protected:
  /// First loading: the virgin curve (and its opening branch).
  ClosureResponse evaluate_contact(double closure) const override
  {
    return _virgin->evaluate(closure);
  }
  ClosureResponse evaluate_open(double closure) const override
  {
    return _virgin->evaluate(closure);
  }

private:
  std::shared_ptr<const ClosureLaw> _virgin;
  double _r;
  double _m;
};

} // namespace rockjoint::constitutive
