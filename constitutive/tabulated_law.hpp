// SPDX-License-Identifier: MIT
#pragma once
/// @file tabulated_law.hpp
/// A closure law tabulated once from any ClosureLaw, with error control: the fast form a
/// finite-element code calls at every interface point in every Newton iteration (theory §8).
///
/// **Interpolant** (monotone_hermite.hpp). Knots (Δ_i, σ_i, k_i) hold the source law's σ
/// and its exact tangent k. Between knots, σ is the cubic Hermite polynomial in Δ with those
/// end values and end slopes (σ errs by O(h⁴), k by O(h³): knots ∝ tolerance^{-1/3}), the
/// slopes limited to the Fritsch-Carlson disc α² + β² <= 9 (Fritsch & Carlson 1980) so that
/// σ is monotone; the limiter rarely acts once the knots are fine. The tangent returned is the
/// exact derivative of the interpolant, so Newton's quadratic convergence is kept (tested).
/// σ(0) = 0; σ strictly increasing and k > 0 for 0 < Δ <= Δ_max (k(0+) = 0 for a Δ^{3/2}
/// onset, as the source).
///
/// **Near Δ = 0.** The laws of this library start like σ ~ k0 Δ (seating-subtracted laws:
/// Barton-Bandis, logarithmic, Gaussian GW) or σ ~ c Δ^{3/2} (Hertzian onset: GW-type laws
/// with a highest summit, k(0+) = 0). A cubic in Δ on [0, Δ1] has a fixed, non-vanishing
/// relative error for Δ^{3/2} however small Δ1 is. So the first segment is a quartic in
/// t = √Δ, A t² + B t³ + C t⁴, with A = k(0+) of the source (probed at Δ = 1e-12 Δ_max:
/// k ≈ constant → linear onset, A = k; k ∝ Δ^{1/2} → Hertzian, A = 0; anything else is
/// refused) and B, C matching σ1 and k1: it reproduces the leading term of either onset
/// exactly, so the relative errors of σ AND k stay O(Δ1) down to Δ = 0 with the exact knot
/// σ(0) = 0, without a dense log grid. Knots are placed by bisection in t, which spaces them
/// geometrically in Δ near 0. Only this segment needs a square root; the others cost a
/// cubic and no division.
///
/// **Knots** (adaptive_knots.hpp): bisection in t until the relative error of σ and of k
/// against the source, checked at 7 interior points per interval (9 on the first), is below
/// half the requested tolerance; capped by maximum_knots, and refused with a clear error
/// where the source is not smooth enough (kinks of an empirical summit list, noise).
/// Typical sizes (bench/results/tabulation.md): 300-500 knots, ~40 KiB at 1e-6.
///
/// **Beyond the table.**
/// * Compression, Δ > Δ_max: linear continuation with the end tangent,
///   σ = σ_max + k_max (Δ - Δ_max), k = k_max: σ and k continuous (C¹), k > 0, status
///   `validity_limit` (the response is no longer the source law's; the table's range is its
///   validity limit). The source law usually stiffens faster (k grows with σ), so the
///   extension is softer than the physics: choose Δ_max / σ_max to cover the scene.
/// * Opening, Δ <= 0: σ = k_res Δ (a tensile-like penalty), k = k_res, status `open`, with
///   the residual stiffness k_res >= 0 (default 1e-6 × the secant stiffness σ_max / Δ_max),
///   so a block held only by an open joint never makes the FE matrix singular. σ is
///   continuous at Δ = 0; k jumps there from k_res to k(0+), as the contact law's own
///   tangent does (Barton-Bandis: from 0 to K_ni). k_res = 0 gives the library's strict
///   convention σ = 0, k = 0.
///
/// **The one documented deviation from ClosureLaw.** The opening branch carries k_res instead
/// of the strict σ = k = 0, through the ClosureLaw::evaluate_open hook, so it is the same
/// whether the table is called as a TabulatedLaw or through a `const ClosureLaw&`.
/// TabulatedLaw::evaluate (single point and batch) re-implements the dispatch inline only to
/// skip the virtual calls in the hot path; it gives identical results (tested).
///
/// **Speed.** One point costs an O(1) index lookup (a uniform grid over Δ whose cells are at
/// most half the smallest knot spacing, up to 16 cells per segment, so a cell meets at most
/// two segments and the choice is branch-free; a bisection only in cells that still hold
/// several knots) and a cubic with its derivative from one 64-byte segment (plus a square
/// root on the first segment). No allocation; the object is immutable after construction
/// and safe to share between threads.

