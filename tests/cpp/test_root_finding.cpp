// The shared root finder (root_finding.hpp) and the monotone interpolant of sampled data
// (monotone_hermite.hpp data_slopes), against roots and functions known in closed form.
#include <rockjoint/constitutive/monotone_hermite.hpp>
#include <rockjoint/constitutive/root_finding.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

using namespace rockjoint::constitutive;
using root_finding::find_root;
using root_finding::Residual;

TEST(RootFinding, NewtonFindsSqrtTwoToRoundOff)
{
  // r(x) = x² - 2 on [0, 2]: root √2.
  const auto root = find_root([](double x) { return Residual{x * x - 2.0, 2.0 * x}; }, 0.0, 2.0, 1.0);
  EXPECT_TRUE(root.converged);
  EXPECT_NEAR(root.x, std::numbers::sqrt2, 4e-16);
  EXPECT_LE(root.evaluations, 8); // quadratic convergence from x0 = 1
}

TEST(RootFinding, NewtonThatLeavesTheBracketFallsBackToBisection)
{
  // r(x) = atan(x - 1): Newton from x0 = 5 overshoots far outside [-10, 10]; the safeguard
  // keeps every iterate inside and the root 1 is found.
  int outside = 0;
  const auto root = find_root(
      [&](double x)
      {
        outside += (x < -10.0 || x > 10.0);
        return Residual{std::atan(x - 1.0), 1.0 / (1.0 + (x - 1.0) * (x - 1.0))};
      },
      -10.0, 10.0, 5.0);
  EXPECT_TRUE(root.converged);
  EXPECT_EQ(outside, 0);
  EXPECT_NEAR(root.x, 1.0, 1e-14);
}

TEST(RootFinding, BisectionWithoutSlopeReturnsATightBracket)
{
  // A step function: r = -1 for x < π/4, +1 from π/4 on. No slope: bisection; the bracket
  // shrinks to the jump and keeps its sides.
  const double jump = std::numbers::pi / 4.0;
  const auto root = find_root([&](double x) { return Residual{x < jump ? -1.0 : 1.0}; }, 0.0, 1.0,
                              std::nan(""));
  EXPECT_TRUE(root.converged);
  EXPECT_LT(root.lo, jump);
  EXPECT_GE(root.hi, jump);
  EXPECT_LE(root.hi - root.lo, 2e-15);
}

TEST(RootFinding, IllinoisIsExactOnAnAffineResidualInOneStep)
{
  root_finding::Options options;
  options.secant = true;
  const auto root = find_root([](double x) { return Residual{3.0 * x - 1.0}; }, 0.0, 1.0,
                              std::nan(""), options, -1.0, 2.0);
  EXPECT_NEAR(root.x, 1.0 / 3.0, 1e-16);
  EXPECT_LE(root.evaluations, 2);
}

TEST(RootFinding, IllinoisConvergesSuperlinearlyOnACurvedResidual)
{
  // r(x) = e^x - 2: root ln 2; plain regula falsi stalls on one side, Illinois does not.
  root_finding::Options options;
  options.secant = true;
  options.residual_tolerance = 1e-15;
  const auto root = find_root([](double x) { return Residual{std::exp(x) - 2.0}; }, 0.0, 3.0,
                              std::nan(""), options, -1.0, std::exp(3.0) - 2.0);
  EXPECT_TRUE(root.converged);
  EXPECT_NEAR(root.x, std::numbers::ln2, 1e-15);
  EXPECT_LE(root.evaluations, 20);
}

TEST(RootFinding, RunningOutOfIterationsIsReportedNotThrown)
{
  root_finding::Options options;
  options.maximum_iterations = 3;
  const auto root = find_root([](double x) { return Residual{x - 0.123456789}; }, 0.0, 1.0,
                              std::nan(""), options);
  EXPECT_FALSE(root.converged);
  EXPECT_EQ(root.evaluations, 3);
  EXPECT_LE(root.lo, 0.123456789);
  EXPECT_GE(root.hi, 0.123456789);
}

TEST(MonotoneHermite, DataSlopesReproduceALineAndKeepMonotoneDataMonotone)
{
  // Linear data: every slope is the line's slope, so the interpolant is the line.
  std::vector<double> x{0.0, 0.1, 0.35, 0.4, 1.0}, y(5), m(5);
  for (std::size_t i = 0; i < x.size(); ++i)
    y[i] = 2.0 + 3.0 * x[i];
  hermite::data_slopes(x, y, m);
  for (double mi : m)
    EXPECT_NEAR(mi, 3.0, 1e-14);
  // Steep-then-flat monotone data (a plateau): the interpolant never decreases and is flat
  // on the plateau.
  std::vector<double> yp{0.0, 0.9, 1.0, 1.0, 1.0}, mp(5);
  hermite::data_slopes(x, yp, mp);
  double previous = -1.0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i)
  {
    const hermite::Segment seg
        = hermite::make_segment(x[i], x[i + 1], yp[i], yp[i + 1], mp[i], mp[i + 1]);
    for (int k = 0; k <= 100; ++k)
    {
      const double xi = x[i] + (x[i + 1] - x[i]) * k / 100.0;
      double v, dv;
      hermite::evaluate(seg, xi, v, dv);
      EXPECT_GE(v, previous - 1e-15) << "at x = " << xi;
      EXPECT_GE(dv, -1e-13);
      if (i >= 2)
        EXPECT_DOUBLE_EQ(v, 1.0);
      previous = v;
    }
  }
}
