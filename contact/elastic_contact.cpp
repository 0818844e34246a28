// SPDX-License-Identifier: MIT
#include "elastic_contact.hpp"

#include "contact_set.hpp"

#include <rockjoint/constitutive/validation.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rockjoint::contact
{

namespace validation = rockjoint::constitutive::validation;

namespace
{
/// K t on the contact set by direct summation while |S|² <= min(4 N, this × M log2 M), M the
/// transform size (a transform pair costs about c M log2 M). 4 N was tuned on the 512² bench
/// joint (factors 2-4 gave the lowest time, 8 was slower, FFT-only 16 % slower). At 1024² a
/// term (HalfSpace::displacement_on, read from an 8 MB periodic or 32 MB zero-padded kernel)
/// cost 5-35 ns as the machine was loaded or not, and 4 N summed for up to 4 times longer than
/// the transform it replaced; at the break-even of bench/bench_contact.py's profile (issue 43:
/// zero-padded, 27 ms per direct sum at |S|² = 4 N against 18.6 ms per transform pair) the
/// factor is 0.03: |S| <= 790 at 1024² periodic, 1660 zero-padded.
constexpr double direct_sum_factor = 0.03;

/// Fraction of the grid that carries the first load's initial pressure (see solve()): on the
/// 512² and 1024² benchmark joints 0.1 % gave the fewest iterations (0.1 %, 1 %, 5 % and the
/// uniform start tried: 218, 225, 228 and 238 iterations at 512²).
constexpr double cold_start_fraction = 0.001;

/// Polonsky & Keer restart CG (δ = 0) whenever a point re-enters contact. Near convergence a
/// handful enter in almost every iteration, and each restart falls back to steepest descent:
/// CG is kept conjugate while at most this fraction of the contact set enters (closure curve of
/// the 1024² benchmark joint: 371 iterations always restarting, 299 at 0.001 and 0.01, 300 at
/// 0.1, 324 at 1; same closures; docs/contact.md).
constexpr double restart_entering_fraction = 0.01;

/// A conjugate direction kept across entering points must have g·t >= this × |g|² on S, else CG
/// restarts from the gap.
constexpr double descent_fraction = 0.1;

/// u = K p is carried from one iteration to the next by u ← s (u - τ K t + K c) (c: the few
/// points clamped to zero or entering contact, summed directly) while |c| · N stays below this
/// × M log2 M (M: transform size), the direct sum's cost against one FFT pair. Measured on the
/// 1024² benchmark joint (bench/results/contact.md): see docs/contact.md.
constexpr double direct_update_factor = 0.25;

/// u is recomputed by FFT after this many carried updates (round-off does not accumulate).
constexpr int carried_updates_limit = 50;

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Consecutive laps of one clock, each added to a phase of ContactProfile; off, it reads no
/// clock (ContactOptions::profile).
class PhaseClock
{
public:
  explicit PhaseClock(bool on) : _on(on)
  {
    if (on)
      _last = Clock::now();
  }
  /// Adds the time since the previous lap to `phase`.
  void lap(double& phase)
  {
    if (!_on)
      return;
    const Clock::time_point now = Clock::now();
    phase += std::chrono::duration<double>(now - _last).count();
    _last = now;
  }

private:
  bool _on;
  Clock::time_point _last;
};

} // namespace

std::size_t scanned_aperture(const topography::Surface& surface, const std::string& owner,
                             std::vector<double>& aperture, std::vector<unsigned char>& valid)
{
  const std::size_t n = static_cast<std::size_t>(surface.rows() * surface.cols());
  aperture.assign(surface.heights().data(), surface.heights().data() + n);
  valid.assign(n, 0);
  std::size_t count = 0;
  double lowest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < n; ++k)
    if (!std::isnan(aperture[k]))
    {
      valid[k] = 1;
      ++count;
      lowest = std::min(lowest, aperture[k]);
    }
  if (count < 2)
    throw std::invalid_argument(owner + ": the aperture has " + std::to_string(count)
                                + " valid (non-NaN) point(s); at least 2 are needed");
  for (std::size_t k = 0; k < n; ++k)
    aperture[k] = valid[k] ? aperture[k] - lowest : 0.0; // first contact at d = 0
  return count;
}

