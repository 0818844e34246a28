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

#include <memory>
#include <span>
#include <vector>

namespace rockjoint::constitutive
{

/// One evaluation of the hysteretic normal law.
struct HysteresisResponse
{
  ClosureResponse response;        ///< σ, k = ∂σ/∂Δ at fixed converged Δ_m, A/A0 (virgin only)
  bool on_virgin_curve = true;     ///< Δ >= Δ_m (or no history yet): loading on σ_v
  double maximum_closure = 0.0;    ///< trial Δ_m = max(converged Δ_m, Δ) [m]
  double permanent_closure = 0.0;  ///< Δ_p(Δ_m) of the branch in force [m]
};

/// A virgin closure law with Bandis-type unloading/reloading branches (H1-H4).
class NormalHysteresis
{
public:
  /// `virgin`: the loading curve; `permanent_fraction` r in [0, 1); `unloading_exponent` m >= 1
  /// (m = 1: straight unloading lines to Δ_p). Throws std::invalid_argument naming the bad one.
  NormalHysteresis(std::shared_ptr<const ClosureLaw> virgin, double permanent_fraction,
                   double unloading_exponent);

  /// Response at closure Δ [m] given the largest closure reached before, Δ_m [m] (>= 0; the
  /// converged history). Never throws: a NaN Δ or Δ_m gives status invalid_closure.
  HysteresisResponse evaluate(double closure, double maximum_closure) const;

  /// Closures [m] along a path of normal stresses σ_i >= 0 [Pa] (load cycles, stress-controlled
  /// as in the laboratory), starting with largest closure `maximum_closure`: above σ_v(Δ_m) the
  /// virgin inverse (and Δ_m follows), below it (H2) inverted,
  ///   Δ = Δ_p + (Δ_m - Δ_p) (σ / σ_v(Δ_m))^(1/m),  Δ <= Δ_p at σ = 0.
  /// Throws std::invalid_argument for a NaN or negative stress (naming its index).
  std::vector<double> closure_path(std::span<const double> stress,
                                   double maximum_closure = 0.0) const;

  /// Δ_p(Δ_m) = r Δ_m [m] (H1).
  double permanent_closure(double maximum_closure) const { return _r * maximum_closure; }

  const ClosureLaw& virgin() const { return *_virgin; }
  const std::shared_ptr<const ClosureLaw>& virgin_law() const { return _virgin; }
  double permanent_fraction() const { return _r; }
  double unloading_exponent() const { return _m; }
  /// The virgin law's parameters followed by r [-] and m [-].
  std::vector<Parameter> parameters() const;

private:
  std::shared_ptr<const ClosureLaw> _virgin;
  double _r;
  double _m;
};

} // namespace rockjoint::constitutive
