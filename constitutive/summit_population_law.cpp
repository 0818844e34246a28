// SPDX-License-Identifier: MIT
#include "summit_population_law.hpp"
#include "gw_integral.hpp"
#include "root_finding.hpp"
#include "substrate.hpp"
#include "validation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace rockjoint::constitutive
{

namespace
{
constexpr double inf = std::numeric_limits<double>::infinity();

/// Default reference: mean summit height + this many σ_s (theory §7 example).
constexpr double automatic_reference_offset = 3.5;

} // namespace

SummitPopulationLaw::SummitPopulationLaw(const std::string& owner, const AsperityParameters& p,
                                         HeightDistribution distribution,
                                         double deflection_coefficient,
                                         std::optional<double> base_radius,
                                         const SeatingReference& reference,
                                         double quadrature_tolerance)
    : _parameters(p), _distribution(distribution), _deflection_coefficient(deflection_coefficient),
      _tolerance(quadrature_tolerance)
{
  validate(p, owner);
  if (distribution == HeightDistribution::empirical)
    throw std::invalid_argument(owner
                                + ": parameter 'distribution' = empirical needs a list "
                                  "of summits (EmpiricalSummits), not statistics");
  check_common(owner, base_radius);
  const double E = p.composite_modulus, eta = p.summit_density, beta = p.summit_radius,
               ss = p.summit_height_std;
  _stress_scale = (4.0 / 3.0) * E * eta * std::sqrt(beta) * ss * std::sqrt(ss);
  _stiffness_scale = 2.0 * E * eta * std::sqrt(beta) * std::sqrt(ss);
  _area_scale = std::numbers::pi * eta * beta * ss;
  _rate_scale = std::numbers::pi * eta * beta;
  _mu = _compliance_factor * std::sqrt(beta) * std::sqrt(ss);
  set_reference(owner, reference);
}

SummitPopulationLaw::SummitPopulationLaw(const std::string& owner, double composite_modulus,
                                         EmpiricalSummits summits, double deflection_coefficient,
                                         std::optional<double> base_radius,
                                         const SeatingReference& reference,
                                         double quadrature_tolerance)
    : _parameters{validation::positive(owner, "composite_modulus", composite_modulus, "Pa"),
                  summits.summit_density(), summits.mean_radius(), summits.height_std()},
      _distribution(HeightDistribution::empirical), _summits(std::move(summits)),
      _deflection_coefficient(deflection_coefficient), _tolerance(quadrature_tolerance)
{
  check_common(owner, base_radius);
  set_reference(owner, reference);
}

void SummitPopulationLaw::check_common(const std::string& owner, std::optional<double> base_radius)
{
  validation::in_range(owner, "quadrature_tolerance", _tolerance, "", 0.0, 1.0);
  validation::non_negative(owner, "deflection_coefficient", _deflection_coefficient, "");
  // Default r0: half the mean summit spacing 1/√η (theory §4 [choice]).
  _base_radius = base_radius ? validation::positive(owner, "base_radius", *base_radius, "m")
                             : 0.5 / std::sqrt(_parameters.summit_density);
  _compliance_factor = _deflection_coefficient / _base_radius;
}

std::vector<Parameter> SummitPopulationLaw::parameters() const
{
  // The distribution as its enum code, so a table file records which one the law used.
  const double distribution = _summits ? static_cast<double>(HeightDistribution::empirical)
                                       : static_cast<double>(_distribution);
  std::vector<Parameter> p{
          {"height_distribution", distribution, "code: 0 gaussian, 1 exponential, 2 empirical"},
          {"composite_modulus", _parameters.composite_modulus, "Pa"},
          {"summit_density", _parameters.summit_density, "1/m^2"},
          {"summit_radius", _parameters.summit_radius, "m"},
          {"summit_height_std", _parameters.summit_height_std, "m"},
          {"reference_separation", _reference_separation, "m"},
          {"seating_stress", _seating_stress, "Pa"},
          {"quadrature_tolerance", _tolerance, ""}};
  if (_summits)
    p.push_back({"summit_count", static_cast<double>(_summits->size()), ""});
  return p;
}

void SummitPopulationLaw::set_reference(const std::string& owner, const SeatingReference& reference)
{
  const double ss = _parameters.summit_height_std;
  double automatic
      = _summits ? _summits->highest()
                 : ss * (summit_heights::standard_mean(_distribution) + automatic_reference_offset);
  switch (reference.kind)
  {
  case SeatingReference::Kind::automatic: _reference_separation = automatic; break;
  case SeatingReference::Kind::separation:
    _reference_separation = validation::finite(owner, "reference_separation", reference.value, "m");
    break;
  case SeatingReference::Kind::stress:
  {
    const double target = validation::positive(owner, "seating_stress", reference.value, "Pa");
    // σ_model(d) decreases strictly (where positive) from +∞ (d -> -∞) to 0. Bracket by
    // doubling steps from the automatic reference, then safeguarded Newton on ln σ (the
    // Gaussian tail makes ln σ nearly quadratic in d).
    double scale = ss > 0.0 ? ss : 1e-3 * _parameters.summit_radius;
    auto stress = [&](double d) { return response_at_separation(d).normal_stress; };
    double lo, hi; // σ(lo) >= target > σ(hi)
    double step = scale;
    int it = 0;
    if (stress(automatic) >= target)
    {
      lo = automatic;
      for (hi = lo + step; stress(hi) >= target; hi = lo + step)
      {
        lo = hi;
        step *= 2.0;
        if (++it > 2000)
          validation::fail(owner, "seating_stress", target, "Pa", "reachable by the model");
      }
    }
    else
    {
      hi = automatic;
      for (lo = hi - step; stress(lo) < target; lo = hi - step)
      {
        hi = lo;
        step *= 2.0;
        if (++it > 2000 || !std::isfinite(lo))
          validation::fail(owner, "seating_stress", target, "Pa", "reachable by the model");
      }
    }
    // r(d) = ln(target/σ(d)) increases with d; r' = k/σ (dσ/dd = -k).
    root_finding::Options newton_on_log;
    newton_on_log.absolute_scale = scale;
    const double x = root_finding::find_root(
                         [&](double d)
                         {
                           const ClosureResponse r = response_at_separation(d);
                           return root_finding::Residual{std::log(target / r.normal_stress),
                                                         r.normal_stiffness / r.normal_stress};
                         },
                         lo, hi, lo, newton_on_log)
                         .x;
    _reference_separation = x;
    break;
  }
  }
  const ClosureResponse seat = response_at_separation(_reference_separation);
  _seating_stress = seat.normal_stress;
  if (!std::isfinite(_seating_stress))
    validation::fail(owner, "reference_separation", _reference_separation, "m",
                     "such that the seating stress is finite");
}

ClosureResponse SummitPopulationLaw::response_at_separation(double separation) const
{
  if (std::isnan(separation))
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan, nan, Status::invalid_closure};
  }
  if (_summits)
    return empirical_response(separation, false, 0.0);
  const double h = separation / _parameters.summit_height_std;
  return parametric_response(h, inf, 0.0);
}

