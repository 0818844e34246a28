// SPDX-License-Identifier: MIT
#include "tabulated_law.hpp"
#include "adaptive_knots.hpp"
#include "root_finding.hpp"
#include "validation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rockjoint::constitutive
{

namespace
{
/// A table holds one curve: a law with history (NormalHysteresis) is tabulated through its
/// virgin law, its branches kept around the table (rockjoint.tabulate does both).
void refuse_history(const ClosureLaw& law)
{
  if (law.has_history())
    throw std::invalid_argument("TabulatedLaw: law '" + law.name()
                                + "' has history; a table holds one curve: tabulate its virgin "
                                  "law and keep the branches (rockjoint.tabulate does both)");
}
} // namespace

TabulatedLaw TabulatedLaw::over_closure_range(const ClosureLaw& law, double maximum_closure,
                                              const Options& options)
{
  const std::string who = "TabulatedLaw";
  refuse_history(law);
  validation::positive(who, "maximum_closure", maximum_closure, "m");
  if (!(maximum_closure < law.maximum_closure()))
  {
    std::ostringstream range;
    range.precision(17);
    range << "below the maximum closure " << law.maximum_closure() << " m of source law '"
          << law.name() << "'";
    validation::fail(who, "maximum_closure", maximum_closure, "m", range.str());
  }
  const bool default_residual = std::isnan(options.residual_stiffness);
  if (!default_residual)
    validation::non_negative(who, "residual_stiffness", options.residual_stiffness, "Pa/m");

  const KnotPlacement knots
      = place_knots(law, maximum_closure, options.tolerance, options.maximum_knots);
  LawTable table;
  table.source_model = law.name();
  table.source_parameters = law.parameters();
  table.source_seating_stress = law.seating_stress();
  table.tolerance = options.tolerance;
  table.checked_error_stress = knots.checked_error_stress;
  table.checked_error_stiffness = knots.checked_error_stiffness;
  table.closure = knots.closure;
  table.normal_stress = knots.normal_stress;
  table.stiffness = knots.stiffness;
  table.residual_stiffness = default_residual ? default_residual_stiffness_fraction
                                                    * table.normal_stress.back()
                                                    / table.closure.back()
                                              : options.residual_stiffness;
  TabulatedLaw tabulated(std::move(table));
  tabulated._law_evaluations = knots.law_evaluations;
  return tabulated;
}

TabulatedLaw TabulatedLaw::up_to_stress(const ClosureLaw& law, double maximum_stress,
                                        const Options& options)
{
  refuse_history(law);
  validation::positive("TabulatedLaw", "maximum_stress", maximum_stress, "Pa");
  double closure;
  try
  {
    closure = law.closure_at_stress(maximum_stress);
  }
  catch (const std::domain_error& e)
  {
    std::ostringstream msg;
    msg.precision(17);
    msg << "TabulatedLaw: maximum_stress " << maximum_stress
        << " Pa is beyond the admissible range of source law '" << law.name()
        << "' (maximum closure " << law.maximum_closure() << " m): " << e.what();
    throw std::domain_error(msg.str());
  }
  if (!(closure < law.maximum_closure()) || !(closure > 0.0))
  {
    std::ostringstream msg;
    msg.precision(17);
    msg << "TabulatedLaw: maximum_stress " << maximum_stress << " Pa maps to closure "
        << closure << " m, not inside (0, " << law.maximum_closure()
        << ") m of source law '" << law.name() << "'";
    throw std::domain_error(msg.str());
  }
  return over_closure_range(law, closure, options);
}

TabulatedLaw::TabulatedLaw(LawTable table) : _table(std::move(table))
{
  validate_law_table(_table, "TabulatedLaw");
  const auto& x = _table.closure;
  const auto& s = _table.normal_stress;
  const auto& k = _table.stiffness;
  const std::size_t n = x.size();
  if (n - 1 >= (std::size_t(1) << 31))
    throw std::invalid_argument("TabulatedLaw: too many knots");

  _segments.reserve(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i)
    _segments.push_back(hermite::make_table_segment(x, s, k, i));

  _first_segment_end = x[1];
  _closure_max = x.back();
  _stress_max = s.back();
  _stiffness_max = k.back();
  _residual_stiffness = _table.residual_stiffness;

  // Index: cells of a uniform grid over [0, Δ_max], at most half the smallest knot spacing
  // (segments >= 1; the first segment has its own branch) wide, so a cell meets at most two
  // segments, within [4(n-1), min(16(n-1), 2^16)] cells. A query's cell is
  // c(Δ) = floor(Δ·inv_width), monotone in Δ; with c_i = c(Δ_i) the segment holding Δ lies in
  // [max{i: c_i < c}, max{i: c_i <= c}] (segment 0 starts at Δ = 0, cell 0).
  double smallest = _closure_max;
  for (std::size_t i = 1; i + 1 < n; ++i)
    smallest = std::min(smallest, x[i + 1] - x[i]);
  const double wanted = std::ceil(2.0 * _closure_max / smallest);
  // The index never outweighs the segments: at most 16 cells (64 bytes) per segment.
  const std::size_t cap = std::min<std::size_t>(16 * (n - 1), std::size_t(1) << 16);
  const std::size_t most = std::max<std::size_t>(cap, 16);
  const std::size_t least = std::min(std::max<std::size_t>(4 * (n - 1), 16), most);
  _cells = wanted >= static_cast<double>(most) ? most
                                               : std::max(least, static_cast<std::size_t>(wanted));
  _inv_cell_width = static_cast<double>(_cells) / _closure_max;
  // A range so small (subnormal closures: found by fuzz/fuzz_law_table) that the cell width
  // underflows would make every cell number inf or NaN, and their conversion undefined.
  if (!std::isfinite(_inv_cell_width))
  {
    std::ostringstream msg;
    msg.precision(17);
    msg << "TabulatedLaw: invalid table: table_maximum_closure " << _closure_max
        << " m is too small to index (" << _cells << " cells over it are narrower than the "
        << "smallest double)";
    throw std::invalid_argument(msg.str());
  }
  _cell_index.assign(_cells, 0);
  std::vector<std::size_t> start_cell(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i)
    start_cell[i] = std::min(static_cast<std::size_t>(x[i] * _inv_cell_width), _cells - 1);
  std::size_t first = 0;
  for (std::size_t c = 0; c < _cells; ++c)
  {
    while (first + 1 < n - 1 && start_cell[first + 1] < c)
      ++first;
    std::size_t last = first;
    while (last + 1 < n - 1 && start_cell[last + 1] <= c)
      ++last;
    _cell_index[c] = last == first       ? static_cast<std::uint32_t>(first)
                     : last == first + 1 ? static_cast<std::uint32_t>(first) | (1u << 31)
                                         : crowded_cell;
  }
}

std::uint32_t TabulatedLaw::crowded_segment(double closure) const
{
  // Last segment starting at or below Δ.
  const auto& knots = _table.closure;
  const auto it = std::upper_bound(knots.begin(), knots.end() - 1, closure);
  return static_cast<std::uint32_t>(std::max<std::ptrdiff_t>(it - knots.begin() - 1, 0));
}

TabulatedLaw TabulatedLaw::load(const std::string& path)
{
  LawTable table = read_law_table(path);
  try
  {
    return TabulatedLaw(std::move(table));
  }
  catch (const std::invalid_argument& e) // the file reads but makes no law: name the file
  {
    throw std::runtime_error("law table file '" + path + "': " + e.what());
  }
}

void TabulatedLaw::save(const std::string& path) const { write_law_table(path, _table); }

std::vector<Parameter> TabulatedLaw::parameters() const
{
  std::vector<Parameter> p{{"tolerance", _table.tolerance, ""},
                           {"table_maximum_closure", _closure_max, "m"},
                           {"table_maximum_stress", _stress_max, "Pa"},
                           {"residual_stiffness", _residual_stiffness, "Pa/m"},
                           {"knots", static_cast<double>(knot_count()), ""}};
  for (const Parameter& q : _table.source_parameters)
    p.push_back({"source." + q.name, q.value, q.unit});
  return p;
}

std::size_t TabulatedLaw::memory_bytes() const
{
  return sizeof(*this) + _segments.size() * sizeof(hermite::Segment)
         + _cell_index.size() * sizeof(std::uint32_t)
         + 3 * _table.closure.size() * sizeof(double);
}

void TabulatedLaw::evaluate(std::span<const double> closure, std::span<double> normal_stress,
                            std::span<double> normal_stiffness, std::span<double> area_ratio,
                            std::span<Status> status) const
{
  check_batch_sizes("TabulatedLaw::evaluate", closure, normal_stress, normal_stiffness,
                    area_ratio, status);
  const std::size_t n = closure.size();
  if (status.empty())
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      const ClosureResponse r = evaluate(closure[i]);
      normal_stress[i] = r.normal_stress;
      normal_stiffness[i] = r.normal_stiffness;
    }
  }
  else
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      const ClosureResponse r = evaluate(closure[i]);
      normal_stress[i] = r.normal_stress;
      normal_stiffness[i] = r.normal_stiffness;
      status[i] = r.status;
    }
  }
  if (!area_ratio.empty())
    std::fill(area_ratio.begin(), area_ratio.end(), 0.0);
}

