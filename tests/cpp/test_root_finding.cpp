// SPDX-License-Identifier: MIT
// The shared root finder (root_finding.hpp), against roots known in closed form or as
// published constants.
#include <rockjoint/constitutive/root_finding.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

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

TEST(RootFinding, NewtonFindsTheDottieNumber)
{
  // x = cos x, the fixed point of the cosine: 0.739085133215160641655... (OEIS A003957).
  const auto root = find_root([](double x) { return Residual{x - std::cos(x), 1.0 + std::sin(x)}; },
                              0.0, 1.0, 0.0);
  EXPECT_TRUE(root.converged);
  EXPECT_NEAR(root.x, 0.739085133215160641655, 2e-16);
  EXPECT_LE(root.evaluations, 8);
}

TEST(RootFinding, AnEndOfTheWrongSignIsReportedAsNotBracketed)
{
  // r(x) = x - 2 on [0, 1] has no root there: the caller's end values say so, and the finder
  // refuses without evaluating instead of returning an end as if it were a root.
  int calls = 0;
  auto r = [&](double x)
  {
    ++calls;
    return Residual{x - 2.0, 1.0};
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto low_end_positive = find_root(r, 0.0, 1.0, nan, {}, 1.0, nan);
  const auto high_end_negative = find_root(r, 0.0, 1.0, nan, {}, nan, -1.0);
  const auto reversed = find_root(r, 1.0, 0.0, 0.5);
  const auto infinite = find_root(r, 0.0, std::numeric_limits<double>::infinity(), 0.5);
  for (const auto& root : {low_end_positive, high_end_negative, reversed, infinite})
  {
    EXPECT_FALSE(root.bracketed);
    EXPECT_FALSE(root.converged);
    EXPECT_TRUE(std::isnan(root.x));
    EXPECT_EQ(root.evaluations, 0);
  }
  EXPECT_EQ(calls, 0);
  // A bracketed call reports bracketed.
  EXPECT_TRUE(find_root(r, 0.0, 3.0, 0.0).bracketed);
}

TEST(RootFinding, GrowTowardsDoublesOrHalvesTheDistanceToTheLimit)
{
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(root_finding::grow_towards(0.25, inf), 0.5);
  EXPECT_EQ(root_finding::grow_towards(0.5, 1.0), 0.75);
  // From 1/2 towards 1 the distance is 2^-(k+1) after k steps: it falls below 1e-15 at
  // k = 49 (2^-50 ≈ 8.9e-16), where the limit itself is returned.
  double x = 0.5;
  int steps = 0;
  while (x != 1.0 && steps < 100)
  {
    x = root_finding::grow_towards(x, 1.0);
    ++steps;
  }
  EXPECT_EQ(x, 1.0);
  EXPECT_EQ(steps, 49);
}
