// SPDX-License-Identifier: MIT
// TabulatedLaw: the error bound against the source law on random points for every
// law of the library, monotonicity and positivity, exact tangent consistency (central
// differences of the table's own σ), behaviour beyond the table, bit-exact file round trip
// and clear errors for malformed files. References are the source laws (closed forms) and
// finite differences; nothing is taken from the table under test.
#include <rockjoint/constitutive/barton_bandis.hpp>
#include <rockjoint/constitutive/empirical_laws.hpp>
#include <rockjoint/constitutive/normal_hysteresis.hpp>
#include <rockjoint/constitutive/tabulated_law.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "expect_error.hpp"
#include "law_checks.hpp"
#include "tabulation_test_laws.hpp"

using namespace rockjoint::constitutive;
using rockjoint::testing::LawCase;

namespace
{
std::vector<double> random_closures(double top, std::size_t n, unsigned seed)
{
  // Half uniform in Δ (where an FE model mostly lives), half log-uniform over 12 decades
  // (the first interval, where relative errors are hardest to control).
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> d(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const double u = uniform(gen);
    d[i] = i % 2 ? top * std::pow(10.0, -12.0 * u) : top * u;
    if (!(d[i] > 0.0))
      d[i] = 0.5 * top;
  }
  return d;
}

std::string temp_path(const std::string& name)
{
  return (std::filesystem::temp_directory_path()
          / ("rockjoint_test_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

std::vector<std::string> read_lines(const std::string& path)
{
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);)
    lines.push_back(l);
  return lines;
}

void write_lines(const std::string& path, const std::vector<std::string>& lines)
{
  std::ofstream out(path);
  for (const auto& l : lines)
    out << l << '\n';
}

/// Index of the first line starting with `prefix`.
std::size_t find_line(const std::vector<std::string>& lines, const std::string& prefix)
{
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i].rfind(prefix, 0) == 0)
      return i;
  ADD_FAILURE() << "no line starts with " << prefix;
  return 0;
}
} // namespace

TEST(TabulatedLaw, ErrorBoundHoldsOnRandomPointsForEveryLaw)
{
  for (const LawCase& c : rockjoint::testing::library_laws())
  {
    for (double tol : {1e-3, 1e-6, 1e-8})
    {
      if (tol < c.finest_tolerance)
        continue;
      SCOPED_TRACE(c.label + " tolerance " + std::to_string(tol));
      TabulatedLaw::Options o;
      o.tolerance = tol;
      const auto table = TabulatedLaw::up_to_stress(*c.law, c.maximum_stress, o);
      const double top = table.table_maximum_closure();
      double worst_s = 0.0, worst_k = 0.0;
      for (double d : random_closures(top, 10000, 42))
      {
        const auto exact = c.law->evaluate(d);
        const auto r = table.evaluate(d);
        ASSERT_EQ(r.status, Status::contact) << d;
        worst_s = std::max(worst_s, std::abs(r.normal_stress / exact.normal_stress - 1.0));
        worst_k = std::max(worst_k, std::abs(r.normal_stiffness / exact.normal_stiffness - 1.0));
      }
      EXPECT_LE(worst_s, tol) << "σ relative error, " << table.knot_count() << " knots";
      EXPECT_LE(worst_k, tol) << "k relative error, " << table.knot_count() << " knots";
      // The last knot is Δ_max = Δ(σ_max) exactly, so σ there is the requested stress.
      EXPECT_EQ(table.table_maximum_closure(), c.law->closure_at_stress(c.maximum_stress));
      EXPECT_NEAR(table.table_maximum_stress(), c.maximum_stress, 1e-9 * c.maximum_stress);
    }
  }
}

