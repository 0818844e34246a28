// SPDX-License-Identifier: MIT
#include "tang_jiao.hpp"
#include "interaction_cell.hpp"
#include "root_finding.hpp"
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
constexpr double pi = std::numbers::pi;
constexpr double inf = std::numeric_limits<double>::infinity();

std::shared_ptr<const ClosureLaw> require_base(std::shared_ptr<const ClosureLaw> base)
{
  if (!base)
    throw std::invalid_argument("TangJiao: parameter 'base' is null; it must be a closure law "
                                "(the f3 of Eq. (6))");
  return base;
}

AsperityParameters asperity_parameters_of(const std::shared_ptr<const AsperityLaw>& base)
{
  if (!base)
    throw std::invalid_argument("TangJiao: parameter 'base' is null; it must be an asperity "
                                "law (the f3 of Eq. (6))");
  return base->asperity_parameters();
}

[[noreturn]] void bad_curve(const std::string& what)
{
  throw std::invalid_argument("TangJiao: geometric overlap curve (overlap_closure, "
                              "overlap_area_ratio) is invalid: "
                              + what);
}
} // namespace

// ---- OverlapCurve ---------------------------------------------------------------------------

OverlapCurve::OverlapCurve(std::vector<double> closure, std::vector<double> area_ratio)
    : _x(std::move(closure)), _y(std::move(area_ratio))
{
  const std::size_t n = _x.size();
  if (n != _y.size())
    bad_curve("overlap_closure has " + std::to_string(n) + " samples but overlap_area_ratio has "
              + std::to_string(_y.size()) + "; they must match");
  if (n < 2)
    bad_curve("it has " + std::to_string(n) + " sample(s); at least 2 are needed");
  for (std::size_t i = 0; i < n; ++i)
  {
    std::ostringstream at;
    at << "[" << i << "]";
    if (!std::isfinite(_x[i]))
      validation::fail("TangJiao", "overlap_closure" + at.str(), _x[i], "m", "finite");
    if (!(_y[i] >= 0.0 && _y[i] <= 1.0))
      validation::fail("TangJiao", "overlap_area_ratio" + at.str(), _y[i], "",
                       "finite and in [0, 1]");
    if (i > 0 && !(_x[i] > _x[i - 1]))
      validation::fail("TangJiao", "overlap_closure" + at.str(), _x[i], "m",
                       "strictly increasing (> the previous sample)");
    if (i > 0 && _y[i] < _y[i - 1])
      validation::fail("TangJiao", "overlap_area_ratio" + at.str(), _y[i], "",
                       "non-decreasing (>= the previous sample)");
  }
  if (_x[0] != 0.0)
    validation::fail("TangJiao", "overlap_closure[0]", _x[0], "m",
                     "0 (the curve starts at first contact)");

  // Monotone C¹ cubic Hermite through the samples (one interpolant for the project:
  // monotone_hermite.hpp).
  std::vector<double> slopes(n);
  hermite::data_slopes(_x, _y, slopes);
  _segments.reserve(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i)
    _segments.push_back(
        hermite::make_segment(_x[i], _x[i + 1], _y[i], _y[i + 1], slopes[i], slopes[i + 1]));
  _end_slope = slopes[n - 1];
}

void OverlapCurve::evaluate(double closure, double& area_ratio, double& area_rate) const
{
  const std::size_t n = _x.size();
  if (closure >= _x[n - 1])
  {
    // Linear continuation with the end slope keeps the curve C¹; s_max caps it.
    area_rate = _end_slope;
    area_ratio = _y[n - 1] + area_rate * (closure - _x[n - 1]);
    return;
  }
  const std::size_t i
      = closure <= 0.0
            ? 0
            : static_cast<std::size_t>(std::upper_bound(_x.begin(), _x.end(), closure)
                                       - _x.begin())
                  - 1;
  hermite::evaluate(_segments[i], std::max(closure, 0.0), area_ratio, area_rate);
  area_ratio = std::max(area_ratio, 0.0);
}

// ---- TangJiao -------------------------------------------------------------------------------

