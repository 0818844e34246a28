// SPDX-License-Identifier: MIT
// The hysteretic normal law (normal_hysteresis.hpp, H1-H4) against its closed forms computed here
// from the Barton-Bandis hyperbola: virgin loading, the unloading branch and its permanent
// closure, continuity at the largest closure, tangents against central differences on each
// branch and one-sided at the switch, the stress-path inverse, and bad parameters.
#include <rockjoint/constitutive/barton_bandis.hpp>
#include <rockjoint/constitutive/normal_hysteresis.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "expect_error.hpp"

using namespace rockjoint::constitutive;

namespace
{
constexpr double kni = 10e9, vm = 0.5e-3; // 10 MPa/mm, 0.5 mm
constexpr double r = 0.25, m = 3.0;
double virgin(double d) { return kni * d / (1 - d / vm); }

NormalHysteresis make() { return NormalHysteresis(std::make_shared<BartonBandis>(kni, vm), r, m); }
} // namespace

TEST(NormalHysteresis, LoadingPastTheMaximumIsTheVirginCurve)
{
  const NormalHysteresis h = make();
  for (double d : {1e-6, 0.1e-3, 0.3e-3, 0.45e-3})
  {
    const HistoryResponse a = h.evaluate_with_history(d, 0.0);         // virgin joint
    const HistoryResponse b = h.evaluate_with_history(d, 0.5 * d);     // past an earlier, smaller maximum
    EXPECT_TRUE(a.on_virgin_curve && b.on_virgin_curve);
    EXPECT_NEAR(a.response.normal_stress, virgin(d), 1e-13 * virgin(d));
    EXPECT_EQ(b.response.normal_stress, a.response.normal_stress);
    EXPECT_EQ(b.maximum_closure, d); // Δ_m follows the closure
    EXPECT_DOUBLE_EQ(b.permanent_closure, r * d);
  }
}

TEST(NormalHysteresis, UnloadingBranchClosedForm)
{
  const NormalHysteresis h = make();
  const double dm = 0.3e-3, dp = r * dm, top = virgin(dm);
  for (double d : {0.08e-3, 0.1e-3, 0.2e-3, 0.29e-3})
  {
    const double x = (d - dp) / (dm - dp);
    const HistoryResponse u = h.evaluate_with_history(d, dm);
    EXPECT_FALSE(u.on_virgin_curve);
    EXPECT_EQ(u.maximum_closure, dm);
    EXPECT_NEAR(u.response.normal_stress, top * std::pow(x, m), 1e-13 * top);
    EXPECT_NEAR(u.response.normal_stiffness, m * top * std::pow(x, m - 1) / (dm - dp),
                1e-12 * m * top / (dm - dp));
    EXPECT_LT(u.response.normal_stress, virgin(d)) << "unloading lies below the virgin curve in σ";
  }
  // Open below the permanent closure (H3), zero at it.
  EXPECT_EQ(h.evaluate_with_history(dp, dm).response.normal_stress, 0.0);
  EXPECT_EQ(h.evaluate_with_history(0.5 * dp, dm).response.normal_stress, 0.0);
  EXPECT_EQ(h.evaluate_with_history(0.5 * dp, dm).response.status, Status::open);
  // Continuous at Δ_m, and stiffer there than loading by (H4): m σ_m / ((1 - r) Δ_m k_v).
  const double below = h.evaluate_with_history(dm * (1 - 1e-12), dm).response.normal_stress;
  EXPECT_NEAR(below, top, 1e-9 * top);
  const double kv = kni / std::pow(1 - dm / vm, 2);
  const double ratio = m * top / ((1 - r) * dm) / kv;
  EXPECT_NEAR(h.evaluate_with_history(dm * (1 - 1e-9), dm).response.normal_stiffness / kv, ratio, 1e-6);
}

TEST(NormalHysteresis, TangentIsTheDerivativeOnEachBranch)
{
  const NormalHysteresis h = make();
  const double dm = 0.3e-3;
  auto fd = [&](double d, double e)
  {
    return (h.evaluate_with_history(d + e, dm).response.normal_stress
            - h.evaluate_with_history(d - e, dm).response.normal_stress) / (2 * e);
  };
  for (double d : {0.1e-3, 0.2e-3, 0.28e-3, 0.35e-3, 0.45e-3}) // branch and virgin
  {
    // Past Δ_m the converged maximum is exceeded: the tangent is the virgin one.
    const double k = h.evaluate_with_history(d, dm).response.normal_stiffness;
    EXPECT_NEAR(fd(d, 1e-9), k, 1e-6 * k) << "closure " << d;
  }
  // Across the switch at Δ_m: one-sided differences give the branch tangent below and the
  // virgin tangent above; the consistent tangent on each side is the matching one.
  const double e = 1e-10;
  const double s0 = h.evaluate_with_history(dm, dm).response.normal_stress;
  const double below = (s0 - h.evaluate_with_history(dm - e, dm).response.normal_stress) / e;
  const double above = (h.evaluate_with_history(dm + e, dm).response.normal_stress - s0) / e;
  EXPECT_NEAR(below, h.evaluate_with_history(dm - e, dm).response.normal_stiffness, 1e-5 * below);
  EXPECT_NEAR(above, h.evaluate_with_history(dm + e, dm).response.normal_stiffness, 1e-5 * above);
  EXPECT_GT(below, above); // unloading is the stiffer side here (ratio (H4) > 1)
}