ClosureResponse SummitPopulationLaw::evaluate_contact(double closure) const
{
  // Δ = +∞: every summit crushed, σ = k = +∞ (maximum_closure() is +∞).
  if (std::isinf(closure))
    return beyond_maximum_closure(inf);
  if (_summits)
    return empirical_response(_reference_separation - closure, true, closure);
  const double ss = _parameters.summit_height_std;
  const double delta = closure / ss;
  const double h_ref = _reference_separation / ss;
  // Δ/σ_s overflows: every summit crushed, σ = k = +∞.
  if (!std::isfinite(delta))
    return beyond_maximum_closure(inf);
  return parametric_response(h_ref - delta, h_ref, delta);
}

bool SummitPopulationLaw::quadrature_converged(double closure) const
{
  if (_summits || !(closure > 0.0) || std::isinf(closure))
    return true;
  const double ss = _parameters.summit_height_std;
  const double delta = closure / ss, h_ref = _reference_separation / ss;
  return !std::isfinite(delta)
         || gw::population_moments(_distribution, _mu, h_ref - delta, h_ref, delta, _tolerance)
                .converged;
}

ClosureResponse SummitPopulationLaw::parametric_response(double h, double h_ref, double delta) const
{
  const gw::Moments m = gw::population_moments(_distribution, _mu, h, h_ref, delta, _tolerance);
  ClosureResponse r{_stress_scale * m.stress, _stiffness_scale * m.stiffness, _area_scale * m.area,
                    _rate_scale * m.rate,
                    m.converged ? Status::contact : Status::quadrature_not_converged};
  // Beyond the range of double (a closure of metres on a nanometre roughness at E* of
  // GPa can overflow σ): report it as a hard limit rather than NaN.
  if (!std::isfinite(r.normal_stress) || !std::isfinite(r.normal_stiffness))
    return beyond_maximum_closure(r.contact_area_ratio);
  if (!std::isfinite(h_ref) && r.normal_stress == 0.0 && r.normal_stiffness == 0.0)
    r.status = Status::open;
  return r;
}

ClosureResponse SummitPopulationLaw::empirical_response(double separation, bool seated,
                                                        double closure) const
{
  const EmpiricalSummits& S = *_summits;
  const auto z = S.heights();
  const auto beta = S.radii();
  const auto sqrt_beta = S.sqrt_radii();
  const double d0 = _reference_separation;
  double sum_stress = 0.0, sum_stiffness = 0.0, sum_area = 0.0, sum_rate = 0.0;
  // Heights decrease: the summits in contact are a prefix; w is the exact approach.
  for (std::size_t i = 0; i < S.size(); ++i)
  {
    const double w = seated ? (z[i] - d0) + closure : z[i] - separation;
    if (!(w > 0.0))
      break;
    const double c = _compliance_factor * sqrt_beta[i];
    const substrate::HertzApproach a = substrate::hertz_approach(w, c);
    // c = 0 keeps g = w exactly, so one summit reproduces Hertz to rounding.
    const double g = a.hertz_part;
    double cube = g * a.root;
    if (seated && z[i] - d0 > 0.0)
      cube = substrate::cube_difference(a.root, substrate::hertz_approach(z[i] - d0, c).root, c,
                                        closure);
    sum_stress += sqrt_beta[i] * cube;
    sum_stiffness += sqrt_beta[i] * a.root * a.derivative;
    sum_area += beta[i] * g;
    sum_rate += beta[i] * a.derivative;
  }
  const double E = _parameters.composite_modulus, A0 = S.area();
  ClosureResponse r{(4.0 / 3.0) * E / A0 * sum_stress, 2.0 * E / A0 * sum_stiffness,
                    std::numbers::pi / A0 * sum_area, std::numbers::pi / A0 * sum_rate,
                    Status::contact};
  if (!std::isfinite(r.normal_stress) || !std::isfinite(r.normal_stiffness))
    return beyond_maximum_closure(r.contact_area_ratio);
  if (!seated && sum_stress == 0.0 && sum_stiffness == 0.0)
    r.status = Status::open;
  return r;
}

} // namespace rockjoint::constitutive