TangJiao::TangJiao(std::shared_ptr<const ClosureLaw> base, double composite_modulus,
                   double radius, double summit_height_std, TangJiaoOptions options)
    : _base(require_base(std::move(base))),
      _composite_modulus(
          validation::positive("TangJiao", "composite_modulus", composite_modulus, "Pa")),
      _radius(validation::positive("TangJiao", "radius", radius, "m")),
      _summit_height_std(
          validation::positive("TangJiao", "summit_height_std", summit_height_std, "m")),
      _options(std::move(options))
{
  validation::in_range("TangJiao", "maximum_area_root", _options.maximum_area_root, "", 0.0,
                       1.0);
  validation::in_range("TangJiao", "maximum_shift_rate", _options.maximum_shift_rate, "", 0.0,
                       1.0);
  if (_options.variant != TangJiaoVariant::stress_interaction
      && _options.variant != TangJiaoVariant::kinematic)
    validation::fail("TangJiao", "variant", static_cast<double>(_options.variant), "",
                     "1 (I1, stress interaction) or 2 (I2, kinematic)");
  if (!_options.overlap_closure.empty() || !_options.overlap_area_ratio.empty())
    _overlap.emplace(_options.overlap_closure, _options.overlap_area_ratio);
  else if (!_base->provides_contact_area())
    throw std::invalid_argument(
        "TangJiao: base law '" + _base->name()
        + "' provides no contact area, but Eq. (2) needs A/A0: use a GW-type base law or "
          "give a geometric overlap curve (overlap_closure, overlap_area_ratio)");
  _contact_radius = interaction_cell::effective_contact_radius(_radius, _summit_height_std);
  // The seating state (Δ = 0+): the base law's seating stress and the Eq. (2) area there.
  _base_seating_stress = _base->seating_stress();
  {
    double area = 0.0, rate = 0.0;
    if (_overlap)
      _overlap->evaluate(0.0, area, rate);
    else
    {
      const ClosureResponse r0 = _base->evaluate(std::numeric_limits<double>::min());
      if (r0.status == Status::contact || r0.status == Status::quadrature_not_converged)
        area = r0.contact_area_ratio;
    }
    _seating_area_root = std::sqrt(std::max(area, 0.0));
  }
  if (!(_seating_area_root < _options.maximum_area_root))
    validation::fail("TangJiao", "maximum_area_root", _options.maximum_area_root, "",
                     "larger than √(A/A0) at first contact (the area ratio of the base law or "
                     "overlap curve already exceeds its square at vanishing closure)");
  _seating_load_fraction = interaction_cell::load_fraction(_seating_area_root);
  _seating_amplification
      = interaction_cell::interaction_fraction(_seating_area_root) / _seating_load_fraction;
  locate_limit();
}

TangJiao::TangJiao(std::shared_ptr<const AsperityLaw> base, TangJiaoOptions options)
    : TangJiao(base, asperity_parameters_of(base).composite_modulus,
               asperity_parameters_of(base).summit_radius,
               asperity_parameters_of(base).summit_height_std, std::move(options))
{
}

std::string TangJiao::name() const { return "tang_jiao"; }

std::vector<Parameter> TangJiao::parameters() const
{
  std::vector<Parameter> p{
      {"variant", static_cast<double>(_options.variant), "(1 = I1, 2 = I2)"},
      {"composite_modulus", _composite_modulus, "Pa"},
      {"radius", _radius, "m"},
      {"summit_height_std", _summit_height_std, "m"},
      {"contact_radius", _contact_radius, "m"},
      {"maximum_area_root", _options.maximum_area_root, ""},
      {"maximum_closure", _maximum_closure, "m"}};
  if (_options.variant == TangJiaoVariant::kinematic)
    p.push_back({"maximum_shift_rate", _options.maximum_shift_rate, ""});
  if (_overlap)
    p.push_back({"overlap_samples", static_cast<double>(_overlap->closure().size()), ""});
  for (const Parameter& b : _base->parameters())
    p.push_back({"base." + b.name, b.value, b.unit});
  return p;
}