TEST(TabulatedLaw, KnotsGrowLikeToleranceToTheMinusOneThird)
{
  // With the source's exact k at the knots, σ errs by O(h⁴) and k (the derivative of a
  // Hermite cubic) by O(h³); the k bound governs, so knots ~ tol^{-1/3}: 10^4 tighter needs
  // ~21x the knots. Slopes from finite differences (second order) would need ~100x.
  BartonBandis law(20e9, 0.3e-3);
  TabulatedLaw::Options loose, tight;
  loose.tolerance = 1e-4;
  tight.tolerance = 1e-8;
  const auto a = TabulatedLaw::up_to_stress(law, 30e6, loose);
  const auto b = TabulatedLaw::up_to_stress(law, 30e6, tight);
  const double ratio = static_cast<double>(b.knot_count()) / a.knot_count();
  EXPECT_GT(ratio, 10.0) << a.knot_count() << " -> " << b.knot_count();
  EXPECT_LT(ratio, 40.0) << a.knot_count() << " -> " << b.knot_count();
}

TEST(TabulatedLaw, PassesTheCommonLawChecks)
{
  // Through the ClosureLaw interface: open branch strict, monotone, k > 0, k vs FD,
  // Δ(σ(Δ)) = Δ for the table's own inverse, batch = pointwise.
  for (const LawCase& c : rockjoint::testing::library_laws())
  {
    SCOPED_TRACE(c.label);
    // k_res = 0: the strict opening convention check_law asserts (k_res > 0 is tested in
    // ResidualStiffnessIsSeenThroughTheBaseInterface).
    TabulatedLaw::Options strict;
    strict.residual_stiffness = 0.0;
    const auto table = TabulatedLaw::up_to_stress(*c.law, c.maximum_stress, strict);
    // Inside the table: at Δ_max itself the FD stencil would straddle the C¹ (not C²) join
    // with the linear extension, tested on its own below.
    rockjoint::testing::check_law(table, 0.999 * table.table_maximum_closure());
  }
}

TEST(TabulatedLaw, MonotoneAndPositiveOnADenseSweep)
{
  for (const LawCase& c : rockjoint::testing::library_laws())
  {
    SCOPED_TRACE(c.label);
    TabulatedLaw::Options o;
    o.tolerance = 1e-2; // coarse tables are where a non-monotone interpolant would show
    const auto table = TabulatedLaw::up_to_stress(*c.law, c.maximum_stress, o);
    const double top = table.table_maximum_closure();
    double previous = 0.0;
    const int n = 200000;
    for (int i = 1; i <= n; ++i)
    {
      // Quadratic spacing: dense near 0, reaches 1.5 Δ_max (into the extension).
      const double d = 1.5 * top * (double(i) / n) * (double(i) / n);
      const auto r = table.evaluate(d);
      ASSERT_GT(r.normal_stress, previous) << "σ not increasing at Δ = " << d;
      ASSERT_GT(r.normal_stiffness, 0.0) << "k not positive at Δ = " << d;
      previous = r.normal_stress;
    }
  }
}

TEST(TabulatedLaw, TangentIsTheExactDerivativeOfTheTable)
{
  for (const LawCase& c : rockjoint::testing::library_laws())
  {
    SCOPED_TRACE(c.label);
    TabulatedLaw::Options o;
    o.tolerance = 1e-3; // a coarse table differs from its source: FD must match the TABLE
    const auto table = TabulatedLaw::up_to_stress(*c.law, c.maximum_stress, o);
    const double top = table.table_maximum_closure();
    for (double d : random_closures(top, 2000, 7))
    {
      // Step 1e-5 × the local length scale min(Δ, σ/k): O(h²) truncation ~1e-10 relative,
      // rounding ~1e-11; a knot inside the stencil adds O(h [σ'']/k), small since σ is C¹
      // with a σ'' jump of the order of the interpolation error.
      const auto r = table.evaluate(d);
      const double h = 1e-5 * std::min(d, r.normal_stress / r.normal_stiffness);
      const double fd = (table.evaluate(d + h).normal_stress
                         - table.evaluate(d - h).normal_stress)
                        / (2 * h);
      const double k = table.evaluate(d).normal_stiffness;
      EXPECT_NEAR(k, fd, 1e-6 * k) << "Δ = " << d;
    }
  }
}