TEST(NormalHysteresis, StressPathFollowsTheCycle)
{
  const NormalHysteresis h = make();
  const std::vector<double> s{0.0, 4e6, 8e6, 4e6, 0.0, 4e6, 8e6, 10e6, 2e6};
  const std::vector<double> c = h.closure_path(s);
  const double d8 = 8e6 / (kni + 8e6 / vm), d10 = 10e6 / (kni + 10e6 / vm); // virgin inverses
  EXPECT_NEAR(c[2], d8, 1e-12 * d8);
  EXPECT_NEAR(c[4], r * d8, 1e-12 * d8);   // permanent closure after the first cycle
  EXPECT_NEAR(c[6], d8, 1e-12 * d8);       // reloading retraces the branch to the maximum
  EXPECT_NEAR(c[7], d10, 1e-12 * d10);     // then the virgin curve
  EXPECT_NEAR(c[3], c[5], 1e-18);          // same branch down and up
  // Every point of the path carries its stress under the history reached before it.
  double dm = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i)
  {
    EXPECT_NEAR(h.evaluate_with_history(c[i], dm).response.normal_stress, s[i], 1e-9 * 10e6) << i;
    dm = std::max(dm, c[i]);
  }
  EXPECT_THROW(h.closure_path(std::vector<double>{1e6, -1.0}), std::invalid_argument);
}

TEST(NormalHysteresis, BadParametersAndInput)
{
  auto bb = std::make_shared<BartonBandis>(kni, vm);
  rockjoint::testing::expect_error([&] { NormalHysteresis(bb, 1.0, 2.0); }, "permanent_fraction");
  rockjoint::testing::expect_error([&] { NormalHysteresis(bb, -0.1, 2.0); }, "permanent_fraction");
  rockjoint::testing::expect_error([&] { NormalHysteresis(bb, 0.2, 0.5); }, "unloading_exponent");
  rockjoint::testing::expect_error([&] { NormalHysteresis(bb, 0.2, std::nan("")); },
                                "unloading_exponent");
  rockjoint::testing::expect_error([&] { NormalHysteresis(nullptr, 0.2, 2.0); }, "virgin");
  const NormalHysteresis h(bb, r, m);
  EXPECT_EQ(h.evaluate_with_history(std::nan(""), 1e-4).response.status, Status::invalid_closure);
  EXPECT_EQ(h.evaluate_with_history(1e-4, std::nan("")).response.status, Status::invalid_closure);
}

// A law with history through the ClosureLaw interface: without history it is the virgin curve
// (the closed form above), its inverse is the virgin inverse, and it carries the branches only
// through evaluate_with_history; an elastic law's evaluate_with_history is its own curve.
TEST(NormalHysteresis, IsALawWithHistory)
{
  auto bb = std::make_shared<BartonBandis>(kni, vm);
  const std::shared_ptr<const ClosureLaw> law = std::make_shared<NormalHysteresis>(bb, r, m);
  EXPECT_TRUE(law->has_history());
  EXPECT_FALSE(bb->has_history());
  EXPECT_EQ(law->name(), "normal_hysteresis");
  EXPECT_EQ(law->maximum_closure(), vm);
  for (double d : {0.02e-3, 0.1e-3, 0.3e-3})
  {
    EXPECT_NEAR(law->normal_stress(d), virgin(d), 1e-12 * virgin(d)) << d;
    EXPECT_NEAR(law->closure_at_stress(virgin(d)), d, 1e-12 * d) << d;
    const HistoryResponse plain = bb->evaluate_with_history(d, 0.3e-3);
    EXPECT_NEAR(plain.response.normal_stress, virgin(d), 1e-12 * virgin(d));
    EXPECT_EQ(plain.maximum_closure, std::max(d, 0.3e-3));
    EXPECT_EQ(plain.permanent_closure, 0.0);
  }
  EXPECT_EQ(law->normal_stress(-1e-5), 0.0); // open: the virgin law's opening branch
  const std::vector<Parameter> p = law->parameters();
  ASSERT_EQ(p.size(), bb->parameters().size() + 2);
  EXPECT_EQ(p[p.size() - 2].name, "permanent_fraction");
  EXPECT_EQ(p.back().value, m);
  // Unloading from Δ_m = 0.3 mm to half of it: the branch (H2), not the virgin curve.
  const double dm = 0.3e-3, d = 0.15e-3, dp = r * dm;
  const double branch = virgin(dm) * std::pow((d - dp) / (dm - dp), m);
  EXPECT_NEAR(law->evaluate_with_history(d, dm).response.normal_stress, branch, 1e-12 * branch);
  rockjoint::testing::expect_error([&] { NormalHysteresis(law, 0.2, 2.0); }, "has history");
}
