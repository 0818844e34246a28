// SPDX-License-Identifier: MIT
// Barton-Bandis, logarithmic and exponential laws against their closed forms (theory §6),
// the open branch, tangents against central differences, inverses and bad input.
#include <rockjoint/constitutive/barton_bandis.hpp>
#include <rockjoint/constitutive/empirical_laws.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "expect_error.hpp"
#include "law_checks.hpp"

using namespace rockjoint::constitutive;

TEST(BartonBandis, MatchesHyperbolaAndItsInverse)
{
  const double kni = 20e9, vm = 0.3e-3; // 20 MPa/mm, 0.3 mm
  BartonBandis law(kni, vm);
  for (double d : {1e-9, 1e-6, 0.1e-3, 0.25e-3, 0.299e-3})
  {
    const double sigma = kni * d / (1 - d / vm);
    EXPECT_NEAR(law.normal_stress(d), sigma, 1e-13 * sigma) << "closure " << d;
    // k = K_ni (1 + σ/(K_ni V_m))², the form quoted by Bandis et al.
    const double k = kni * std::pow(1 + sigma / (kni * vm), 2);
    EXPECT_NEAR(law.normal_stiffness(d), k, 1e-12 * k);
    EXPECT_NEAR(law.closure_at_stress(sigma), d, 1e-12 * d);
  }
}

TEST(BartonBandis, BeyondMaximumClosureIsReportedNotGarbage)
{
  BartonBandis law(20e9, 0.3e-3);
  const auto r = law.evaluate(0.3e-3);
  EXPECT_EQ(r.status, Status::beyond_maximum_closure);
  EXPECT_TRUE(std::isinf(r.normal_stress));
  EXPECT_EQ(law.evaluate(std::numeric_limits<double>::infinity()).status,
            Status::beyond_maximum_closure);
}

TEST(BartonBandis, FromJointPropertiesUsesBandisCorrelations)
{
  // JRC 10, JCS 100 MPa, a_j 0.5 mm: JCS/a_j = 200 MPa/mm.
  auto law = BartonBandis::from_joint_properties(10, 100e6, 0.5e-3);
  EXPECT_NEAR(law.initial_normal_stiffness(), (-7.15 + 17.5 + 4.0) * 1e9, 1e-3);
  const double vm_mm = -0.1032 - 0.0074 * 10 + 1.1350 * std::pow(200.0, -0.2510);
  EXPECT_NEAR(law.maximum_closure(), vm_mm * 1e-3, 1e-15);
  // A smooth wall (JRC 0) with a wide aperture gives a negative K_ni: a clear error.
  EXPECT_THROW(BartonBandis::from_joint_properties(0, 10e6, 5e-3), std::invalid_argument);
}

TEST(LogarithmicLaw, IsTheGwExponentialClosedForm)
{
  const double B = 0.05e-3, s0 = 0.1e6;
  LogarithmicLaw law(B, s0);
  for (double d : {1e-12, 1e-6, 0.2e-3, 1e-3})
  {
    const double total = law.normal_stress(d) + s0;
    EXPECT_NEAR(d, B * std::log(total / s0), 1e-12 * std::max(d, B)) << d;
    EXPECT_NEAR(law.normal_stiffness(d), total / B, 1e-12 * total / B); // k = σ_t/B
  }
}

TEST(ExponentialLaw, MatchesClosedForm)
{
  const double vm = 0.2e-3, sc = 5e6;
  ExponentialLaw law(vm, sc);
  // Up to 10 σ_c: beyond, 1 - Δ/V_m loses digits to the rounding of Δ itself.
  for (double sigma : {1e3, 1e6, 2e7, 5e7})
  {
    const double d = vm * (1 - std::exp(-sigma / sc));
    EXPECT_NEAR(law.normal_stress(d), sigma, 1e-9 * sigma);
    EXPECT_NEAR(law.closure_at_stress(sigma), d, 1e-14 * vm);
  }
}