TangJiao::State TangJiao::state(double xi) const
{
  State st;
  const ClosureResponse r3 = _base->evaluate(xi);
  st.status = r3.status;
  st.base_stress = r3.normal_stress;
  st.base_stiffness = r3.normal_stiffness;
  double area = r3.contact_area_ratio, rate = r3.contact_area_rate;
  if (_overlap)
    _overlap->evaluate(xi, area, rate);
  st.area_ratio = std::max(area, 0.0);
  st.area_rate = rate;
  st.reported_area_ratio = _base->provides_contact_area() ? r3.contact_area_ratio : area;
  st.reported_area_rate = _base->provides_contact_area() ? r3.contact_area_rate : rate;
  // A base quadrature that missed its tolerance still gives the best estimate: carry on and
  // pass its status through.
  if (r3.status != Status::contact && r3.status != Status::quadrature_not_converged)
    return st;

  const double s = std::sqrt(st.area_ratio);
  st.area_root = s;
  if (!(s < 1.0))
  {
    st.load_fraction = 0.0;
    st.normal_stress = st.normal_stiffness = inf;
    return st;
  }
  const double q = interaction_cell::load_fraction(s);
  const double c = std::sqrt((1.0 - s) * (1.0 + s));
  st.load_fraction = q;
  // I1 with a consistent seating state: the cell acts on the model's stress
  // σ_model = f3 + σ_seat (the base law returns f3 = σ_model - σ_seat), and the law returns
  // the cell stress in excess of its value at Δ = 0, where s = s0:
  //     F = σ_model/Q(s) - σ_seat/Q(s0) = f3/Q(s) + σ_seat [g(s) - g(s0)],  g = 1/Q - 1,
  // with g = (1-Q)/Q from the series of 1-Q (no cancellation as s → 0). F(0) = 0, and the
  // law depends on the seating datum only through a shift of Δ and σ (tested).
  // dQ/dξ = Q'(s) s', s' = A'/(2s), Q' = -(4/π)s²/√(1-s²): the 1/s cancels, so the tangent
  // stays finite as s → 0; dF/dξ = f3'/Q - σ_model Q_ξ/Q².
  const double dq = -(2.0 / pi) * s * st.area_rate / c;
  const double amplification = interaction_cell::interaction_fraction(s) / q; // g(s)
  st.normal_stress = st.base_stress / q
                     + _base_seating_stress * (amplification - _seating_amplification);
  st.normal_stiffness
      = st.base_stiffness / q - (st.base_stress + _base_seating_stress) * dq / (q * q);
  // I2 shift ε = (2F/E*) a √(1-s²)/s and dε/dξ = (2a/E*)[F' √(1-s²)/s - F A'/(2s³√(1-s²))].
  if (s > 0.0)
  {
    const double scale = 2.0 * _contact_radius / _composite_modulus;
    st.closure_shift = scale * st.normal_stress * c / s;
    st.closure_shift_rate = scale
                            * (st.normal_stiffness * c / s
                               - st.normal_stress * st.area_rate / (2.0 * s * s * s * c));
  }
  return st;
}

ClosureResponse TangJiao::response(const State& st) const
{
  if (st.status != Status::contact && st.status != Status::quadrature_not_converged)
    return {st.base_stress, st.base_stiffness, st.reported_area_ratio, st.reported_area_rate,
            st.status};
  if (_options.variant == TangJiaoVariant::stress_interaction)
    return {st.normal_stress, st.normal_stiffness, st.reported_area_ratio,
            st.reported_area_rate, st.status};
  // I2: Δ = ξ - ε(ξ), dΔ/dξ = 1 - ε'.
  const double jacobian = 1.0 - st.closure_shift_rate;
  return {st.normal_stress, st.normal_stiffness / jacobian, st.reported_area_ratio,
          st.reported_area_rate / jacobian, st.status};
}