TEST(TabulatedLaw, NewtonOnTheTableConvergesQuadratically)
{
  // The consistent tangent is what keeps an FE Newton solve quadratic: solve σ(Δ) = σ* with
  // the table's own k and check r_{n+1} <= 10 r_n² in the asymptotic range (observed
  // constants are <= 1). Control: a tangent off by only 1e-3 (e.g. the source's k instead of
  // the table's) converges linearly, r_{n+1} ≈ 1e-3 r_n, and breaks the bound.
  auto newton = [](const TabulatedLaw& table, double target, double tangent_factor)
  {
    double d = table.table_maximum_closure(); // start from the stiff end (no overshoot)
    std::vector<double> residual;
    for (int it = 0; it < 60; ++it)
    {
      const auto r = table.evaluate(d);
      residual.push_back(std::abs(r.normal_stress - target) / target);
      if (residual.back() < 1e-14)
        break;
      d -= (r.normal_stress - target) / (tangent_factor * r.normal_stiffness);
    }
    return residual;
  };
  auto quadratic = [](const std::vector<double>& residual)
  {
    bool ok = true;
    for (std::size_t n = 0; n + 1 < residual.size(); ++n)
      if (residual[n] < 1e-3 && residual[n] > 1e-7) // asymptotic, above rounding
        ok = ok && residual[n + 1] <= 10.0 * residual[n] * residual[n];
    return ok;
  };
  for (const LawCase& c : rockjoint::testing::library_laws())
  {
    SCOPED_TRACE(c.label);
    TabulatedLaw::Options o;
    o.tolerance = 1e-3; // coarse: knots are far apart, the tangent must still be exact
    const auto table = TabulatedLaw::up_to_stress(*c.law, c.maximum_stress, o);
    for (double target : {0.01 * c.maximum_stress, 0.3 * c.maximum_stress})
    {
      const auto residual = newton(table, target, 1.0);
      ASSERT_LT(residual.back(), 1e-14) << "no convergence";
      EXPECT_LE(residual.size(), 15u);
      EXPECT_TRUE(quadratic(residual)) << "target " << target;
      EXPECT_FALSE(quadratic(newton(table, target, 1.0 + 1e-3))) << "control, target " << target;
    }
  }
}

TEST(TabulatedLaw, HertzianOnsetKeepsRelativeErrorDownToZero)
{
  // σ = c Δ^{3/2}(1 + Δ/L) (k(0+) = 0, GW-type first contact): relative error still bounded
  // at Δ = 1e-30 m, and the table's k ~ Δ^{1/2} like the source.
  rockjoint::testing::HertzianOnsetLaw law(1e12, 0.05e-3);
  TabulatedLaw::Options o;
  o.tolerance = 1e-7;
  const auto table = TabulatedLaw::up_to_stress(law, 30e6, o);
  for (double d : {1e-30, 1e-20, 1e-14, 1e-10, 1e-7})
  {
    const auto exact = law.evaluate(d);
    const auto r = table.evaluate(d);
    EXPECT_NEAR(r.normal_stress, exact.normal_stress, 1e-7 * exact.normal_stress) << d;
    EXPECT_NEAR(r.normal_stiffness, exact.normal_stiffness, 1e-7 * exact.normal_stiffness)
        << d;
  }
}