double TabulatedLaw::closure_at_stress(double target) const
{
  check_target_stress(target);
  if (target == 0.0)
    return 0.0;
  if (target >= _stress_max)
    return _closure_max + (target - _stress_max) / _stiffness_max;

  // Segment i with σ_i <= target < σ_{i+1}.
  const auto& s = _table.normal_stress;
  const std::size_t i
      = static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), target) - s.begin()) - 1;
  const hermite::Segment& seg = _segments[i];
  // Safeguarded Newton on p(τ) = target, p increasing on [0, 1]. The first segment is a
  // quartic in τ = √Δ/t1 (c0 = c1 = 0), the others cubics in τ = (Δ - Δ_i)/h (c4 = 0).
  root_finding::Options options;
  options.relative_tolerance = 1e-16;
  options.maximum_iterations = 2000;
  const double tau = root_finding::find_root(
                         [&](double t)
                         {
                           const double p
                               = seg.c0 + t * (seg.c1 + t * (seg.c2 + t * (seg.c3 + t * seg.c4)));
                           const double dp
                               = seg.c1 + t * (2.0 * seg.c2 + t * (3.0 * seg.c3 + t * (4.0 * seg.c4)));
                           return root_finding::Residual{p - target, dp};
                         },
                         0.0, 1.0, 0.5, options)
                         .x;
  if (i == 0)
  {
    const double t = tau / seg.inv_h;
    return t * t;
  }
  return seg.x0 + tau / seg.inv_h;
}

} // namespace rockjoint::constitutive
