// SPDX-License-Identifier: MIT
// Tang substrate law (theory §4): the cubic w = g + κ_s √β g^{3/2}/r0 across scales, the GW
// limit κ_s -> 0, an independent long-double quadrature of f3, k and A, the §7 example, the
// common law checks, hard cases and named errors.
#include <rockjoint/constitutive/elasticity.hpp>
#include <rockjoint/constitutive/greenwood_williamson.hpp>
#include <rockjoint/constitutive/hertz.hpp>
#include <rockjoint/constitutive/substrate.hpp>
#include <rockjoint/constitutive/tang_substrate.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "expect_error.hpp"
#include "gw_reference.hpp"
#include "law_checks.hpp"

using namespace rockjoint::constitutive;
using rockjoint::testing::cubic_root_bisection;
using rockjoint::testing::cubic_root_newton;
using rockjoint::testing::phi_ld;
using rockjoint::testing::tanh_sinh;

namespace
{
// §7 example: E 50 GPa, ν 0.25, η 0.3 mm⁻², β 2.5 mm, σ_s 0.05 mm, κ_s 8/(3π), r0 1 mm.
const double Es = 50e9 / (2 * (1 - 0.25 * 0.25));
constexpr double eta = 0.3e6, beta = 2.5e-3, sigma_s = 0.05e-3, r0 = 1e-3;
const AsperityParameters example{Es, eta, beta, sigma_s};
const SubstrateParameters centre{substrate::centre_deflection, r0};
} // namespace

TEST(TangCubic, RootIsAccurateFromNanometresToMetres)
{
  // c = κ_s √β / r0 [m^-½] from "no substrate" to β = 0.1 m on r0 = 1 µm.
  for (double c : {0.0, 1e-8, 1e-3, 1.0, 42.0, 1e4, 2.7e5, 1e8})
    for (double w = 1e-20; w <= 1.0; w *= 3.7)
    {
      const auto a = substrate::hertz_approach(w, c);
      const long double t = cubic_root_bisection(w, c);
      EXPECT_NEAR(a.root, (double)t, 1e-15 * (double)t) << "w " << w << " c " << c;
      EXPECT_NEAR(a.hertz_part, (double)(t * t), 2e-15 * (double)(t * t));
      // dg/dw = 1/(dw/dg) = 1/(1 + 1.5 c √g), from the reference root.
      const double dg = (double)(1.0L / (1.0L + 1.5L * c * t));
      EXPECT_NEAR(a.derivative, dg, 1e-15 * dg);
      EXPECT_LE(a.hertz_part, w * (1 + 4.5e-16)); // g <= w up to the rounding of t²
    }
}

TEST(TangCubic, DerivativeMatchesFiniteDifferenceOfTheRoot)
{
  for (double c : {1e-3, 42.0, 1e5})
    for (double w : {1e-12, 1e-6, 1e-3})
    {
      const double h = 1e-5 * w;
      const double fd = (double)((cubic_root_bisection(w + h, c) * cubic_root_bisection(w + h, c)
                                  - cubic_root_bisection(w - h, c) * cubic_root_bisection(w - h, c))
                                 / (2.0L * h));
      EXPECT_NEAR(substrate::hertz_approach(w, c).derivative, fd, 1e-8 * fd) << w << " " << c;
    }
}

TEST(TangCubic, ReductionFactorLimitsAndCubeDifference)
{
  EXPECT_EQ(substrate::reduction_factor(0.0), 1.0);
  EXPECT_EQ(substrate::reduction_factor(std::numeric_limits<double>::infinity()), 0.0);
  EXPECT_NEAR(substrate::reduction_factor(1e-300), 1.0, 1e-16);
  for (double q : {1e6, 1e12, 1e100})
  {
    const double tau = substrate::reduction_factor(q);
    EXPECT_NEAR(q * tau * tau * tau + tau * tau, 1.0, 4e-16) << q;
  }
  // q = 1: τ³ + τ² = 1, τ = 0.75487766624669276 (real root of the cubic, Cardano).
  EXPECT_NEAR(substrate::reduction_factor(1.0), 0.75487766624669276, 2e-16);
  // Cube difference of two close roots, against long-double direct subtraction.
  const double c = 42.0, wb = 3e-6, dw = 1e-13;
  const long double ta = cubic_root_bisection(wb + dw, c), tb = cubic_root_bisection(wb, c);
  const double ref = (double)(ta * ta * ta - tb * tb * tb);
  const double diff = substrate::cube_difference(substrate::hertz_approach(wb + dw, c).root,
                                                 substrate::hertz_approach(wb, c).root, c, dw);
  EXPECT_NEAR(diff, ref, 1e-9 * ref); // the long-double reference itself holds ~1e-11
}

