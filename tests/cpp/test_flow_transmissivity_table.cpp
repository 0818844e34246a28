// SPDX-License-Identifier: MIT
// T(Δ) tabulated from knots (flow/transmissivity_table.hpp): through the knots, exact on data
// whose ln T is linear in Δ (PCHIP reproduces linear data), monotone between uneven knots, the
// closed forms outside the knots (rigid separation below, exponential decay beyond, a linear
// fall to a knot with T = 0), bad knots named.
#include "expect_error.hpp"

#include <rockjoint/flow/transmissivity_table.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using rockjoint::flow::TransmissivityTable;
using rockjoint::testing::expect_error;

namespace
{
/// T = T0 exp(-Δ/a) at uneven knots: the table is that exponential between and beyond them.
TEST(TransmissivityTable, ReproducesAnExponentialDecayBetweenAndBeyondTheKnots)
{
  const double t0 = 1e-12, a = 2e-5;
  const std::vector<double> d{0.0, 1e-6, 4e-6, 1.2e-5, 3e-5, 5e-5};
  std::vector<double> t;
  for (const double x : d)
    t.push_back(t0 * std::exp(-x / a));
  const TransmissivityTable table(d, t);
  for (double x = 0.0; x <= 8e-5; x += 7e-7)
    EXPECT_NEAR(table.transmissivity(x), t0 * std::exp(-x / a), 1e-10 * t0 * std::exp(-x / a)) << x;
}

/// Below the first knot the walls separate rigidly: e_h = e_h(Δ0) + Δ0 - Δ.
TEST(TransmissivityTable, OpensAsParallelSeparationBelowTheFirstKnot)
{
  const double eh0 = 1e-4, d0 = 2e-6;
  const TransmissivityTable table(std::vector<double>{d0, 1e-5}, std::vector<double>{eh0 * eh0 * eh0 / 12.0, 1e-14});
  for (const double opening : {0.0, 1e-6, 5e-5})
  {
    const double e = eh0 + opening;
    EXPECT_NEAR(table.transmissivity(d0 - opening), e * e * e / 12.0, 1e-12 * e * e * e);
  }
}

/// Uneven knots with a sharp fall: the interpolant stays between its knots' values, falls
/// monotonically, and passes through every knot; a knot with T = 0 ends it linearly.
TEST(TransmissivityTable, IsMonotoneThroughTheKnotsAndEndsAtAZero)
{
  const std::vector<double> d{0.0, 1e-6, 1.5e-6, 8e-6, 9e-6, 2e-5, 2.5e-5};
  const std::vector<double> t{1e-11, 9e-12, 2e-12, 1.9e-12, 1e-15, 1e-16, 0.0};
  const TransmissivityTable table(d, t);
  for (std::size_t i = 0; i < d.size(); ++i)
    EXPECT_NEAR(table.transmissivity(d[i]), t[i], 1e-12 * t[0]);
  double previous = table.transmissivity(0.0);
  for (double x = 1e-8; x < 3e-5; x += 1e-8)
  {
    const double v = table.transmissivity(x);
    EXPECT_LE(v, previous * (1 + 1e-14)) << x;
    previous = v;
  }
  EXPECT_NEAR(table.transmissivity(2.25e-5), 0.5e-16, 1e-28) << "linear from the last positive knot to 0";
  EXPECT_EQ(table.transmissivity(3e-5), 0.0);
  EXPECT_TRUE(std::isnan(table.transmissivity(NAN)));
}

TEST(TransmissivityTable, BadKnotsAreNamed)
{
  using V = std::vector<double>;
  expect_error([] { TransmissivityTable(V{0.0, 1e-6}, V{1e-12}); }, "2 closures and 1");
  expect_error([] { TransmissivityTable(V{0.0, 1e-6, 2e-6}, V{1e-12, 2e-12, 1e-13}); },
               {"knot 1", "must not increase"});
  expect_error([] { TransmissivityTable(V{0.0, 1e-6, 1e-6}, V{1e-12, 1e-13, 1e-14}); },
               {"knot 2", "strictly increasing"});
  expect_error([] { TransmissivityTable(V{0.0, 1e-6}, V{0.0, 0.0}); }, {"knot 0", "first transmissivity"});
  expect_error([] { TransmissivityTable(V{0.0, 1e-6}, V{1e-12, -1e-13}); }, {"knot 1", ">= 0"});
  expect_error([] { TransmissivityTable(V{0.0, NAN}, V{1e-12, 1e-13}); }, {"knot 1", "finite"});
}
} // namespace
