// SPDX-License-Identifier: MIT
#pragma once
/// @file closure_law.hpp
/// The interface every normal-closure law of a rough rock joint implements.
///
/// Conventions (docs/theory.md §0): SI units (Pa, m); compression positive; the closure
/// Δ [m] is the relative normal approach of the two walls *net of the intact rock's own
/// deformation*. Δ <= 0 is an open joint: σ = 0, k = 0, A/A0 = 0, never NaN (a law may
/// instead document a residual stiffness there: TabulatedLaw, for FE use). Every law is
/// continuous at Δ = 0 (σ(0) = 0); laws whose model carries a seating stress return the
/// stress in excess of it (see seating_stress()).

#include <limits>
#include <span>
#include <string>
#include <vector>

namespace rockjoint::constitutive
{

/// What one evaluation of a law found. A status, not an exception: laws are called in FE
/// hot loops (MGIS practice).
enum class Status : int
{
  contact = 0,          ///< Δ > 0 inside the law's domain
  open = 1,             ///< Δ <= 0: joint open, zero response
  validity_limit = 2,   ///< the model's validity limit was passed; response frozen at the limit
  beyond_maximum_closure = 3, ///< Δ >= maximum closure (e.g. V_m): σ, k = +inf
  invalid_closure = 4,  ///< Δ is NaN: response is NaN
  quadrature_not_converged = 5, ///< an integral missed its tolerance: best estimate returned
};

/// Human-readable name of a status.
const char* to_string(Status status);

/// Response of a closure law at one closure.
struct ClosureResponse
{
  double normal_stress = 0.0;      ///< σ [Pa], compression positive
  double normal_stiffness = 0.0;   ///< k = dσ/dΔ [Pa/m] (consistent, analytic)
  double contact_area_ratio = 0.0; ///< A/A0 [-] (0 for laws without an area model)
  double contact_area_rate = 0.0;  ///< d(A/A0)/dΔ [1/m]
  Status status = Status::open; ///< where Δ lies: contact, open, past a limit (Status)
};

/// Response of a law at Δ given the largest closure Δ_m reached before: the history a joint
/// point keeps (JointPointState::maximum_closure). For a law without history it is the loading
/// curve and Δ_m simply follows; a law with history (NormalHysteresis) unloads and reloads on
/// branches set by Δ_m.
struct HistoryResponse
{
  ClosureResponse response;        ///< σ, k = ∂σ/∂Δ at the fixed converged Δ_m, A/A0
  bool on_virgin_curve = true;     ///< Δ >= Δ_m (or no history yet): loading
  double maximum_closure = 0.0;    ///< trial Δ_m = max(converged Δ_m, Δ) [m]
  double permanent_closure = 0.0;  ///< Δ_p(Δ_m) of the branch in force (0 without history) [m]
};

/// A named parameter of a law, for self-describing output (tables, reports).
struct Parameter
{
  std::string name; ///< parameter name, e.g. "maximum_closure"
  double value; ///< value in the SI unit `unit`
  std::string unit; ///< SI unit, e.g. "m", "Pa", "Pa/m", "-"
};

/// Normal-closure law σ(Δ) of a rough joint.
///
/// Implementations override evaluate_contact() (called only for finite Δ > 0) and describe
/// themselves. Parameters are validated once, in constructors.
class ClosureLaw
{
public:
  virtual ~ClosureLaw() = default;

  /// Short model name, e.g. "barton_bandis".
  virtual std::string name() const = 0;

  /// All parameters with SI units.
  virtual std::vector<Parameter> parameters() const = 0;

  /// True if contact_area_ratio is a model output (GW-type laws); false for empirical laws.
  virtual bool provides_contact_area() const { return false; }

  /// Supremum of admissible closures [m]: V_m for hyperbolic laws, the validity limit of
  /// a self-consistent model, +inf otherwise.
  virtual double maximum_closure() const
  {
    return std::numeric_limits<double>::infinity();
  }

  /// Stress the underlying model carries at Δ = 0 [Pa] (subtracted so that σ(0) = 0).
  virtual double seating_stress() const { return 0.0; }

  /// Response at one closure Δ [m]. Handles Δ <= 0 (open) and NaN; never throws. For a law
  /// with history: first loading of an untouched joint (its virgin curve).
  ClosureResponse evaluate(double closure) const;

  /// True if the response depends on the largest closure reached (NormalHysteresis): the FE
  /// joint then keeps Δ_m per point and calls evaluate_with_history.
  virtual bool has_history() const { return false; }

  /// Response at Δ [m] after a largest closure Δ_m [m] (>= 0, the converged history). Default
  /// (no history): evaluate(Δ), with Δ_m = max(Δ_m, Δ) and no permanent closure. Never throws:
  /// a NaN Δ or Δ_m gives status invalid_closure.
  virtual HistoryResponse evaluate_with_history(double closure, double maximum_closure) const;

  /// Batch evaluation. Output spans must have the size of `closure`; `area_ratio` and
  /// `status` may be empty (not written).
  void evaluate(std::span<const double> closure, std::span<double> normal_stress,
                std::span<double> normal_stiffness, std::span<double> area_ratio = {},
                std::span<Status> status = {}) const;

  /// σ(Δ) [Pa].
  double normal_stress(double closure) const { return evaluate(closure).normal_stress; }
  /// k(Δ) = dσ/dΔ [Pa/m].
  double normal_stiffness(double closure) const
  {
    return evaluate(closure).normal_stiffness;
  }
  /// A/A0(Δ) [-].
  double contact_area_ratio(double closure) const
  {
    return evaluate(closure).contact_area_ratio;
  }

  /// Inverse Δ(σ) [m] for σ >= 0 [Pa]. Default: bracket by doubling (capped below
  /// maximum_closure()), then safeguarded Newton (bisection whenever Newton leaves the
  /// bracket) to |δΔ| <= 1e-15 Δ. Throws std::invalid_argument for NaN/negative σ and
  /// std::domain_error if σ is beyond the law's admissible range.
  virtual double closure_at_stress(double normal_stress) const;

protected:
  /// Response for Δ > 0 (possibly +inf). Must not throw; a law with a finite
  /// maximum_closure() handles Δ >= maximum_closure() itself (status
  /// beyond_maximum_closure or validity_limit).
  virtual ClosureResponse evaluate_contact(double closure) const = 0;

  /// Response for Δ <= 0 (open joint). Default: the library's convention σ = k = 0. A law
  /// may document a residual stiffness instead (TabulatedLaw: σ = k_res Δ, k = k_res).
  virtual ClosureResponse evaluate_open(double /*closure*/) const { return {}; }

  /// Throw std::invalid_argument (naming the law) unless a target stress of closure_at_stress
  /// is finite and >= 0.
  void check_target_stress(double normal_stress) const;

  /// Throw std::invalid_argument unless the output spans of a batch evaluate() have the size
  /// of `closure` (`area_ratio` and `status` may be empty). `who` names the caller.
  static void check_batch_sizes(const char* who, std::span<const double> closure,
                                std::span<double> normal_stress,
                                std::span<double> normal_stiffness, std::span<double> area_ratio,
                                std::span<Status> status);

  /// The response for Δ at or past a hard closure limit: σ = k = +inf.
  static ClosureResponse beyond_maximum_closure(double contact_area_ratio = 0.0);
};

} // namespace rockjoint::constitutive