TEST(TangSubstrate, ZeroDeflectionCoefficientIsGwExactly)
{
  const SubstrateParameters none{0.0, r0};
  std::vector<std::pair<std::shared_ptr<SummitPopulationLaw>, std::shared_ptr<SummitPopulationLaw>>>
      pairs;
  for (auto dist : {HeightDistribution::gaussian, HeightDistribution::exponential})
    pairs.emplace_back(std::make_shared<TangSubstrate>(example, dist, none),
                       std::make_shared<GreenwoodWilliamson>(example, dist));
  EmpiricalSummits summits({0.0, -1e-5, -3e-5}, {1e-3, 3e-3, 2e-3}, 1e-5);
  pairs.emplace_back(std::make_shared<TangSubstrate>(Es, summits, none),
                     std::make_shared<GreenwoodWilliamson>(Es, summits));
  for (const auto& [tang, gw] : pairs)
  {
    EXPECT_EQ(tang->seating_stress(), gw->seating_stress());
    EXPECT_EQ(tang->reference_separation(), gw->reference_separation());
    for (double d : {1e-15, 1e-9, 1e-6, 1e-4, 1e-3, 1.0})
    {
      const auto a = tang->evaluate(d), b = gw->evaluate(d);
      EXPECT_EQ(a.normal_stress, b.normal_stress) << d;
      EXPECT_EQ(a.normal_stiffness, b.normal_stiffness) << d;
      EXPECT_EQ(a.contact_area_ratio, b.contact_area_ratio) << d;
      EXPECT_EQ(a.contact_area_rate, b.contact_area_rate) << d;
    }
  }
}

TEST(TangSubstrate, TinyDeflectionCoefficientApproachesGw)
{
  // Relative effect ~ c √w = 1e-8 √β/r0 √(few σ_s) ~ 1e-8: a 1e-6 band is generous, and the
  // substrate must soften (less stress at the same separation).
  for (auto dist : {HeightDistribution::gaussian, HeightDistribution::exponential})
  {
    TangSubstrate tang(example, dist, {1e-8, r0});
    GreenwoodWilliamson gw(example, dist);
    for (double d : {1e-9, 1e-5, 1e-4, 3e-4})
    {
      const auto a = tang.evaluate(d), b = gw.evaluate(d);
      EXPECT_NEAR(a.normal_stress, b.normal_stress, 1e-6 * b.normal_stress) << d;
      EXPECT_NEAR(a.normal_stiffness, b.normal_stiffness, 1e-6 * b.normal_stiffness) << d;
      EXPECT_NEAR(a.contact_area_ratio, b.contact_area_ratio, 1e-6 * b.contact_area_ratio);
    }
    const double d = 0.5 * sigma_s;
    EXPECT_LT(tang.response_at_separation(d).normal_stress,
              gw.response_at_separation(d).normal_stress);
  }
}

TEST(TangSubstrate, MatchesIndependentQuadratureOfTheGaussianPopulation)
{
  TangSubstrate law(example, HeightDistribution::gaussian, centre);
  const long double c = substrate::centre_deflection * std::sqrt(beta) / r0;
  for (double h : {-2.0, 0.0, 1.5, 3.5, 6.0})
  {
    // ∫_d^∞ F(g(z-d)) f(z) dz with z = d + σ_s u², in long double, cubic by Newton.
    const long double d = h * sigma_s;
    auto integral = [&](auto F)
    {
      const long double top = std::sqrt(std::max((long double)h, 0.0L) + 16.0L - h);
      return (double)tanh_sinh(
          [&](long double u)
          {
            const long double w = sigma_s * u * u;
            const long double t = cubic_root_newton(w, c);
            return 2.0L * u * F(t) * phi_ld(h + u * u);
          },
          0.0L, top);
    };
    const double stress = (4.0 / 3.0) * Es * eta * std::sqrt(beta)
                          * integral([](long double t) { return t * t * t; });
    const double stiffness = 2.0 * Es * eta * std::sqrt(beta)
                             * integral([&](long double t) { return t / (1.0L + 1.5L * c * t); });
    const double area
        = std::numbers::pi * eta * beta * integral([](long double t) { return t * t; });
    const auto r = law.response_at_separation((double)d);
    EXPECT_NEAR(r.normal_stress, stress, 1e-9 * stress) << "h " << h;
    EXPECT_NEAR(r.normal_stiffness, stiffness, 1e-9 * stiffness) << "h " << h;
    EXPECT_NEAR(r.contact_area_ratio, area, 1e-9 * area) << "h " << h;
  }
}

