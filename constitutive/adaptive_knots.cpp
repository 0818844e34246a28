// SPDX-License-Identifier: MIT
#include "adaptive_knots.hpp"
#include "monotone_hermite.hpp"
#include "validation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rockjoint::constitutive
{

namespace
{
/// The source law at one knot.
struct Knot
{
  double t;         ///< √Δ [m^½] (bisection variable)
  double closure;   ///< Δ [m] where the law was evaluated (t·t, or exactly Δ_max)
  double stress;    ///< σ [Pa]
  double stiffness; ///< k [Pa/m]
};

/// What was last verified on an interval, to skip re-checking unchanged intervals.
struct IntervalCheck
{
  bool checked = false;
  double slope_left = 0.0, slope_right = 0.0; ///< limited slopes the check used
  double error_stress = 0.0, error_stiffness = 0.0;
};

constexpr std::array<double, 7> interior_points{0.1, 0.21132486540518713, 0.35, 0.5,
                                                0.65, 0.78867513459481287, 0.9};
constexpr std::array<double, 2> first_interval_points{0.01, 0.05};

class Sampler
{
public:
  explicit Sampler(const ClosureLaw& law) : _law(law) {}

  /// The law at t = √Δ (a knot: Δ = t·t).
  Knot at(double t) { return response(t * t, t); }

  /// The law at Δ = `closure` (a check point), t = √Δ.
  Knot at_closure(double closure) { return response(closure, std::sqrt(closure)); }

private:
  Knot response(double closure, double t)
  {
    const ClosureResponse r = _law.evaluate(closure);
    ++evaluations;
    if (r.status != Status::contact || !std::isfinite(r.normal_stress)
        || !std::isfinite(r.normal_stiffness) || !(r.normal_stiffness > 0.0))
    {
      std::ostringstream msg;
      msg.precision(17);
      msg << "TabulatedLaw: source law '" << _law.name() << "' at closure " << closure
          << " m (inside the requested range) returned status " << to_string(r.status)
          << ", σ = " << r.normal_stress << " Pa, k = " << r.normal_stiffness
          << " Pa/m; a table needs finite σ and k > 0 in contact over the whole range";
      throw std::domain_error(msg.str());
    }
    return {t, closure, r.normal_stress, r.normal_stiffness};
  }

public:
  std::size_t evaluations = 0;

private:
  const ClosureLaw& _law;
};

double relative_error(double approximation, double exact)
{
  const double scale = std::abs(exact);
  const double diff = std::abs(approximation - exact);
  return scale > 0.0 ? diff / scale : (diff > 0.0 ? HUGE_VAL : 0.0);
}
} // namespace

KnotPlacement place_knots(const ClosureLaw& law, double maximum_closure, double tolerance,
                          std::size_t maximum_knots)
{
  const std::string who = "TabulatedLaw";
  validation::in_range(who, "tolerance", tolerance, "", 1e-13, 0.1, true);
  validation::positive(who, "maximum_closure", maximum_closure, "m");
  if (maximum_knots < 32)
    validation::fail(who, "maximum_knots", static_cast<double>(maximum_knots), "", ">= 32");

  Sampler sample(law);
  const double t_max = std::sqrt(maximum_closure);

  // Initial grid: uniform in t = √Δ (so denser in Δ near 0, where relative errors are
  // hardest to control), plus knots at Δ_max·10⁻² and 10⁻⁴ so features at Δ << Δ_max are
  // sampled from the start.
  std::vector<double> start;
  for (int i = 0; i <= 16; ++i)
    start.push_back(i == 16 ? t_max : t_max * i / 16.0);
  start.push_back(t_max * 0.1);
  start.push_back(t_max * 0.01);
  std::sort(start.begin(), start.end());
  start.erase(std::unique(start.begin(), start.end()), start.end());

  // Onset at first contact (see the header): k(0+) for the quartic first segment.
  double initial_stiffness = 0.0;
  {
    const double probe = 1e-12 * maximum_closure;
    const double k1 = sample.at(std::sqrt(probe)).stiffness;
    const double k4 = sample.at(2.0 * std::sqrt(probe)).stiffness; // Δ = 4 Δ_p
    const double ratio = k1 / k4;
    if (std::abs(ratio - 1.0) < 0.02)
      initial_stiffness = k1;
    else if (std::abs(ratio - 0.5) >= 0.02)
    {
      std::ostringstream msg;
      msg.precision(6);
      msg << who << ": source law '" << law.name() << "' has k(" << probe << " m) / k("
          << 4 * probe << " m) = " << ratio
          << "; a table supports a tangent that is constant near Δ = 0 (ratio 1, σ ~ Δ) or "
             "grows like Δ^{1/2} (ratio 1/2, Hertzian σ ~ Δ^{3/2})";
      throw std::domain_error(msg.str());
    }
  }

  std::vector<Knot> knots;
  knots.push_back({0.0, 0.0, 0.0, initial_stiffness});
  for (std::size_t i = 1; i + 1 < start.size(); ++i)
    knots.push_back(sample.at(start[i]));
  knots.push_back(sample.at_closure(maximum_closure)); // the range ends exactly at Δ_max
  std::vector<IntervalCheck> checks(knots.size() - 1);

  std::vector<double> t, closure, stress, stiffness;
  const double target = knot_safety_factor * tolerance;
  double worst_error = 0.0;
  for (;;)
  {
    const std::size_t n = knots.size();
    t.resize(n);
    closure.resize(n);
    stress.resize(n);
    stiffness.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      t[i] = knots[i].t;
      closure[i] = knots[i].closure;
      stress[i] = knots[i].stress;
      stiffness[i] = knots[i].stiffness;
      if (i > 0 && !(stress[i] > stress[i - 1]))
      {
        std::ostringstream msg;
        msg.precision(17);
        msg << who << ": source law '" << law.name() << "' is not strictly increasing: σ("
            << closure[i - 1] << " m) = " << stress[i - 1] << " Pa >= σ(" << closure[i]
            << " m) = " << stress[i] << " Pa";
        throw std::domain_error(msg.str());
      }
    }
    hermite::limit_slopes(closure, stress, stiffness);

    // Check every interval whose data changed; collect those to split.
    std::vector<char> split(n - 1, 0);
    std::size_t splits = 0, worst = 0;
    worst_error = 0.0;
    for (std::size_t i = 0; i + 1 < n; ++i)
    {
      IntervalCheck& c = checks[i];
      if (!c.checked || c.slope_left != stiffness[i] || c.slope_right != stiffness[i + 1])
      {
        const hermite::Segment s = hermite::make_table_segment(closure, stress, stiffness, i);
        c = {true, stiffness[i], stiffness[i + 1], 0.0, 0.0};
        if (i == 0 && !hermite::first_segment_is_monotone(s))
          c.error_stress = HUGE_VAL; // not monotone yet: split until it is
        auto check = [&](double tau)
        {
          // The first segment lives in t, the others in Δ: sample each in its variable.
          const double x = i == 0 ? (tau * t[1]) * (tau * t[1])
                                  : closure[i] + tau * (closure[i + 1] - closure[i]);
          const Knot exact = sample.at_closure(x);
          double sigma, k;
          if (i == 0)
            hermite::evaluate_first(s, x, sigma, k);
          else
            hermite::evaluate(s, x, sigma, k);
          c.error_stress = std::max(c.error_stress, relative_error(sigma, exact.stress));
          c.error_stiffness = std::max(c.error_stiffness, relative_error(k, exact.stiffness));
        };
        for (double tau : interior_points)
          check(tau);
        if (i == 0)
          for (double tau : first_interval_points)
            check(tau);
      }
      const double e = std::max(c.error_stress, c.error_stiffness);
      if (e > worst_error)
      {
        worst_error = e;
        worst = i;
      }
      if (e > target)
      {
        split[i] = 1;
        ++splits;
      }
    }

    if (splits == 0)
    {
      KnotPlacement out;
      out.closure = closure;
      out.normal_stress = stress;
      out.stiffness = stiffness;
      for (const IntervalCheck& c : checks)
      {
        out.checked_error_stress = std::max(out.checked_error_stress, c.error_stress);
        out.checked_error_stiffness = std::max(out.checked_error_stiffness, c.error_stiffness);
      }
      out.law_evaluations = sample.evaluations;
      return out;
    }

    auto describe_worst = [&]
    {
      std::ostringstream msg;
      msg.precision(6);
      msg << "the worst interval is closure [" << t[worst] * t[worst] << ", "
          << t[worst + 1] * t[worst + 1] << "] m with relative error " << worst_error
          << " (target " << target << " = " << knot_safety_factor << " x tolerance " << tolerance
          << ")";
      return msg.str();
    };
    if (n + splits > maximum_knots)
    {
      std::ostringstream msg;
      msg << who << ": could not reach tolerance " << tolerance << " for source law '"
          << law.name() << "' within maximum_knots = " << maximum_knots << " (" << n
          << " knots placed); " << describe_worst()
          << ". Loosen the tolerance, shrink the range or raise maximum_knots; a law that is "
             "not smooth to this accuracy (noisy quadrature, kinks) cannot be tabulated "
             "tighter.";
      throw std::runtime_error(msg.str());
    }

    std::vector<Knot> refined;
    std::vector<IntervalCheck> refined_checks;
    refined.reserve(n + splits);
    refined_checks.reserve(n + splits - 1);
    for (std::size_t i = 0; i + 1 < n; ++i)
    {
      refined.push_back(knots[i]);
      if (split[i])
      {
        const double mid = 0.5 * (t[i] + t[i + 1]);
        // Below a width of 1e-9 t the Hermite coefficients (differences of σ) lose more
        // digits to rounding than bisection gains: the law is not smooth there (a kink, e.g.
        // a new summit touching in an empirical list, or quadrature noise).
        if (!(mid > t[i] && mid < t[i + 1]) || t[i + 1] - t[i] < 1e-9 * t[i + 1])
        {
          std::ostringstream msg;
          msg.precision(6);
          msg << who << ": source law '" << law.name() << "' is not smooth enough near closure "
              << t[i] * t[i] << " m to reach tolerance " << tolerance
              << " (the interval there is already 1e-9 of √Δ wide and its relative error is "
              << std::max(checks[i].error_stress, checks[i].error_stiffness)
              << "): a kink (e.g. a summit of an empirical list coming into contact) or noise. "
                 "Loosen the tolerance; "
              << describe_worst();
          throw std::runtime_error(msg.str());
        }
        refined.push_back(sample.at(mid));
        refined_checks.emplace_back();
        refined_checks.emplace_back();
      }
      else
        refined_checks.push_back(checks[i]);
    }
    refined.push_back(knots.back());
    knots = std::move(refined);
    checks = std::move(refined_checks);
  }
}

} // namespace rockjoint::constitutive