TEST(TabulatedLaw, BeyondTheTableIsContinuousAndPositive)
{
  BartonBandis law(20e9, 0.3e-3);
  const auto table = TabulatedLaw::up_to_stress(law, 30e6);
  const double dmax = table.table_maximum_closure();
  const double smax = table.table_maximum_stress();
  const double kmax = table.table_end_stiffness();
  // k at the last knot is the source's tangent there (to the tolerance).
  EXPECT_NEAR(kmax, law.normal_stiffness(dmax), 1e-6 * kmax);

  // Continuity of σ and k at Δ_max from both sides.
  const auto below = table.evaluate(dmax * (1 - 1e-12));
  const auto above = table.evaluate(dmax * (1 + 1e-12));
  EXPECT_EQ(below.status, Status::contact);
  EXPECT_EQ(above.status, Status::validity_limit);
  EXPECT_NEAR(below.normal_stress, smax, 1e-10 * smax);
  EXPECT_NEAR(above.normal_stress, smax, 1e-10 * smax);
  EXPECT_NEAR(below.normal_stiffness, kmax, 1e-9 * kmax);
  EXPECT_EQ(above.normal_stiffness, kmax);
  // Linear extension: σ = σ_max + k_max (Δ - Δ_max), k > 0 (also past the source's V_m).
  for (double f : {1.01, 2.0, 10.0})
  {
    const auto r = table.evaluate(f * dmax);
    EXPECT_DOUBLE_EQ(r.normal_stress, smax + kmax * (f - 1) * dmax);
    EXPECT_GT(r.normal_stiffness, 0.0);
  }
  EXPECT_NEAR(table.closure_at_stress(2 * smax), dmax + smax / kmax, 1e-12 * dmax);

  // Opening: σ = k_res Δ with the default k_res = 1e-6 σ_max/Δ_max; σ continuous at 0.
  const double kres = 1e-6 * smax / dmax;
  EXPECT_DOUBLE_EQ(table.residual_stiffness(), kres);
  for (double d : {-1e-12, -1e-6, -1e-3})
  {
    const auto r = table.evaluate(d);
    EXPECT_EQ(r.status, Status::open);
    EXPECT_DOUBLE_EQ(r.normal_stress, kres * d);
    EXPECT_EQ(r.normal_stiffness, kres);
  }
  EXPECT_EQ(table.evaluate(0.0).normal_stress, 0.0);
  EXPECT_NEAR(table.evaluate(1e-15).normal_stress, 0.0, 1e-15 * 20e9 * 1.01);
  EXPECT_NEAR(table.evaluate(1e-15).normal_stiffness, 20e9, 1e-6 * 20e9); // k(0+) = K_ni
  // Through the ClosureLaw interface the opening side is the same (evaluate_open hook).
  const ClosureLaw& base = table;
  EXPECT_DOUBLE_EQ(base.evaluate(-1e-6).normal_stress, kres * -1e-6);
  EXPECT_EQ(base.evaluate(-1e-6).normal_stiffness, kres);
  EXPECT_EQ(base.evaluate(1e-5).normal_stress, table.evaluate(1e-5).normal_stress);

  // k_res = 0: the strict convention, even at Δ = -inf.
  TabulatedLaw::Options strict;
  strict.residual_stiffness = 0.0;
  const auto t0 = TabulatedLaw::up_to_stress(law, 30e6, strict);
  for (double d : {-1e-6, -HUGE_VAL})
  {
    EXPECT_EQ(t0.evaluate(d).normal_stress, 0.0);
    EXPECT_EQ(t0.evaluate(d).normal_stiffness, 0.0);
  }
  EXPECT_EQ(t0.evaluate(std::nan("")).status, Status::invalid_closure);
}

TEST(TabulatedLaw, BatchEqualsPointwiseAndThreadsAgree)
{
  LogarithmicLaw law(0.05e-3, 0.1e6);
  const auto table = TabulatedLaw::up_to_stress(law, 30e6);
  std::vector<double> d = random_closures(1.3 * table.table_maximum_closure(), 5000, 3);
  d.push_back(-1e-5);
  d.push_back(0.0);
  std::vector<double> s(d.size()), k(d.size()), a(d.size());
  std::vector<Status> st(d.size());
  table.evaluate(d, s, k, a, st);
  for (std::size_t i = 0; i < d.size(); ++i)
  {
    const auto r = table.evaluate(d[i]);
    ASSERT_EQ(s[i], r.normal_stress);
    ASSERT_EQ(k[i], r.normal_stiffness);
    ASSERT_EQ(st[i], r.status);
    ASSERT_EQ(a[i], 0.0);
  }
  // Immutable and shared: 4 threads evaluating the same table get the same answers.
  std::vector<std::vector<double>> out(4, std::vector<double>(d.size()));
  std::vector<std::thread> threads;
  for (int w = 0; w < 4; ++w)
    threads.emplace_back(
        [&, w]
        {
          std::vector<double> kk(d.size());
          table.evaluate(d, out[w], kk);
        });
  for (auto& t : threads)
    t.join();
  for (int w = 0; w < 4; ++w)
    EXPECT_EQ(out[w], s);
  std::vector<double> wrong(3);
  EXPECT_THROW(table.evaluate(d, wrong, k), std::invalid_argument);
}