TEST(TangSubstrate, EmpiricalSummitsUseTheirOwnRadii)
{
  const std::vector<double> z{0.0, -2e-6, -7e-6}, r{1e-3, 4e-3, 0.3e-3};
  const double area = 1e-5, kappa = substrate::rigid_base, base = 0.2e-3;
  TangSubstrate law(Es, EmpiricalSummits(z, r, area), {kappa, base});
  for (double d : {1e-7, 5e-6, 2e-5})
  {
    double s = 0, k = 0, a = 0;
    for (std::size_t i = 0; i < z.size(); ++i)
    {
      const double w = z[i] + d;
      if (w <= 0)
        continue;
      const long double c = kappa * std::sqrt(r[i]) / base;
      const double t = (double)cubic_root_bisection(w, c);
      s += hertz::load(Es, r[i], t * t);
      k += hertz::stiffness(Es, r[i], t * t) / (1 + 1.5 * (double)c * t);
      a += hertz::contact_area(r[i], t * t);
    }
    const auto res = law.evaluate(d);
    EXPECT_NEAR(res.normal_stress, s / area, 1e-13 * s / area) << d;
    EXPECT_NEAR(res.normal_stiffness, k / area, 1e-13 * k / area) << d;
    EXPECT_NEAR(res.contact_area_ratio, a / area, 1e-13 * a / area) << d;
  }
}

TEST(TangSubstrate, Section7ExampleClosesAboutAnEighthOfAMillimetreAt10MPa)
{
  // Theory §7: "about 0.125 mm closure at 10 MPa with A/A0 ≈ 0.8 %".
  TangSubstrate law(example, HeightDistribution::gaussian, centre);
  const double closure = law.closure_at_stress(10e6);
  EXPECT_GT(closure, 0.12e-3);
  EXPECT_LT(closure, 0.13e-3);
  const double area = law.contact_area_ratio(closure);
  EXPECT_GT(area, 0.007);
  EXPECT_LT(area, 0.009);
  EXPECT_NEAR(law.normal_stress(closure), 10e6, 1e-9 * 10e6);
}

TEST(TangSubstrate, DefaultsAreDocumented)
{
  TangSubstrate law(example);
  EXPECT_EQ(law.deflection_coefficient(), 8.0 / (3.0 * std::numbers::pi));
  EXPECT_DOUBLE_EQ(law.base_radius(), 0.5 / std::sqrt(eta)); // half the summit spacing
  EXPECT_DOUBLE_EQ(law.reference_separation(), 3.5 * sigma_s);
  EXPECT_NEAR(substrate::mean_deflection, 64.0 / (9.0 * std::numbers::pi * std::numbers::pi), 0);
  EXPECT_EQ(substrate::rigid_base, 2.0 / 3.0);
  EXPECT_EQ(law.name(), "tang_substrate");
  EXPECT_EQ(law.parameters().back().name, "base_radius");
}

TEST(TangSubstrate, PassesCommonLawChecks)
{
  std::vector<std::pair<std::string, std::shared_ptr<ClosureLaw>>> laws;
  using D = HeightDistribution;
  laws.emplace_back("gaussian §7", std::make_shared<TangSubstrate>(example, D::gaussian, centre));
  laws.emplace_back("gaussian rigid base, default r0",
                    std::make_shared<TangSubstrate>(
                        example, D::gaussian, SubstrateParameters{substrate::rigid_base, {}}));
  laws.emplace_back(
      "gaussian r0 = 1 µm (substrate dominated)",
      std::make_shared<TangSubstrate>(example, D::gaussian,
                                      SubstrateParameters{substrate::centre_deflection, 1e-6}));
  laws.emplace_back("gaussian seated at 10 kPa",
                    std::make_shared<TangSubstrate>(example, D::gaussian, centre,
                                                    SeatingReference::at_stress(1e4)));
  laws.emplace_back("exponential",
                    std::make_shared<TangSubstrate>(example, D::exponential, centre));
  laws.emplace_back(
      "exponential mean deflection, d0 = -σ_s",
      std::make_shared<TangSubstrate>(example, D::exponential,
                                      SubstrateParameters{substrate::mean_deflection, r0},
                                      SeatingReference::at_separation(-sigma_s)));
  const double top = 6 * sigma_s;
  // Onsets staggered between the sampled closures (see test_greenwood_williamson.cpp).
  std::vector<double> z{0.0}, r{2e-3};
  for (int i = 3; i < 199; i += 6)
  {
    z.push_back(-top * std::pow(10.0, -6.0 + 6.0 * (i + 0.5) / 199));
    r.push_back(1e-3 * (1.5 + std::sin(0.7 * i)));
  }
  laws.emplace_back("empirical",
                    std::make_shared<TangSubstrate>(Es, EmpiricalSummits(z, r, 2e-5), centre));
  for (const auto& [label, law] : laws)
  {
    SCOPED_TRACE(label);
    rockjoint::testing::check_law(*law, top);
  }
}