ElasticContact::ElasticContact(const topography::Surface& aperture, double composite_modulus,
                               Kernel kernel, ContactOptions options)
    : _half_space(static_cast<std::size_t>(aperture.rows()),
                  static_cast<std::size_t>(aperture.cols()), aperture.spacing_x(),
                  aperture.spacing_y(), composite_modulus, kernel),
      _options(options), _rows(static_cast<std::size_t>(aperture.rows())),
      _cols(static_cast<std::size_t>(aperture.cols()))
{
  const Clock::time_point setup_start = Clock::now(); // the planning is timed by _half_space
  validation::positive("ElasticContact", "tolerance", options.tolerance, "");
  if (options.maximum_iterations < 1)
    validation::fail("ElasticContact", "maximum_iterations", options.maximum_iterations, "",
                     ">= 1");
  const std::size_t n = _rows * _cols;
  _valid_count = scanned_aperture(aperture, "ElasticContact", _aperture, _valid);
  _u.assign(n, 0.0);
  _t.assign(n, 0.0);
  _r.assign(n, 0.0);
  _previous.assign(n, 0.0);
  _pressure.assign(n, 0.0);
  {
    // Self-compliance K_kk: displacement at a point under unit pressure on its own cell.
    const std::size_t centre = (_rows / 2) * _cols + _cols / 2;
    _t[centre] = 1.0;
    _half_space.displacement(_t, _u);
    _self_compliance = _u[centre];
    _t[centre] = 0.0;
    std::fill(_u.begin(), _u.end(), 0.0);
  }
  if (kernel == Kernel::non_periodic)
  {
    for (std::size_t k = 0; k < n; ++k)
      _t[k] = _valid[k] ? 1.0 : 0.0;
    _half_space.displacement(_t, _u);
    double sum = 0.0;
    for (std::size_t k = 0; k < n; ++k)
      if (_valid[k])
        sum += _u[k];
    _bulk_compliance = sum / double(_valid_count);
  }
  _setup_seconds = seconds_since(setup_start) + _half_space.planning_seconds();
}

double ElasticContact::transform_pair_seconds(int repeats)
{
  if (repeats < 1)
    validation::fail("ElasticContact::transform_pair_seconds", "repeats", repeats, "", ">= 1");
  // Scratch output of the solver's own layout (a std::vector like _u); _r is free between loads.
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < repeats; ++k)
  {
    const Clock::time_point start = Clock::now();
    _half_space.displacement(_pressure, _r);
    best = std::min(best, seconds_since(start));
  }
  return best;
}