void TangJiao::locate_limit()
{
  const double base_max = _base->maximum_closure();
  const double target = _options.maximum_area_root * _options.maximum_area_root;
  auto area_at = [&](double xi)
  {
    if (_overlap)
    {
      double a = 0.0, r = 0.0;
      _overlap->evaluate(xi, a, r);
      return a;
    }
    const ClosureResponse r = _base->evaluate(xi);
    return r.status == Status::contact ? r.contact_area_ratio : -inf;
  };

  // 1. The area cap s = s_max: bracket by doubling (or halving towards a finite base limit)
  //    from the roughness scale σ_s, then bisect to 1e-15 relative. Monotone A assumed.
  double xi_area = inf;
  {
    double hi = std::isfinite(base_max) ? std::min(_summit_height_std, 0.5 * base_max)
                                        : _summit_height_std;
    double lo = 0.0;
    bool found = false;
    if (area_at(hi) >= target)
    {
      found = true;
      lo = hi;
      int k = 0;
      for (; area_at(lo) >= target && k < 3000; ++k)
        lo *= 0.5;
      if (k == 3000 || lo == 0.0)
        validation::fail("TangJiao", "maximum_area_root", _options.maximum_area_root, "",
                         "larger than √(A/A0) at first contact (the area ratio of the base law "
                         "or overlap curve already exceeds its square at vanishing closure)");
      hi = 2.0 * lo;
    }
    else
    {
      for (int k = 0; k < 2000; ++k)
      {
        lo = hi;
        hi = root_finding::grow_towards(hi, base_max);
        if (std::isfinite(base_max) && hi == base_max) // A never reaches the cap below it
          break;
        if (area_at(hi) >= target)
        {
          found = true;
          break;
        }
      }
    }
    if (found) // bisection: the first closure with A >= target, to 1e-15 relative
      xi_area = root_finding::find_root([&](double xi)
                                        { return root_finding::Residual{area_at(xi) - target}; },
                                        lo, hi, 0.5 * (lo + hi))
                    .hi;
  }

  _maximum_internal = xi_area;
  _limit = std::isfinite(xi_area) ? TangJiaoLimit::area_root : TangJiaoLimit::none;

  // 2. I2: the first internal closure where dε/dξ reaches maximum_shift_rate, scanned on a
  //    log grid (60 points a decade over 12 decades below the end of the domain) and bisected.
  if (_options.variant == TangJiaoVariant::kinematic)
  {
    const double end = std::isfinite(xi_area)
                           ? xi_area
                           : (std::isfinite(base_max) ? base_max * (1.0 - 1e-12)
                                                      : 1e3 * _summit_height_std);
    const double cap = _options.maximum_shift_rate;
    auto excess = [&](double xi)
    {
      const State st = state(xi);
      return st.status == Status::contact ? st.closure_shift_rate - cap : -1.0;
    };
    const int n = 720;
    double prev = end * 1e-12;
    double xi_rate = inf;
    if (excess(prev) >= 0.0)
    {
      // ε grows faster than ξ from first contact (e.g. a base stress linear in ξ with an
      // area vanishing at ξ = 0: ε ~ F/s ~ √ξ): I2 has no monotone branch at all.
      std::ostringstream msg;
      msg.precision(6);
      msg << "TangJiao: variant I2 has no monotone branch over base law '" << _base->name()
          << "': dε/dΔ >= maximum_shift_rate = " << cap << " already at internal closure "
          << prev << " m (ε = (2F/E*)√(b²-a²) must vanish faster than Δ at first contact; "
          << "use I1, or an area source that is positive at Δ = 0)";
      throw std::invalid_argument(msg.str());
    }
    for (int i = 1; i <= n && !std::isfinite(xi_rate); ++i)
    {
      const double x = i == n ? end : end * std::pow(10.0, -12.0 + 12.0 * i / n);
      if (excess(x) >= 0.0)
      {
        // Bisection; the last point with dε/dξ < cap keeps the tangent finite.
        xi_rate = root_finding::find_root([&](double xi)
                                          { return root_finding::Residual{excess(xi)}; },
                                          prev, x, 0.5 * (prev + x))
                      .lo;
      }
      prev = x;
    }
    if (xi_rate < _maximum_internal)
    {
      _maximum_internal = xi_rate;
      _limit = TangJiaoLimit::closure_shift_rate;
    }
  }

  if (_limit == TangJiaoLimit::none)
  {
    _maximum_internal = base_max;
    _maximum_closure = base_max;
    if (std::isfinite(base_max))
      _limit = TangJiaoLimit::base_law;
    return;
  }
  const State st = state(_maximum_internal);
  _maximum_closure = _options.variant == TangJiaoVariant::kinematic
                         ? _maximum_internal - st.closure_shift
                         : _maximum_internal;
  _limit_response = response(st);
  if (_limit_response.status == Status::contact)
    _limit_response.status = Status::validity_limit;
}