TEST(TangSubstrate, ContactAreaRateIsTheDerivativeOfTheArea)
{
  // d(A/A0)/dΔ is analytic (π η β ∫ (dg/dw) f dz); check_law does not look at it.
  std::vector<std::pair<std::string, std::shared_ptr<ClosureLaw>>> laws;
  for (auto dist : {HeightDistribution::gaussian, HeightDistribution::exponential})
  {
    laws.emplace_back(std::string("tang ") + to_string(dist),
                      std::make_shared<TangSubstrate>(example, dist, centre));
    laws.emplace_back(std::string("gw ") + to_string(dist),
                      std::make_shared<GreenwoodWilliamson>(example, dist));
    laws.emplace_back(std::string("tang r0 1 µm ") + to_string(dist),
                      std::make_shared<TangSubstrate>(
                          example, dist, SubstrateParameters{substrate::rigid_base, 1e-6}));
  }
  // A/A0 is not seated (it is A(d0 - Δ) itself), so at Δ << σ_s it barely changes and a
  // difference quotient drowns in rounding: check from Δ = 0.01 σ_s (step 1e-4 Δ) upwards.
  for (const auto& [label, law] : laws)
    for (int i = 0; i <= 24; ++i)
    {
      const double d = 0.01 * sigma_s * std::pow(800.0, i / 24.0);
      const auto r = law->evaluate(d);
      const double h = 1e-4 * std::min(d, sigma_s);
      const double fd = (law->contact_area_ratio(d + h) - law->contact_area_ratio(d - h)) / (2 * h);
      EXPECT_NEAR(r.contact_area_rate, fd, 1e-6 * fd) << label << " closure " << d;
    }
}

TEST(TangSubstrate, PassesCommonLawChecksAcrossScales)
{
  // σ_s from 0.1 µm to 1 mm and E from 1 to 200 GPa, GW and Tang, both parametric shapes.
  for (auto dist : {HeightDistribution::gaussian, HeightDistribution::exponential})
    for (double ss : {1e-7, 1e-5, 1e-3})
      for (double young : {1e9, 200e9})
      {
        const AsperityParameters p{composite_modulus(young, 0.25), eta, beta, ss};
        SCOPED_TRACE(std::string(to_string(dist)) + " σ_s " + std::to_string(ss) + " E "
                     + std::to_string(young));
        rockjoint::testing::check_law(GreenwoodWilliamson(p, dist), 6 * ss);
        rockjoint::testing::check_law(TangSubstrate(p, dist, centre), 6 * ss);
      }
}

TEST(TangSubstrate, HardCasesStayFiniteMonotoneAndInvertible)
{
  for (auto dist : {HeightDistribution::gaussian, HeightDistribution::exponential})
    for (double ss : {1e-7, 1e-5, 1e-3})
      for (double young : {1e9, 200e9})
        for (double base : {1e-6, 1e-3})
        {
          SCOPED_TRACE(std::string(to_string(dist)) + " σ_s " + std::to_string(ss) + " E "
                       + std::to_string(young) + " r0 " + std::to_string(base));
          TangSubstrate law({composite_modulus(young, 0.25), eta, beta, ss}, dist,
                            {substrate::centre_deflection, base});
          EXPECT_EQ(law.evaluate(0.0).status, Status::open);
          rockjoint::testing::check_extreme_closures(law);
        }
}

TEST(TangSubstrate, RejectsBadParametersWithNamedErrors)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto expect_named = [](auto make, const std::string& what)
  { rockjoint::testing::expect_error(make, {what, "TangSubstrate"}); };
  // Δ = +∞ is a hard limit, not NaN, for every distribution.
  EXPECT_EQ(TangSubstrate(example).evaluate(inf).status, Status::beyond_maximum_closure);
  const auto crushed = TangSubstrate(Es, EmpiricalSummits({0.0}, {1e-3}, 1e-6)).evaluate(inf);
  EXPECT_EQ(crushed.status, Status::beyond_maximum_closure);
  EXPECT_FALSE(std::isnan(crushed.contact_area_ratio));
  for (double bad : {nan, inf, -1.0})
    expect_named(
        [&] {
          TangSubstrate(example, HeightDistribution::gaussian, {bad, r0});
        },
        "deflection_coefficient");
  for (double bad : {nan, inf, -1.0, 0.0})
  {
    expect_named(
        [&] {
          TangSubstrate(example, HeightDistribution::gaussian, {0.5, bad});
        },
        "base_radius");
    expect_named([&] { TangSubstrate({Es, eta, beta, bad}); }, "summit_height_std");
    expect_named([&] { TangSubstrate(bad, EmpiricalSummits({0.0}, {1e-3}, 1e-6)); },
                 "composite_modulus");
  }
}
