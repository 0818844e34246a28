// SPDX-License-Identifier: MIT
#pragma once
/// @file tang_jiao.hpp
/// The self-consistent model with asperity interaction of Tang & Jiao (IJRMMS 2018,
/// doi 10.1016/j.ijrmms.2017.10.009), theory §5, composed over any base closure law f3.
///
/// Equations (numbers of the paper):
///   - Eq. (1): effective contact radius a = (3/4) √(π R σ_s), R the representative radius
///     (project choice R = β, the mean summit radius), σ_s the summit-height std;
///   - Eq. (2): territory radius b from (a/b)² = A/A0, s = a/b = √(A/A0);
///   - Eq. (3): p̄ π b² = P (self-consistency); Eqs. (4)-(5): Boussinesq displacements of the
///     cell, solved in closed form in interaction_cell.hpp (numerically, as in the paper's
///     Fig. 2, in interaction_cell_numeric.hpp);
///   - Eq. (6): f3, the base law's nominal stress (Tang's substrate-corrected GW, plain GW, an
///     empirical summit list, ...);
///   - Eq. (7): F = f2 + f3.
///
/// Reading of Eq. (7) (theory §5). Taken literally, f2 is a displacement (π E* times the
/// Boussinesq integral of Eq. (5)) and cannot be added to a stress, and the excerpt of the
/// paper does not say how F and the closure are obtained from the cell. The two variants
/// below are the project's dimensionally consistent readings, not the paper's words: F is
/// the nominal stress of the joint; the added term is the interaction part of the cell's
/// nominal stress, P_int/(π b²) = (1 - Q(s)) F, with Q(s) = (2/π)[arccos s + s√(1-s²)] the
/// Hertz fraction of the cell load. Hence
///
///   - variant I1 ("stress interaction", default; the project's reading of Eq. (7) that
///     follows the paper's iteration most directly): the closure drives the base law and
///     the area of Eq. (2) directly (ξ = Δ) and the interaction changes the stress only:
///     F(Δ) = σ_model(Δ)/Q(s(Δ)) - σ_seat/Q(s0), where σ_model = f3 + σ_seat is the base
///     model's stress (f3 the seated stress the base law returns, σ_seat its
///     seating_stress()) and s0 the area root at Δ = 0+. Subtracting the cell's own stress
///     at the seating state (not σ_seat/Q(s)) keeps F(0) = 0 with one cell relation for the
///     whole stress, so the law changes with the seating datum only by a shift of Δ and σ.
///     With σ_seat = 0 (an empirical summit list seated at its highest summit) F = f3/Q.
///     The paper's p̄ iteration is the contraction F_model ← σ_model + (1-Q) F_model, whose
///     fixed point σ_model/Q this is. A/A0 reported: the base law's elastic area (the
///     Eq. (2) area when the base has none), i.e. the interaction changes the stress, not
///     the contact area.
///   - variant I2 ("kinematic"): the internal closure ξ drives the base law and the area of
///     Eq. (2), and the interaction also lifts each contact's surroundings: the observed
///     closure is Δ = ξ - ε(ξ) with ε = (2F/E*)√(b²-a²), the p̄ term of the finite-fringe
///     local approach, F the seated I1 stress above (so ε(0) = 0: ε is the lift produced by
///     the load added since seating; the lift of the seating load itself is part of the
///     datum, and it is infinite for a base with a seating stress but no area at Δ = 0).
///     The law is F at the observed closure Δ = ξ - ε(ξ), parametric in the internal closure
///     ξ; Δ → ξ is inverted by a bracketed, safeguarded Newton solve; the tangent is
///     dF/dξ / (1 - dε/dξ), the area rate dA/dξ / (1 - dε/dξ). Monotone only while
///     dε/dξ < 1: the law stops (validity limit) where dε/dξ reaches maximum_shift_rate
///     (default 0.9, so the tangent is amplified at most 10×). When s = 0 (no contact
///     area, b = ∞) ε is taken as 0. I2 needs ε = o(ξ) at first contact: over a base whose
///     stress is linear in ξ while its area vanishes at ξ = 0 (e.g. an empirical law with the
///     geometric overlap curve), ε ~ F/s ~ √ξ and dε/dξ → ∞, so there is no monotone
///     branch: the constructor throws. GW-type bases with a seating reference (A/A0 > 0 at
///     Δ = 0) are fine; over the GW-exponential base dε/dξ ≈ (3/4)s stays below 0.4.
///   Both variants give F → f3 as s → 0 (1 - Q ≈ 4s³/(3π), evaluated by its series, so the
///   limit is exact), hence F → GW when also κ_s = 0 in the base.
///   Magnitude: at A/A0 ~ 1 % (s = 0.1) the I1 correction 1/Q - 1 ≈ 4.2e-4, so at
///   A/A0 ~ 1 % the I1 correction is below 1 %; it reaches 1 % near A/A0 ≈ 8 %, 1.4 % at
///   A/A0 = 10 % and 22 % at A/A0 = 50 %.
///
/// Area source for Eq. (2) [project choice]: the base law's elastic contact area (default;
/// the base must then provide one, else std::invalid_argument), or the purely geometric
/// overlap fraction{e <= Δ} of the aperture field (theory §3), given as monotone samples
/// (Δ_i, ratio_i) with Δ_0 = 0 and interpolated by a monotone piecewise-cubic Hermite
/// (Fritsch-Carlson) curve: C¹, so the tangent stays analytic; beyond the last sample it is
/// continued linearly with the end slope. With a geometric curve any base law works.
///
/// Validity limit. As A/A0 → 1, Q → 0 and F → ∞: the cell model leaves its domain. The area
/// root is capped at s_max = maximum_area_root (default 0.99): maximum_closure() is the
/// closure where s = s_max (found once at construction by a bracketed solve; +inf if the
/// area never reaches s_max²), or, for I2, the observed closure of the first of (s = s_max,
/// dε/dξ = maximum_shift_rate; located on a log grid of 60 points a decade over the 12 decades
/// below the area limit, then bisected: an excursion narrower than the grid could be
/// missed). At and beyond it evaluate() returns Status::validity_limit
/// with the response frozen at the limit (finite, never inf/NaN) and closure_at_stress()
/// throws std::domain_error naming the limit. A base law with its own closure limit (e.g.
/// V_m) passes its status through beyond it.
///
/// f3 is the stress the base law returns (in excess of its seating stress, which TangJiao
/// reports unchanged as its own seating_stress()).
///
/// Units: SI (Pa, m). Parameters are validated once, at construction.