TEST(EmpiricalLaws, PassTheCommonLawChecks)
{
  std::vector<std::shared_ptr<ClosureLaw>> laws{
      std::make_shared<BartonBandis>(20e9, 0.3e-3),
      std::make_shared<BartonBandis>(1e7, 1e-7), // soft, tiny V_m
      std::make_shared<LogarithmicLaw>(0.05e-3, 0.1e6),
      std::make_shared<ExponentialLaw>(0.2e-3, 5e6)};
  for (const auto& law : laws)
  {
    SCOPED_TRACE(law->name());
    const double top = std::isfinite(law->maximum_closure()) ? 0.999 * law->maximum_closure()
                                                              : 2e-3;
    rockjoint::testing::check_law(*law, top);
  }
}

TEST(EmpiricalLaws, RejectBadParametersWithNamedErrors)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : {nan, inf, -1.0, 0.0})
  {
    EXPECT_THROW(BartonBandis(bad, 1e-3), std::invalid_argument);
    EXPECT_THROW(BartonBandis(1e9, bad), std::invalid_argument);
    EXPECT_THROW(LogarithmicLaw(bad, 1e5), std::invalid_argument);
    EXPECT_THROW(ExponentialLaw(1e-3, bad), std::invalid_argument);
  }
  try
  {
    BartonBandis(-5.0, 1e-3);
    FAIL() << "no exception";
  }
  catch (const std::invalid_argument& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("initial_normal_stiffness"), std::string::npos) << what;
    EXPECT_NE(what.find("-5"), std::string::npos) << what;
    EXPECT_NE(what.find("> 0"), std::string::npos) << what;
  }
  BartonBandis law(20e9, 0.3e-3);
  EXPECT_THROW(law.closure_at_stress(nan), std::invalid_argument);
  EXPECT_THROW(law.closure_at_stress(-1.0), std::invalid_argument);
}

// The laws' parameter metadata (constitutive/parameter_spec.hpp): the ranges the constructors
// check are the ones the specs state, and the specs' words are the error's.
TEST(ParameterSpec, RangesAreTheConstructorsOwn)
{
  const auto& bb = BartonBandis::parameter_specs();
  ASSERT_EQ(bb.size(), 2u);
  EXPECT_EQ(bb[0].name, "initial_normal_stiffness");
  EXPECT_EQ(bb[1].symbol, "V_m");
  EXPECT_EQ(bb[1].unit, "m");
  EXPECT_EQ(bb[1].file_unit, "mm");
  EXPECT_EQ(bb[1].range(), "finite and > 0");
  EXPECT_TRUE(bb[1].admits(1e-3));
  for (double bad : {0.0, -1e-3, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()})
  {
    EXPECT_FALSE(bb[1].admits(bad)) << bad;
    rockjoint::testing::expect_error([&] { BartonBandis(20e9, bad); },
                                     {"BartonBandis", "maximum_closure", "finite and > 0"});
  }
  for (const auto& specs : {LogarithmicLaw::parameter_specs(), ExponentialLaw::parameter_specs()})
    for (const auto& s : specs)
      EXPECT_FALSE(s.admits(0.0)) << s.name;   // every empirical parameter is positive
}

TEST(ParameterSpec, ClosedAndOpenBoundsInWordsAndInTests)
{
  const ParameterSpec r{"permanent_fraction", "r", "-", "-", 0.0, true, 1.0, false};
  EXPECT_EQ(r.range(), "in [0, 1)");
  EXPECT_TRUE(r.admits(0.0));
  EXPECT_FALSE(r.admits(1.0));
  const ParameterSpec m{"unloading_exponent", "m", "-", "-", 1.0, true};
  EXPECT_EQ(m.range(), "finite and >= 1");
  EXPECT_TRUE(m.admits(1.0));
  EXPECT_FALSE(m.admits(0.999));
  rockjoint::testing::expect_error([&] { m.check("Owner", 0.5); },
                                   {"Owner", "unloading_exponent", "0.5", "finite and >= 1"});
}
