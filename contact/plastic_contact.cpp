// SPDX-License-Identifier: MIT
#include "plastic_contact.hpp"

#include <rockjoint/constitutive/root_finding.hpp>
#include <rockjoint/constitutive/validation.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rockjoint::contact
{

namespace validation = rockjoint::constitutive::validation;

PlasticContact::PlasticContact(const topography::Surface& aperture, double composite_modulus,
                               Kernel kernel, double hardness, ContactOptions options)
    : _half_space(static_cast<std::size_t>(aperture.rows()),
                  static_cast<std::size_t>(aperture.cols()), aperture.spacing_x(),
                  aperture.spacing_y(), composite_modulus, kernel),
      _options(options), _hardness(hardness), _rows(static_cast<std::size_t>(aperture.rows())),
      _cols(static_cast<std::size_t>(aperture.cols()))
{
  if (!(hardness > 0.0)) // NaN fails too
    validation::fail("PlasticContact", "hardness", hardness, "Pa", "> 0 (+inf for elastic walls)");
  validation::positive("PlasticContact", "tolerance", options.tolerance, "");
  const std::size_t n = _rows * _cols;
  _valid_count = scanned_aperture(aperture, "PlasticContact", _aperture, _valid);
  _pressure.assign(n, 0.0);
  _u.assign(n, 0.0);
  _g.assign(n, 0.0);
  _t.assign(n, 0.0);
  _r.assign(n, 0.0);
}

double PlasticContact::mean_pressure_at(double d)
{
  // Projected conjugate gradients for min ½ pᵀKp - pᵀ(d - e), 0 <= p <= H: the free points are
  // those strictly inside the box and those at a bound whose gradient g = Kp + e - d points
  // inside; the direction is conjugate while the free set stays the same, steepest otherwise.
  const std::size_t n = _rows * _cols;
  std::vector<double>& p = _pressure;
  std::vector<unsigned char> free(n, 0), free_old(n, 0);
  double gg_old = 1.0;
  bool conjugate = false;
  std::fill(_t.begin(), _t.end(), 0.0);
  for (int it = 0; it < _options.maximum_iterations; ++it, ++_iterations)
  {
    _half_space.displacement(p, _u);
    double gg = 0.0;
    bool same = true;
    for (std::size_t k = 0; k < n; ++k)
    {
      _g[k] = _u[k] + _aperture[k] - d;
      const bool f = _valid[k]
                     && ((p[k] > 0.0 && p[k] < _hardness) || (p[k] <= 0.0 && _g[k] < 0.0)
                         || (p[k] >= _hardness && _g[k] > 0.0));
      free[k] = f;
      same = same && f == free_old[k];
      if (f)
        gg += _g[k] * _g[k];
    }
    if (gg == 0.0)
      break;
    const double beta = conjugate && same ? gg / gg_old : 0.0;
    gg_old = gg;
    for (std::size_t k = 0; k < n; ++k)
      _t[k] = free[k] ? _g[k] + beta * _t[k] : 0.0;
    _half_space.displacement(_t, _r);
    double gt = 0.0, tkt = 0.0;
    for (std::size_t k = 0; k < n; ++k)
      if (free[k])
      {
        gt += _g[k] * _t[k];
        tkt += _t[k] * _r[k];
      }
    if (!(tkt > 0.0))
      break;
    const double tau = gt / tkt;
    double change = 0.0, total = 0.0;
    for (std::size_t k = 0; k < n; ++k)
      if (free[k])
      {
        const double next = std::clamp(p[k] - tau * _t[k], 0.0, _hardness);
        change += std::abs(next - p[k]);
        p[k] = next;
      }
    for (std::size_t k = 0; k < n; ++k)
      total += p[k];
    free_old.swap(free);
    conjugate = true;
    if (change <= _options.tolerance * std::max(total, std::numeric_limits<double>::min()))
      break;
  }
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    sum += p[k];
  return sum / double(_valid_count);
}

PlasticContactState PlasticContact::solve(double sigma)
{
  validation::positive("PlasticContact::solve", "mean_pressure", sigma, "Pa");
  PlasticContactState st;
  st.mean_pressure = sigma;
  const int iterations_before = _iterations;
  // Bracket d: σ(d) rises with d; from the previous approach (or first contact) up or down.
  namespace rf = constitutive::root_finding;
  double lo = _approach, hi = _approach;
  double s_lo = mean_pressure_at(lo), s_hi = s_lo;
  double step = std::max(1e-9, 1e-3 * std::abs(_approach)) + sigma * 1e-12;
  int evaluations = 1;
  // Δd for a stress change: a stiffness scale E*/(grid side) gives the order of magnitude.
  step = std::max(step, std::abs(sigma - s_lo) * double(std::max(_rows, _cols))
                            * 1e-3 / _half_space.composite_modulus());
  while (s_lo > sigma && evaluations < 200)
  {
    hi = lo;
    s_hi = s_lo;
    lo -= step;
    step *= 2.0;
    s_lo = mean_pressure_at(lo);
    ++evaluations;
  }
  while (s_hi < sigma && evaluations < 200)
  {
    lo = hi;
    s_lo = s_hi;
    hi += step;
    step *= 2.0;
    s_hi = mean_pressure_at(hi);
    ++evaluations;
  }
  rf::Options options;
  options.secant = true;
  options.relative_tolerance = 1e-14;
  options.absolute_scale = std::max(std::abs(hi), 1e-12);
  options.residual_tolerance = 1e-12 * sigma;
  const rf::Root root = rf::find_root(
      [&](double d)
      {
        ++evaluations;
        return rf::Residual{mean_pressure_at(d) - sigma};
      },
      lo, hi, hi, options, s_lo - sigma, s_hi - sigma);
  const double d = root.converged ? root.x : 0.5 * (root.lo + root.hi);
  const double reached = mean_pressure_at(d);
  // σ(d) is known to the inner solves' tolerance: the load is met to ten times it.
  st.converged = root.bracketed
                 && std::abs(reached - sigma) <= std::max(1e-9, 10.0 * _options.tolerance) * sigma;
  _approach = d;

  // Flatten the overlap at the capped points (plastic flow), then the state.
  const std::size_t n = _rows * _cols;
  std::size_t capped = 0;
  double mean_u = 0.0;
  for (std::size_t k = 0; k < n; ++k)
  {
    if (!_valid[k])
      continue;
    mean_u += _u[k];
    const double g = _u[k] + _aperture[k] - d;
    if (_pressure[k] >= _hardness && g < 0.0)
    {
      _aperture[k] -= g;
      _flattening_sum -= g;
    }
    capped += _pressure[k] >= _hardness;
  }
  mean_u /= double(_valid_count);
  st.approach = d;
  st.mean_flattening = _flattening_sum / double(_valid_count);
  st.closure = d - mean_u - st.mean_flattening;
  // The gap of the final pressure on the flattened walls (_u is the last iteration's, one step
  // behind p), and the contact set it defines with p (contact_set.hpp).
  _half_space.displacement(_pressure, _u);
  for (std::size_t k = 0; k < n; ++k)
    _g[k] = _valid[k] ? _u[k] + _aperture[k] - d : 0.0;
  _contact = contact_set(_pressure, _g, _valid);
  st.contact_area_ratio = double(_contact.count) / double(_valid_count);
  st.plastic_area_ratio = double(capped) / double(_valid_count);
  st.evaluations = evaluations;
  st.iterations = _iterations - iterations_before;
  return st;
}

double PlasticContact::unloaded_closure() const
{
  double d0 = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < _aperture.size(); ++k)
    if (_valid[k])
      d0 = std::min(d0, _aperture[k]);
  return d0 - _flattening_sum / double(_valid_count);
}

std::vector<double> PlasticContact::gap() const
{
  if (_contact.member.empty())
    return {};
  return gap_field(_g, _contact, _valid);
}

std::vector<double> PlasticContact::pressure() const
{
  std::vector<double> p(_pressure);
  for (std::size_t k = 0; k < p.size(); ++k)
    if (!_valid[k])
      p[k] = std::numeric_limits<double>::quiet_NaN();
  return p;
}

} // namespace rockjoint::contact