ContactState ElasticContact::solve(double mean_pressure, bool keep_fields)
{
  validation::positive("ElasticContact::solve", "mean_pressure", mean_pressure, "Pa");
  const Clock::time_point solve_start = _options.profile ? Clock::now() : Clock::time_point{};
  PhaseClock clock(_options.profile);
  ContactState st;
  ContactProfile& prof = st.profile;
  const std::size_t n = _rows * _cols;
  std::vector<double>& p = _pressure;
  const double total = mean_pressure * double(_valid_count); // Σ p over the scanned points
  // Warm start: the previous pressure scaled to the new load, or uniform.
  if (_last_stress > 0.0)
    for (double& x : p)
      x *= mean_pressure / _last_stress;
  else
  {
    // Cold start: the load spread evenly over the points of smallest aperture (the first to
    // touch), a few per cent of the grid; the iteration adds and removes points from there.
    std::vector<double> e;
    e.reserve(_valid_count);
    for (std::size_t k = 0; k < n; ++k)
      if (_valid[k])
        e.push_back(_aperture[k]);
    const std::size_t count
        = std::clamp<std::size_t>(std::size_t(cold_start_fraction * double(_valid_count)), 1,
                                  _valid_count);
    std::nth_element(e.begin(), e.begin() + (count - 1), e.end());
    const double threshold = e[count - 1];
    std::size_t chosen = 0;
    for (std::size_t k = 0; k < n; ++k)
      chosen += _valid[k] && _aperture[k] <= threshold;
    for (std::size_t k = 0; k < n; ++k)
      p[k] = _valid[k] && _aperture[k] <= threshold ? total / double(chosen) : 0.0;
  }

  // Polonsky & Keer (1999), load-controlled constrained conjugate gradients. Gap g = u + e - d
  // with the rigid approach d = mean of (u + e) over the contact set S = {p > 0}; the search
  // direction t is conjugate on S, restarted (δ = 0) whenever points re-enter contact.
  // Everything but the transforms and one scan for interpenetration works on the list of S
  // (a few per cent of the grid): on large grids the full-grid passes, not the FFTs, would
  // otherwise dominate (the arrays no longer fit the caches).
  st.mean_pressure = mean_pressure;
  std::fill(_t.begin(), _t.end(), 0.0);
  _contact.clear();
  _member.assign(n, 0);
  for (std::size_t k = 0; k < n; ++k)
    if (_valid[k] && p[k] > 0.0)
    {
      _contact.push_back(k);
      _member[k] = 1;
    }
  double g_old = 1.0;
  bool conjugate = false;
  bool u_current = false; // _u = K p already (carried over from the previous iteration)
  int carried = 0;
  const double transform_size = double(_half_space.transform_size());
  const double update_limit
      = direct_update_factor * transform_size * std::log2(transform_size) / double(n);
  const double direct_sum_limit
      = std::min(4.0 * double(n), direct_sum_factor * transform_size * std::log2(transform_size));
  clock.lap(prof.start);
  int it = 0;
  for (; it < _options.maximum_iterations; ++it)
  {
    if (!u_current)
    {
      _half_space.displacement(p, _u); // u = K p
      ++prof.transform_pairs;
      carried = 0;
      clock.lap(prof.transforms);
    }
    const std::size_t m = _contact.size();
    double approach = 0.0;
    for (std::size_t k : _contact)
      approach += _u[k] + _aperture[k];
    approach /= double(m);
    _gap_contact.resize(m);
    double g_norm = 0.0;
    for (std::size_t a = 0; a < m; ++a)
    {
      const std::size_t k = _contact[a];
      _gap_contact[a] = _u[k] + _aperture[k] - approach;
      g_norm += _gap_contact[a] * _gap_contact[a];
    }
    // t = g + β t_old on S, 0 elsewhere (points that left S were zeroed when they left). Kept
    // conjugate across a few entering points, t must stay a descent direction (g·t > 0):
    // otherwise restart from the gap.
    double beta = conjugate ? g_norm / g_old : 0.0;
    if (beta > 0.0)
    {
      double g_t_old = 0.0;
      for (std::size_t a = 0; a < m; ++a)
        g_t_old += _gap_contact[a] * _t[_contact[a]];
      if (g_norm + beta * g_t_old <= descent_fraction * g_norm)
        beta = 0.0;
    }
    g_old = g_norm;
    _t_contact.resize(m);
    _r_contact.resize(m);
    for (std::size_t a = 0; a < m; ++a)
    {
      const std::size_t k = _contact[a];
      _t[k] = _gap_contact[a] + beta * _t[k];
      _t_contact[a] = _t[k];
    }
    // r = K t is needed on S only: direct summation while S is small (direct_sum_factor),
    // one FFT convolution otherwise.
    const bool r_everywhere = double(m) * double(m) > direct_sum_limit;
    clock.lap(prof.contact_set);
    if (!r_everywhere)
    {
      _half_space.displacement_on(_contact, _t_contact, _r_contact);
      clock.lap(prof.direct_sums);
    }
    else
    {
      _half_space.displacement(_t, _r);
      ++prof.transform_pairs;
      clock.lap(prof.transforms);
      for (std::size_t a = 0; a < m; ++a)
        _r_contact[a] = _r[_contact[a]];
    }
    double r_mean = 0.0;
    for (double r : _r_contact)
      r_mean += r;
    r_mean /= double(m);
    double gt = 0.0, rt = 0.0;
    for (std::size_t a = 0; a < m; ++a)
    {
      gt += _gap_contact[a] * _t_contact[a];
      rt += (_r_contact[a] - r_mean) * _t_contact[a];
    }
    // One contact point (or a flat direction) gives no CG step: the gap on S is 0 by the
    // definition of d. Points that interpenetrate then enter with the pressure that would close
    // their overlap alone, g / K_kk (after a deep unloading to one point, a reload would
    // otherwise add no pressure anywhere and stop at once, "converged" on a single point).
    const double tau = rt > 0.0 ? gt / rt : 1.0 / _self_compliance;
    // Update on S (old values kept for the change), then points without pressure that
    // interpenetrate (g < 0) go back into contact: the one full-grid scan.
    _previous.resize(m);
    _clamped.clear();
    for (std::size_t a = 0; a < m; ++a)
    {
      const std::size_t k = _contact[a];
      _previous[a] = p[k];
      const double stepped = p[k] - tau * _t_contact[a];
      p[k] = std::max(stepped, 0.0);
      if (stepped <= 0.0) // 0 too: such a point may re-enter below and then has a correction
        _clamped.push_back({a, stepped});
    }
    clock.lap(prof.contact_set);
    // Serial: a pass this short (a few ms at 1024²) lost more waiting for a second core of the
    // shared bench machine than it gained on two threads (bench/bench_contact.py, issue 43).
    _entering.clear();
    bool overlap = false;
    for (std::size_t k = 0; k < n; ++k)
      if (p[k] == 0.0 && _valid[k] && _u[k] + _aperture[k] - approach < 0.0)
      {
        p[k] = -tau * (_u[k] + _aperture[k] - approach);
        overlap = true;
        if (!_member[k]) // a point of S clamped to 0 this iteration stays on the list
          _entering.push_back(k);
      }
    clock.lap(prof.grid_passes);
    // CG restarts (δ = 0) when more than a few points re-enter (restart_entering_fraction).
    conjugate = !overlap || double(_entering.size()) <= restart_entering_fraction * double(m);
    double load = 0.0;
    for (std::size_t k : _contact)
      load += p[k];
    for (std::size_t k : _entering)
      load += p[k];
    if (!(load > 0.0))
    {
      _contact.clear();
      u_current = false;
      for (std::size_t k = 0; k < n; ++k)
      {
        p[k] = _valid[k] ? mean_pressure : 0.0; // lost every contact: restart uniform
        _t[k] = 0.0;
        _member[k] = _valid[k];
        if (_valid[k])
          _contact.push_back(k);
      }
      conjugate = false;
      clock.lap(prof.grid_passes);
      continue;
    }
    // Rescale to the load, measure the change, and form the next contact set.
    const double scale = total / load;
    // Carry u = K p over: p_new = s (p - τ t + c), c = what clamping and entering changed.
    u_current = r_everywhere && carried < carried_updates_limit
                && double(_clamped.size() + _entering.size()) <= update_limit;
    if (u_current)
    {
      _correction_nodes.clear();
      _correction_values.clear();
      for (const auto& [a, stepped] : _clamped)
      {
        _correction_nodes.push_back(_contact[a]);
        _correction_values.push_back(scale * (p[_contact[a]] - stepped));
      }
      for (std::size_t k : _entering)
      {
        _correction_nodes.push_back(k);
        _correction_values.push_back(scale * p[k]);
      }
      clock.lap(prof.contact_set);
      _half_space.carry_displacement(scale, tau, _r, _correction_nodes, _correction_values, _u);
      clock.lap(prof.grid_passes);
      ++carried;
      ++prof.carried_updates;
    }
    double change = 0.0;
    std::size_t kept = 0;
    for (std::size_t a = 0; a < m; ++a)
    {
      const std::size_t k = _contact[a];
      p[k] *= scale;
      change += std::abs(p[k] - _previous[a]);
      if (p[k] > 0.0)
        _contact[kept++] = k;
      else
      {
        _t[k] = 0.0; // left S: no search direction there
        _member[k] = 0;
      }
    }
    _contact.resize(kept);
    for (std::size_t k : _entering)
    {
      p[k] *= scale;
      change += p[k];
      _contact.push_back(k);
      _member[k] = 1;
    }
    st.relative_change = change / total;
    clock.lap(prof.contact_set);
    if (st.relative_change <= _options.tolerance)
    {
      st.converged = true;
      ++it;
      break;
    }
  }
  st.iterations = it;
  _last_stress = mean_pressure;

  // Final state from the final pressure: d, gap, complementarity.
  _half_space.displacement(p, _u);
  ++prof.transform_pairs;
  clock.lap(prof.transforms);
  double approach = 0.0, sum = 0.0, mean_u = 0.0;
  std::size_t in_contact = 0;
  for (std::size_t k = 0; k < n; ++k)
    if (_valid[k])
    {
      mean_u += _u[k];
      if (p[k] > 0.0)
      {
        sum += _u[k] + _aperture[k];
        ++in_contact;
      }
    }
  approach = sum / double(in_contact);
  mean_u /= double(_valid_count);
  st.approach = approach;
  // Closure = the change of the mean aperture, mean(e) - mean(g) = d - mean(u) with g = e - d + u:
  // what an extensometer across the joint measures. Periodic: mean(u) = 0, so Δ = d. Non-periodic:
  // mean(u) is the patch's own (bulk) deformation under the actual pressure. It is not σ·c (the
  // uniform-pressure value, bulk_compliance()): a load at a spot near the patch's edge displaces
  // the patch less on average than one near its centre, so σ·c drifts from mean(u) as the contact
  // spots change, and d - σ·c lost monotonicity under load (1024² bench joint: 0.0601 mm at
  // 13 MPa, 0.0565 mm at 30 MPa).
  st.closure = approach - mean_u;
  st.minimum_gap = std::numeric_limits<double>::infinity();
  std::vector<double> g(n, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < n; ++k)
  {
    if (!_valid[k])
      continue;
    g[k] = _u[k] + _aperture[k] - approach;
    st.complementarity = std::max(st.complementarity, std::abs(p[k] * g[k]));
    if (!(p[k] > 0.0))
      st.minimum_gap = std::min(st.minimum_gap, g[k]);
  }
  const ContactSet contact = contact_set(p, g, _valid);
  st.contact_area_ratio = double(contact.count) / double(_valid_count);
  st.contact_patches = count_patches(contact.member, _rows, _cols,
                                     _half_space.kernel() == Kernel::periodic);
  if (keep_fields)
  {
    st.pressure.resize(n);
    for (std::size_t k = 0; k < n; ++k)
      st.pressure[k] = _valid[k] ? p[k] : std::numeric_limits<double>::quiet_NaN();
    st.gap = gap_field(g, contact, _valid);
  }
  clock.lap(prof.final_state);
  if (_options.profile)
    prof.wall = seconds_since(solve_start);
  return st;
}

std::vector<ContactState> ElasticContact::closure_curve(std::span<const double> mean_pressures,
                                                        bool keep_fields)
{
  std::vector<ContactState> out;
  out.reserve(mean_pressures.size());
  for (double s : mean_pressures)
    out.push_back(solve(s, keep_fields));
  return out;
}

} // namespace rockjoint::contact