TEST(TabulatedLaw, RejectsBadRangesAndReportsRunaway)
{
  BartonBandis bb(20e9, 0.3e-3);
  ExponentialLaw ex(0.2e-3, 5e6);
  // σ_max beyond the admissible range (Δ(σ) rounds to V_m): clear error naming σ_max.
  for (const ClosureLaw* law : {static_cast<const ClosureLaw*>(&bb),
                                static_cast<const ClosureLaw*>(&ex)})
  {
    try
    {
      TabulatedLaw::up_to_stress(*law, 1e300);
      FAIL() << "no exception for " << law->name();
    }
    catch (const std::domain_error& e)
    {
      EXPECT_NE(std::string(e.what()).find("maximum_stress"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(TabulatedLaw::over_closure_range(bb, 0.3e-3), std::invalid_argument);
  EXPECT_THROW(TabulatedLaw::over_closure_range(bb, -1.0), std::invalid_argument);
  EXPECT_THROW(TabulatedLaw::up_to_stress(bb, std::nan("")), std::invalid_argument);
  TabulatedLaw::Options bad;
  bad.tolerance = 0.5;
  EXPECT_THROW(TabulatedLaw::up_to_stress(bb, 30e6, bad), std::invalid_argument);
  bad.tolerance = 1e-6;
  bad.residual_stiffness = -1.0;
  EXPECT_THROW(TabulatedLaw::up_to_stress(bb, 30e6, bad), std::invalid_argument);

  TabulatedLaw::Options tiny;
  tiny.tolerance = 1e-12;
  tiny.maximum_knots = 40;
  rockjoint::testing::expect_error<std::runtime_error>(
      [&] { TabulatedLaw::up_to_stress(bb, 30e6, tiny); },
      {"maximum_knots = 40", "worst interval"});

  // A law with history holds more than one curve: refused, naming what to do instead.
  const NormalHysteresis history(std::make_shared<BartonBandis>(bb), 0.25, 3.0);
  rockjoint::testing::expect_error([&] { TabulatedLaw::up_to_stress(history, 30e6); },
                                   {"normal_hysteresis", "has history", "virgin"});
  rockjoint::testing::expect_error([&] { TabulatedLaw::over_closure_range(history, 0.1e-3); },
                                   "has history");
}

TEST(TabulatedLaw, IndexFindsTheSegmentEvenInCrowdedCells)
{
  // Hand-made table of σ = a Δ + b Δ² + c Δ³, which the cubic segments reproduce exactly,
  // with knots crowding geometrically towards Δ = 1 (spacing down to 2^-40: far below any
  // index cell, so the bisection fallback runs). Reference: a linear scan for the segment.
  const double a = 3.0, b = 2.0, c = 0.5;
  auto sigma = [&](double x) { return x * (a + x * (b + x * c)); };
  auto tangent = [&](double x) { return a + x * (2 * b + x * 3 * c); };
  LawTable tab;
  tab.source_model = "cubic_polynomial";
  tab.tolerance = 1e-6;
  std::vector<double> knots{0.0};
  for (int i = 1; i <= 40; ++i)
    knots.push_back(1.0 - std::ldexp(1.0, -i));
  knots.push_back(1.0);
  for (double x : knots)
  {
    tab.closure.push_back(x);
    tab.normal_stress.push_back(sigma(x));
    tab.stiffness.push_back(tangent(x)); // k_0 = k(0+) = a
  }
  const TabulatedLaw law(tab);

  std::vector<double> queries;
  std::mt19937_64 gen(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 20000; ++i)
    queries.push_back(i % 2 ? u(gen) : 1.0 - std::pow(2.0, -45.0 * u(gen)));
  for (double x : knots)
    for (double q : {std::nextafter(x, -1.0), x, std::nextafter(x, 2.0)})
      if (q > 0.0 && q <= 1.0)
        queries.push_back(q);
  const double eps = std::numeric_limits<double>::epsilon();
  for (double x : queries)
  {
    std::size_t seg = 0;
    while (seg + 2 < knots.size() && knots[seg + 1] <= x)
      ++seg;
    double s_ref, k_ref;
    const auto segment
        = hermite::make_table_segment(tab.closure, tab.normal_stress, tab.stiffness, seg);
    if (seg == 0)
      hermite::evaluate_first(segment, x, s_ref, k_ref);
    else
      hermite::evaluate(segment, x, s_ref, k_ref);
    const auto r = law.evaluate(x);
    ASSERT_EQ(r.normal_stress, s_ref) << "Δ = " << x;
    ASSERT_EQ(r.normal_stiffness, k_ref) << "Δ = " << x;
    if (seg > 0)
    {
      // Exact for the cubic up to rounding; k = p'(τ)/h: the coefficients' rounding (a few
      // ulps of σ) is amplified by 1/h in the 2^-40-wide segments.
      const double h = knots[seg + 1] - knots[seg];
      ASSERT_NEAR(r.normal_stress, sigma(x), 1e-14 * sigma(x)) << x;
      ASSERT_NEAR(r.normal_stiffness, tangent(x),
                  1e-13 * tangent(x) + 16 * eps * sigma(x) / h)
          << x;
    }
  }
}

TEST(TabulatedLaw, KinkedEmpiricalLawTabulatesLooselyAndRefusesClearly)
{
  // An empirical summit list has a kink in k (a new (Δ - Δ_i)^{1/2} term) wherever a summit
  // comes into contact: a smooth interpolant reaches 1e-3 but not 1e-6, and says why.
  std::mt19937_64 gen(2);
  std::normal_distribution<double> height(0.0, 0.05e-3);
  std::uniform_real_distribution<double> radius(1e-3, 4e-3);
  std::vector<double> z(50), r(50);
  for (std::size_t i = 0; i < z.size(); ++i)
  {
    z[i] = height(gen);
    r[i] = radius(gen);
  }
  GreenwoodWilliamson law(composite_modulus(50e9, 0.25), EmpiricalSummits(z, r, 50 / 0.3e6));
  TabulatedLaw::Options loose;
  loose.tolerance = 1e-3;
  const auto table = TabulatedLaw::up_to_stress(law, 30e6, loose);
  EXPECT_EQ(table.table().stiffness[0], 0.0); // k(0+) = 0: Hertzian onset, one summit touches
  for (double d : random_closures(table.table_maximum_closure(), 10000, 8))
  {
    const auto exact = law.evaluate(d);
    const auto t = table.evaluate(d);
    ASSERT_NEAR(t.normal_stress, exact.normal_stress, 1e-3 * exact.normal_stress) << d;
    ASSERT_NEAR(t.normal_stiffness, exact.normal_stiffness, 1e-3 * exact.normal_stiffness) << d;
  }
  TabulatedLaw::Options tight;
  tight.tolerance = 1e-6;
  try
  {
    TabulatedLaw::up_to_stress(law, 30e6, tight);
    FAIL() << "no exception";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("not smooth enough"), std::string::npos) << e.what();
  }
}

TEST(TabulatedLaw, StressBeyondTheTangJiaoValidityLimitIsRefused)
{
  const AsperityParameters p{composite_modulus(50e9, 0.25), 0.3e6, 2.5e-3, 0.05e-3};
  TangJiao law(std::make_shared<GreenwoodWilliamson>(p));
  try
  {
    TabulatedLaw::up_to_stress(law, 1e12);
    FAIL() << "no exception";
  }
  catch (const std::domain_error& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("maximum_stress"), std::string::npos) << what;
    EXPECT_NE(what.find("tang_jiao"), std::string::npos) << what;
  }
  EXPECT_THROW(TabulatedLaw::over_closure_range(law, law.maximum_closure()),
               std::invalid_argument);
}

TEST(TabulatedLawFile, RoundTripIsBitExact)
{
  for (const LawCase& c : rockjoint::testing::library_laws())
  {
    SCOPED_TRACE(c.label);
    const auto table = TabulatedLaw::up_to_stress(*c.law, c.maximum_stress);
    const std::string path = temp_path("roundtrip.rjt");
    table.save(path);
    const auto back = TabulatedLaw::load(path);
    const LawTable& a = table.table();
    const LawTable& b = back.table();
    EXPECT_EQ(a.closure, b.closure); // vector== compares every double exactly
    EXPECT_EQ(a.normal_stress, b.normal_stress);
    EXPECT_EQ(a.stiffness, b.stiffness);
    EXPECT_EQ(a.tolerance, b.tolerance);
    EXPECT_EQ(a.checked_error_stress, b.checked_error_stress);
    EXPECT_EQ(a.checked_error_stiffness, b.checked_error_stiffness);
    EXPECT_EQ(a.residual_stiffness, b.residual_stiffness);
    EXPECT_EQ(a.source_seating_stress, b.source_seating_stress);
    EXPECT_EQ(b.source_model, c.law->name());
    const auto params = c.law->parameters();
    ASSERT_EQ(b.source_parameters.size(), params.size());
    for (std::size_t i = 0; i < params.size(); ++i)
    {
      EXPECT_EQ(b.source_parameters[i].name, params[i].name);
      EXPECT_EQ(b.source_parameters[i].value, params[i].value);
      EXPECT_EQ(b.source_parameters[i].unit, params[i].unit);
    }
    std::vector<double> d = random_closures(1.2 * table.table_maximum_closure(), 10000, 11);
    d.push_back(-1e-4);
    for (double x : d)
    {
      const auto r1 = table.evaluate(x), r2 = back.evaluate(x);
      ASSERT_EQ(r1.normal_stress, r2.normal_stress) << x;
      ASSERT_EQ(r1.normal_stiffness, r2.normal_stiffness) << x;
    }
    // Saving the loaded table reproduces the file byte for byte.
    const std::string again = temp_path("roundtrip2.rjt");
    back.save(again);
    EXPECT_EQ(read_lines(path), read_lines(again));
    std::remove(path.c_str());
    std::remove(again.c_str());
  }
}

TEST(TabulatedLawFile, MalformedFilesFailWithAClearMessage)
{
  BartonBandis law(20e9, 0.3e-3);
  TabulatedLaw::Options o;
  o.tolerance = 1e-3;
  const auto table = TabulatedLaw::up_to_stress(law, 30e6, o);
  const std::string good = temp_path("good.rjt");
  table.save(good);
  const auto lines = read_lines(good);
  const std::size_t knot3 = find_line(lines, "knot 3 ");

  struct Corruption
  {
    std::string label;
    std::function<void(std::vector<std::string>&)> edit;
    std::vector<std::string> expected; ///< fragments the message must contain
  };
  auto field = [](const std::string& line, int index)
  {
    std::istringstream w(line);
    std::string f;
    for (int i = 0; i <= index; ++i)
      w >> f;
    return f;
  };
  const std::vector<Corruption> cases{
      {"truncated", [&](auto& l) { l.resize(knot3 + 1); }, {"truncated", "knots"}},
      {"no end", [&](auto& l) { l.pop_back(); }, {"truncated", "'end'"}},
      {"wrong magic", [&](auto& l) { l[0] = "PK\x03\x04 zipfile"; }, {"line 1", "not a rockjoint"}},
      {"wrong version", [&](auto& l) { l[0] = "rockjoint-law-table 2"; },
       {"line 1", "version '2'", "reads version 1"}},
      {"NaN knot",
       [&](auto& l) { l[knot3] = "knot 3 " + field(l[knot3], 2) + " nan " + field(l[knot3], 4); },
       {"line " + std::to_string(knot3 + 1), "knot 3 normal_stress", "finite"}},
      {"non-monotone knots",
       [&](auto& l)
       {
         // knot 3 gets knot 2's stress: σ no longer strictly increasing.
         const std::size_t k2 = knot3 - 1;
         l[knot3] = "knot 3 " + field(l[knot3], 2) + " " + field(l[k2], 3) + " "
                    + field(l[knot3], 4);
       },
       {"line " + std::to_string(knot3 + 1), "strictly increasing"}},
      {"missing field", [&](auto& l) { l.erase(l.begin() + find_line(l, "tolerance ")); },
       {"missing field 'tolerance'"}},
      {"garbage number",
       [&](auto& l) { l[find_line(l, "residual_stiffness ")] = "residual_stiffness 12abc Pa/m"; },
       {"residual_stiffness", "not a hexadecimal float"}},
      {"range disagrees with the knots",
       [&](auto& l)
       {
         const std::size_t i = find_line(l, "table_maximum_stress ");
         l[i] = "table_maximum_stress 0x1p+30 Pa";
       },
       {"line " + std::to_string(find_line(lines, "table_maximum_stress ") + 1),
        "table_maximum_stress", "disagrees with the last knot"}},
      {"signed %-escape",  // from_chars into a signed int once accepted "%-1" as a byte
       [&](auto& l) { l[find_line(l, "source_model ")] = "source_model bb%-1"; },
       {"source_model", "malformed %-escape"}},
      {"foreign interpolation",
       [&](auto& l) { l[find_line(l, "interpolation ")] = "interpolation linear"; },
       {"interpolation", "linear"}},
  };
  for (const Corruption& c : cases)
  {
    SCOPED_TRACE(c.label);
    auto edited = lines;
    c.edit(edited);
    const std::string path = temp_path("bad.rjt");
    write_lines(path, edited);
    try
    {
      TabulatedLaw::load(path);
      ADD_FAILURE() << "no exception";
    }
    catch (const std::runtime_error& e)
    {
      const std::string what = e.what();
      EXPECT_NE(what.find(path), std::string::npos) << what;
      for (const auto& fragment : c.expected)
        EXPECT_NE(what.find(fragment), std::string::npos) << "'" << fragment << "' in: " << what;
    }
    std::remove(path.c_str());
  }
  EXPECT_THROW(TabulatedLaw::load(temp_path("does_not_exist.rjt")), std::runtime_error);
  std::remove(good.c_str());
}

TEST(TabulatedLaw, ResidualStiffnessIsSeenThroughTheBaseInterface)
{
  // An FE code holding only a `const ClosureLaw&` must get the same opening branch
  // σ = k_res Δ, k = k_res as the table called directly (evaluate_open hook).
  BartonBandis source(10e9, 0.3e-3);
  TabulatedLaw::Options options;
  options.residual_stiffness = 1e3;
  const auto table = TabulatedLaw::up_to_stress(source, 30e6, options);
  const ClosureLaw& base = table;
  for (double d : {0.0, -1e-9, -1e-3})
  {
    const auto direct = table.evaluate(d);
    const auto through = base.evaluate(d);
    EXPECT_EQ(through.normal_stress, 1e3 * d);
    EXPECT_EQ(through.normal_stiffness, 1e3);
    EXPECT_EQ(through.status, Status::open);
    EXPECT_EQ(through.normal_stress, direct.normal_stress);
    EXPECT_EQ(through.normal_stiffness, direct.normal_stiffness);
  }
  std::vector<double> d{-1e-4, 1e-5}, s(2), k(2);
  base.evaluate(d, s, k);
  EXPECT_EQ(s[0], -1e3 * 1e-4);
  EXPECT_EQ(k[0], 1e3);
}

// fuzz/regressions/law_table/subnormal_range.rjt: a valid-looking table over subnormal closures
// made the segment index's cell numbers NaN (undefined conversion, UBSan in fuzz/fuzz_law_table).
TEST(TabulatedLawFile, SubnormalRangeIsRefusedNamingTheFile)
{
  const std::string path = temp_path("subnormal.rjt");
  write_lines(path, {"rockjoint-law-table 1", "units closure=m stress=Pa stiffness=Pa/m",
                     "interpolation monotone_hermite_sqrt_first_segment",
                     "compression_extension linear_end_tangent",
                     "opening_extension residual_stiffness", "source_model linear",
                     "source_seating_stress 0x0p+0 Pa", "tolerance 0x1p-7",
                     "checked_error_stress 0x0p+0", "checked_error_stiffness 0x0p+0",
                     "residual_stiffness 0x0p+0 Pa/m", "table_maximum_closure 0x1p-1029 m",
                     "table_maximum_stress 0x1p-1029 Pa", "knots 3", "knot 0 0x0p+0 0x0p+0 0x1p+0",
                     "knot 1 0x1p-1030 0x1p-1030 0x1p+0", "knot 2 0x1p-1029 0x1p-1029 0x1p+0",
                     "end"});
  rockjoint::testing::expect_error<std::runtime_error>([&] { TabulatedLaw::load(path); },
                                                       {path, "table_maximum_closure",
                                                        "too small to index"});
  std::remove(path.c_str());
}