std::string TangJiao::limit_description() const
{
  std::ostringstream msg;
  msg.precision(6);
  switch (_limit)
  {
  case TangJiaoLimit::none: msg << "no validity limit (A/A0 never reaches s_max²)"; break;
  case TangJiaoLimit::area_root:
    msg << "validity limit of the interaction cell: A/A0 = s_max² = "
        << _options.maximum_area_root * _options.maximum_area_root
        << " (maximum_area_root s_max = " << _options.maximum_area_root << ")";
    break;
  case TangJiaoLimit::closure_shift_rate:
    msg << "validity limit of variant I2: dε/dΔ = maximum_shift_rate = "
        << _options.maximum_shift_rate << " (beyond it the closure shift would make the law "
        << "non-monotone at dε/dΔ = 1)";
    break;
  case TangJiaoLimit::base_law:
    msg << "maximum closure of the base law '" << _base->name() << "'";
    break;
  }
  if (_limit == TangJiaoLimit::area_root || _limit == TangJiaoLimit::closure_shift_rate)
    msg << ", reached at closure " << _maximum_closure << " m and normal stress "
        << _limit_response.normal_stress << " Pa";
  return msg.str();
}

double TangJiao::internal_closure(double closure) const
{
  return solve_internal(closure).first;
}

std::pair<double, TangJiao::State> TangJiao::solve_internal(double closure) const
{
  if (_options.variant == TangJiaoVariant::stress_interaction || !(closure > 0.0))
    return {closure, state(closure)};
  // Solve g(ξ) = ξ - ε(ξ) - Δ = 0 on [Δ, ξ_max]: g(Δ) = -ε(Δ) <= 0, g increasing (dε/dξ < 1
  // below the limit). Safeguarded Newton from ξ = Δ; the state of the last iterate is returned
  // with it (no extra evaluation: it is within 1e-15 relative of the root).
  double lo = closure;
  double hi = _maximum_internal;
  double x = lo;
  State st = state(x);
  if (st.status != Status::contact || st.closure_shift <= 0.0)
    return {x, st};
  if (!std::isfinite(hi))
  {
    hi = 2.0 * (closure + st.closure_shift);
    for (int k = 0; k < 2000; ++k, hi *= 2.0)
    {
      const State sh = state(hi);
      if (sh.status != Status::contact || hi - sh.closure_shift - closure > 0.0)
        break;
    }
  }
  // The residual keeps the state of the last evaluated ξ, which find_root returns.
  root_finding::Options options;
  options.maximum_iterations = 200;
  const double root = root_finding::find_root(
                          [&](double xi)
                          {
                            if (xi != x)
                            {
                              x = xi;
                              st = state(xi);
                            }
                            return root_finding::Residual{xi - st.closure_shift - closure,
                                                          1.0 - st.closure_shift_rate};
                          },
                          lo, hi, x, options)
                          .x;
  return {root, st};
}

ClosureResponse TangJiao::evaluate_contact(double closure) const
{
  const bool own_limit
      = _limit == TangJiaoLimit::area_root || _limit == TangJiaoLimit::closure_shift_rate;
  if (own_limit && closure >= _maximum_closure)
    return _limit_response;
  return response(solve_internal(closure).second);
}

double TangJiao::closure_at_stress(double normal_stress) const
{
  const bool own_limit
      = _limit == TangJiaoLimit::area_root || _limit == TangJiaoLimit::closure_shift_rate;
  if (own_limit && std::isfinite(normal_stress)
      && normal_stress > _limit_response.normal_stress)
  {
    std::ostringstream msg;
    msg.precision(6);
    msg << "tang_jiao: normal stress " << normal_stress
        << " Pa is beyond the model's domain: " << limit_description();
    throw std::domain_error(msg.str());
  }
  return ClosureLaw::closure_at_stress(normal_stress);
}

} // namespace rockjoint::constitutive