#include "closure_law.hpp"
#include "law_table_file.hpp"
#include "monotone_hermite.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace rockjoint::constitutive
{

/// Any ClosureLaw tabulated with error control on a monotone C¹ Hermite interpolant (the
/// file comment: knots, error bound, extensions); what the finite-element assembly evaluates.
/// Built by up_to_stress()/over_closure_range() or read by load() (std::runtime_error naming
/// the file, line and field of a malformed table).
class TabulatedLaw : public ClosureLaw
{
public:
  /// How to build a table.
  struct Options
  {
    /// Maximum relative error of σ and of k against the source law [-], in [1e-13, 0.1].
    double tolerance = 1e-6;
    /// Knot budget; exceeding it is an error (runaway guard).
    std::size_t maximum_knots = 20000;
    /// k_res [Pa/m] of the opening branch; NaN selects the default 1e-6 σ_max/Δ_max;
    /// 0 selects the strict convention σ = k = 0 for Δ <= 0.
    double residual_stiffness = std::numeric_limits<double>::quiet_NaN();
  };

  /// Default k_res as a fraction of the secant stiffness σ_max / Δ_max.
  static constexpr double default_residual_stiffness_fraction = 1e-6;

  /// Tabulate `law` over closures [0, maximum_closure] [m]; maximum_closure must be below
  /// law.maximum_closure(). Throws std::invalid_argument (bad options/range),
  /// std::domain_error (law not tabulable there), std::runtime_error (knot budget).
  static TabulatedLaw over_closure_range(const ClosureLaw& law, double maximum_closure,
                                         const Options& options);
  /// over_closure_range() with the default Options.
  static TabulatedLaw over_closure_range(const ClosureLaw& law, double maximum_closure)
  {
    return over_closure_range(law, maximum_closure, Options{});
  }

  /// Tabulate `law` up to the normal stress `maximum_stress` [Pa]:
  /// Δ_max = law.closure_at_stress(maximum_stress). Throws std::domain_error naming σ_max if
  /// it lies beyond the law's admissible range.
  static TabulatedLaw up_to_stress(const ClosureLaw& law, double maximum_stress,
                                   const Options& options);
  /// up_to_stress() with the default Options.
  static TabulatedLaw up_to_stress(const ClosureLaw& law, double maximum_stress)
  {
    return up_to_stress(law, maximum_stress, Options{});
  }

  /// A table from its data (validated: validate_law_table).
  explicit TabulatedLaw(LawTable table);

  /// Read a table file (law_table_file.hpp); errors name the file, line and field.
  static TabulatedLaw load(const std::string& path);
  /// Write the table (bit-exact: load(path) evaluates identically).
  void save(const std::string& path) const;

  std::string name() const override { return "tabulated"; }
  /// The table's own settings, then the source's parameters prefixed "source.".
  std::vector<Parameter> parameters() const override;
  /// The source law's seating stress [Pa] (σ of the table is in excess of it, like the source).
  double seating_stress() const override { return _table.source_seating_stress; }
  /// Inverse of the interpolant (and of the linear extension beyond Δ_max): safeguarded
  /// Newton on the segment that brackets σ. σ must be finite and >= 0.
  double closure_at_stress(double normal_stress) const override;

  /// Response at Δ [m], with the residual stiffness for Δ <= 0 (see the file comment).
  inline ClosureResponse evaluate(double closure) const;

  /// Batch form of evaluate(double) (k_res included). Output spans must have the size of
  /// `closure`; `area_ratio` (always 0: no area model) and `status` may be empty.
  void evaluate(std::span<const double> closure, std::span<double> normal_stress,
                std::span<double> normal_stiffness, std::span<double> area_ratio = {},
                std::span<Status> status = {}) const;

  /// The defining data (knots, provenance).
  const LawTable& table() const { return _table; }
  /// Last knot Δ_max [m] and σ_max [Pa], and the end tangent k_max [Pa/m].
  double table_maximum_closure() const { return _closure_max; }
  /// σ_max [Pa] at the last knot.
  double table_maximum_stress() const { return _stress_max; }
  /// k [Pa/m] at the last knot: the slope of the linear extension.
  double table_end_stiffness() const { return _stiffness_max; }
  /// k_res [Pa/m].
  double residual_stiffness() const { return _residual_stiffness; }
  /// Number of knots.
  std::size_t knot_count() const { return _table.closure.size(); }
  /// Bytes used by the evaluation data (segments and index) plus the knots.
  std::size_t memory_bytes() const;
  /// Source-law evaluations the build used (0 for a loaded table).
  std::size_t law_evaluations() const { return _law_evaluations; }

protected:
  ClosureResponse evaluate_contact(double closure) const override { return evaluate(closure); }
  ClosureResponse evaluate_open(double closure) const override { return evaluate(closure); }

private:
  LawTable _table;
  /// Index entry of a cell holding two or more knots (bisection over all segments).
  static constexpr std::uint32_t crowded_cell = 0xffffffffu;
  /// Segment holding Δ by bisection (cells too crowded for the O(1) path).
  std::uint32_t crowded_segment(double closure) const;

  std::vector<hermite::Segment> _segments;
  /// Per cell of a uniform grid over Δ: first segment it meets | (1 << 31 if it meets the
  /// next one too), or crowded_cell.
  std::vector<std::uint32_t> _cell_index;
  double _inv_cell_width = 0.0;
  std::size_t _cells = 0;
  double _first_segment_end = 0.0; ///< Δ1 [m]: below it, the quartic in √Δ
  double _closure_max = 0.0, _stress_max = 0.0, _stiffness_max = 0.0;
  double _residual_stiffness = 0.0;
  std::size_t _law_evaluations = 0;
};

inline ClosureResponse TabulatedLaw::evaluate(double closure) const
{
  if (closure > 0.0)
  {
    if (closure <= _closure_max)
    {
      ClosureResponse r;
      r.status = Status::contact;
      if (closure >= _first_segment_end) [[likely]]
      {
        std::size_t cell = static_cast<std::size_t>(closure * _inv_cell_width);
        cell = cell < _cells ? cell : _cells - 1;
        const std::uint32_t entry = _cell_index[cell];
        std::uint32_t i;
        if (entry != crowded_cell) [[likely]]
        {
          // At most one knot inside the cell: branch-free choice between its two segments.
          const std::uint32_t step = entry >> 31;
          i = entry & 0x7fffffffu;
          i += step & static_cast<std::uint32_t>(closure >= _segments[i + step].x0);
        }
        else
          i = crowded_segment(closure);
        hermite::evaluate(_segments[i], closure, r.normal_stress, r.normal_stiffness);
      }
      else // [0, Δ1]: the quartic in √Δ
        hermite::evaluate_first(_segments[0], closure, r.normal_stress, r.normal_stiffness);
      return r;
    }
    // Linear continuation with the end tangent (C¹ at Δ_max).
    return {_stress_max + _stiffness_max * (closure - _closure_max), _stiffness_max, 0.0, 0.0,
            Status::validity_limit};
  }
  if (closure <= 0.0)
    return {_residual_stiffness > 0.0 ? _residual_stiffness * closure : 0.0,
            _residual_stiffness, 0.0, 0.0, Status::open};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return {nan, nan, nan, nan, Status::invalid_closure};
}

} // namespace rockjoint::constitutive