#include "asperity_parameters.hpp"
#include "closure_law.hpp"
#include "monotone_hermite.hpp"

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rockjoint::constitutive
{

/// Which reading of Eq. (7) (see the file comment).
enum class TangJiaoVariant : int
{
  /// I1, the project's stress reading of Eq. (7) (default): F = σ_model/Q(s) - σ_seat/Q(s0),
  /// closure unchanged.
  stress_interaction = 1,
  /// Former name of stress_interaction; it is the project's reading, not the paper's words.
  as_published [[deprecated("use TangJiaoVariant::stress_interaction")]] = 1,
  kinematic = 2, ///< I2: F at Δ = ξ - ε(ξ), ε = (2F/E*)√(b²-a²)
};

/// What sets maximum_closure() of a TangJiao law.
enum class TangJiaoLimit : int
{
  none = 0,               ///< no limit found: maximum_closure() = +inf
  area_root = 1,          ///< s = √(A/A0) reached maximum_area_root
  closure_shift_rate = 2, ///< I2: dε/dξ reached maximum_shift_rate (loss of monotonicity)
  base_law = 3,           ///< the base law's own maximum closure comes first
};

/// Monotone C¹ interpolant of the geometric overlap ratio fraction{e <= Δ} (theory §3),
/// the optional area source of Eq. (2).
class OverlapCurve
{
public:
  /// @param closure Δ_i [m], strictly increasing, Δ_0 = 0, at least 2 samples, finite
  /// @param area_ratio ratio_i [-] in [0, 1], non-decreasing, finite
  OverlapCurve(std::vector<double> closure, std::vector<double> area_ratio);
  /// Ratio and its derivative d(ratio)/dΔ [1/m] at Δ >= 0.
  void evaluate(double closure, double& area_ratio, double& area_rate) const;
  /// Samples Δ_i [m].
  const std::vector<double>& closure() const { return _x; }
  /// Samples of the overlap ratio [-].
  const std::vector<double>& area_ratio() const { return _y; }

private:
  std::vector<double> _x, _y;
  std::vector<hermite::Segment> _segments; // monotone cubic Hermite (monotone_hermite.hpp)
  double _end_slope = 0.0;                 // slope of the linear continuation past Δ_{n-1}
};

/// Options of the Tang & Jiao law.
struct TangJiaoOptions
{
  /// Reading of Eq. (7).
  TangJiaoVariant variant = TangJiaoVariant::stress_interaction;
  /// Geometric overlap samples for Eq. (2): closures Δ_i [m] (empty: the base law's elastic
  /// contact area) ...
  std::vector<double> overlap_closure = {};
  /// ... and the matching ratios fraction{e <= Δ_i} [-].
  std::vector<double> overlap_area_ratio = {};
  /// s_max, cap on s = √(A/A0), in (0, 1).
  double maximum_area_root = 0.99;
  /// I2 only: limit on dε/dξ, in (0, 1).
  double maximum_shift_rate = 0.9;
};

/// Tang & Jiao (2018) self-consistent interaction over a base law f3.
class TangJiao : public ClosureLaw
{
public:
  /// @param base f3, any closure law (not null); it must provide a contact area unless a
  ///        geometric overlap curve is given in `options`
  /// @param composite_modulus E* [Pa], 1/E* = Σ (1-ν²)/E (not E/(1-ν²)), > 0
  /// @param radius R [m] of the representative asperity (project choice: β), > 0
  /// @param summit_height_std σ_s [m] of Eq. (1), > 0
  /// @param options variant, optional overlap curve and validity caps (TangJiaoOptions)
  /// @throws std::invalid_argument naming the parameter
  TangJiao(std::shared_ptr<const ClosureLaw> base, double composite_modulus, double radius,
           double summit_height_std, TangJiaoOptions options = {});

  /// Convenience: E*, R = β and σ_s from base->asperity_parameters().
  explicit TangJiao(std::shared_ptr<const AsperityLaw> base, TangJiaoOptions options = {});

  std::string name() const override;
  std::vector<Parameter> parameters() const override;
  bool provides_contact_area() const override { return true; }
  double maximum_closure() const override { return _maximum_closure; }
  /// Cell stress at Δ = 0 [Pa]: σ_seat/Q(s0), σ_seat the base law's seating stress and s0
  /// the Eq. (2) area root there (equal to σ_seat when s0 = 0).
  double seating_stress() const override
  {
    return _base_seating_stress / _seating_load_fraction;
  }
  /// s0 = √(A/A0) of Eq. (2) at Δ = 0+ (the seating state) [-].
  double seating_area_root() const { return _seating_area_root; }
  /// Δ(σ) [m]; std::domain_error naming the validity limit if σ exceeds the stress there.
  double closure_at_stress(double normal_stress) const override;

  /// The base law f3.
  const ClosureLaw& base() const { return *_base; }
  /// Reading of Eq. (7): I1 or I2.
  TangJiaoVariant variant() const { return _options.variant; }
  /// What sets maximum_closure().
  TangJiaoLimit limit() const { return _limit; }
  /// Human-readable description of the limit (for messages and reports).
  std::string limit_description() const;
  /// Internal closure ξ [m] at the limit (= maximum_closure() for I1).
  double maximum_internal_closure() const { return _maximum_internal; }
  /// Eq. (1): a [m].
  double contact_radius() const { return _contact_radius; }

  /// The cell state at internal closure ξ > 0 [m] (for I1 ξ is the closure). Diagnostic:
  /// not capped, so past the validity limit s may exceed s_max (F = +inf once s >= 1).
  struct State
  {
    double base_stress = 0.0;        ///< f3 [Pa]
    double base_stiffness = 0.0;     ///< df3/dξ [Pa/m]
    double area_ratio = 0.0;         ///< A/A0 feeding Eq. (2) [-]
    double area_rate = 0.0;          ///< d(A/A0)/dξ [1/m]
    double area_root = 0.0;          ///< s [-]
    double load_fraction = 1.0;      ///< Q(s) [-]
    double normal_stress = 0.0;      ///< F = f3/Q [Pa]
    double normal_stiffness = 0.0;   ///< dF/dξ [Pa/m]
    double closure_shift = 0.0;      ///< ε [m] (computed for both variants)
    double closure_shift_rate = 0.0; ///< dε/dξ [-]
    double reported_area_ratio = 0.0; ///< A/A0 the law reports [-]
    double reported_area_rate = 0.0;  ///< its derivative [1/m]
    Status status = Status::contact;  ///< the base law's status at ξ
  };
  /// The cell's State at internal closure ξ [m] (diagnostics).
  State state(double internal_closure) const;

  /// I2: internal closure ξ [m] at an observed closure 0 < Δ < maximum_closure() [m].
  double internal_closure(double closure) const;

protected:
  ClosureResponse evaluate_contact(double closure) const override;

private:
  void locate_limit();
  /// I2: the internal closure ξ for an observed closure Δ and the state there (I1: Δ).
  std::pair<double, State> solve_internal(double closure) const;
  ClosureResponse response(const State& st) const;

  std::shared_ptr<const ClosureLaw> _base;
  double _composite_modulus, _radius, _summit_height_std;
  TangJiaoOptions _options;
  std::optional<OverlapCurve> _overlap;
  double _contact_radius;
  double _base_seating_stress = 0.0;   // σ_seat of the base law [Pa]
  double _seating_area_root = 0.0;     // s0 [-]
  double _seating_load_fraction = 1.0; // Q(s0) [-]
  double _seating_amplification = 0.0; // g(s0) = 1/Q(s0) - 1 [-]
  double _maximum_internal;
  double _maximum_closure;
  TangJiaoLimit _limit = TangJiaoLimit::none;
  ClosureResponse _limit_response;
};

} // namespace rockjoint::constitutive
