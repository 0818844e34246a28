// SPDX-License-Identifier: MIT
// Greenwood-Williamson law (theory §2): exponential closed forms, Gaussian partial moments
// against parabolic cylinder functions and an independent long-double quadrature, empirical
// sums, the common law checks on every configuration, hard cases and named errors.
#include <rockjoint/constitutive/elasticity.hpp>
#include <rockjoint/constitutive/greenwood_williamson.hpp>
#include <rockjoint/constitutive/hertz.hpp>
#include <rockjoint/constitutive/population_quadrature.hpp>
#include <rockjoint/constitutive/tang_substrate.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "expect_error.hpp"
#include "gw_reference.hpp"
#include "law_checks.hpp"

using namespace rockjoint::constitutive;
using rockjoint::testing::gaussian_moment_parabolic_cylinder;
using rockjoint::testing::gaussian_moment_quadrature;
using rockjoint::testing::tanh_sinh;

namespace
{
// The §7 example topography: E 50 GPa, ν 0.25, η 0.3 mm⁻², β 2.5 mm, σ_s 0.05 mm.
const double Es = 50e9 / (2 * (1 - 0.25 * 0.25));
constexpr double eta = 0.3e6, beta = 2.5e-3, sigma_s = 0.05e-3;
const AsperityParameters example{Es, eta, beta, sigma_s};
const double sqrt_pi = std::sqrt(std::numbers::pi);

/// An empirical list whose contact onsets Δ_j = d0 - z_j fall half-way (in log scale) between
/// the closures check_law samples (top·10^{-6+6i/199}): σ = Σ (z-d)^{3/2} is only C¹ at an
/// onset, where a central difference is meaningless, and this keeps every onset >= 3.5 %
/// away from a sampled closure (FD truncation < 1e-7 relative).
EmpiricalSummits staggered_summits(double top)
{
  std::vector<double> z{0.0}, r{2e-3};
  for (int i = 3; i < 199; i += 6)
  {
    z.push_back(-top * std::pow(10.0, -6.0 + 6.0 * (i + 0.5) / 199));
    r.push_back(1e-3 * (1.5 + std::sin(0.7 * i)));
  }
  return EmpiricalSummits(z, r, 2e-5);
}
} // namespace

TEST(GreenwoodWilliamson, ExponentialMatchesClosedForms)
{
  GreenwoodWilliamson law(example, HeightDistribution::exponential);
  EXPECT_DOUBLE_EQ(law.reference_separation(), 4.5 * sigma_s); // mean σ_s + 3.5 σ_s
  const double C = sqrt_pi * Es * eta * std::sqrt(beta) * std::pow(sigma_s, 1.5);
  const double s0 = law.seating_stress();
  EXPECT_NEAR(s0, C * std::exp(-4.5), 1e-14 * s0);
  for (double d : {1e-13, 1e-9, 1e-6, 5e-5, 2e-4, 2.25e-4})
  {
    const double h = (4.5 * sigma_s - d) / sigma_s;
    const auto r = law.evaluate(d);
    const double total = r.normal_stress + s0;
    EXPECT_NEAR(total, C * std::exp(-h), 1e-13 * total) << "closure " << d;
    EXPECT_NEAR(r.normal_stiffness, total / sigma_s, 1e-13 * total / sigma_s); // k = σ/σ_s
    const double area = std::numbers::pi * eta * beta * sigma_s * std::exp(-h);
    EXPECT_NEAR(r.contact_area_ratio, area, 1e-13 * area);
    EXPECT_NEAR(r.contact_area_rate, area / sigma_s, 1e-13 * area / sigma_s);
    // Δ = σ_s ln(σ_total/σ0), written as log1p for tiny Δ.
    EXPECT_NEAR(law.closure_at_stress(r.normal_stress), sigma_s * std::log1p(r.normal_stress / s0),
                1e-11 * d);
    EXPECT_NEAR(sigma_s * std::log1p(r.normal_stress / s0), d, 1e-11 * d);
  }
}

TEST(GreenwoodWilliamson, ExponentialBelowTheLowestSummitMatchesQuadrature)
{
  // d < 0: every summit touches; ∫_0^∞ (x + a)^n e^{-x} dx with a = -d/σ_s.
  GreenwoodWilliamson law(example, HeightDistribution::exponential);
  for (double a : {1e-6, 0.5, 3.0, 40.0, 1e4})
  {
    auto moment = [a](long double n)
    {
      return (double)tanh_sinh([&](long double x) { return std::pow(x + a, n) * std::exp(-x); },
                               0.0L, 120.0L);
    };
    const auto r = law.response_at_separation(-a * sigma_s);
    const double s
        = (4.0 / 3.0) * Es * eta * std::sqrt(beta) * std::pow(sigma_s, 1.5) * moment(1.5L);
    EXPECT_NEAR(r.normal_stress, s, 1e-12 * s) << "a " << a;
    const double k = 2 * Es * eta * std::sqrt(beta) * std::sqrt(sigma_s) * moment(0.5L);
    EXPECT_NEAR(r.normal_stiffness, k, 1e-12 * k) << "a " << a;
    const double area = std::numbers::pi * eta * beta * sigma_s * (1 + a);
    EXPECT_NEAR(r.contact_area_ratio, area, 1e-14 * area);
  }
}

TEST(GreenwoodWilliamson, GaussianReferencesAgreeWithEachOther)
{
  // Sanity of the two independent references before using them.
  for (double h = 0.5; h <= 8.0; h += 0.5)
    for (double n : {0.5, 1.5})
    {
      const double pcf = gaussian_moment_parabolic_cylinder(n, h);
      const double quad = (double)gaussian_moment_quadrature(n, h);
      EXPECT_NEAR(pcf, quad, 1e-11 * quad) << "n " << n << " h " << h;
    }
}

TEST(GreenwoodWilliamson, GaussianMatchesParabolicCylinderForms)
{
  GreenwoodWilliamson law(example, HeightDistribution::gaussian);
  EXPECT_DOUBLE_EQ(law.reference_separation(), 3.5 * sigma_s);
  const double stress_scale = (4.0 / 3.0) * Es * eta * std::sqrt(beta) * std::pow(sigma_s, 1.5);
  const double stiffness_scale = 2.0 * Es * eta * std::sqrt(beta) * std::sqrt(sigma_s);
  const double area_scale = std::numbers::pi * eta * beta * sigma_s;
  const double rate_scale = std::numbers::pi * eta * beta;
  for (double h = -3.0; h <= 8.0; h += 0.25)
  {
    const auto r = law.response_at_separation(h * sigma_s);
    const double m32 = h > 0 ? gaussian_moment_parabolic_cylinder(1.5, h)
                             : (double)gaussian_moment_quadrature(1.5L, h);
    const double m12 = h > 0 ? gaussian_moment_parabolic_cylinder(0.5, h)
                             : (double)gaussian_moment_quadrature(0.5L, h);
    EXPECT_NEAR(r.normal_stress / stress_scale, m32, 1e-9 * m32) << "h " << h;
    EXPECT_NEAR(r.normal_stiffness / stiffness_scale, m12, 1e-9 * m12) << "h " << h;
    // The quadrature reference for every h, tighter where it is the only one.
    const double q32 = (double)gaussian_moment_quadrature(1.5L, h);
    EXPECT_NEAR(r.normal_stress / stress_scale, q32, 1e-9 * q32) << "h " << h;
    const double m1 = (double)gaussian_moment_quadrature(1.0L, h);
    EXPECT_NEAR(r.contact_area_ratio / area_scale, m1, 1e-12 * m1) << "h " << h;
    const double m0 = (double)gaussian_moment_quadrature(0.0L, h);
    EXPECT_NEAR(r.contact_area_rate / rate_scale, m0, 1e-12 * m0) << "h " << h;
  }
}

TEST(GreenwoodWilliamson, GaussianSeatedStressIsTheDifferenceOfTotals)
{
  GreenwoodWilliamson law(example);
  const double scale = (4.0 / 3.0) * Es * eta * std::sqrt(beta) * std::pow(sigma_s, 1.5);
  const double m0 = (double)gaussian_moment_quadrature(1.5L, 3.5L);
  EXPECT_NEAR(law.seating_stress(), scale * m0, 1e-9 * scale * m0);
  for (double delta : {0.1, 1.0, 3.5, 6.0, 50.0})
  {
    const double m = (double)gaussian_moment_quadrature(1.5L, 3.5L - delta);
    const double expected = scale * (m - m0);
    EXPECT_NEAR(law.normal_stress(delta * sigma_s), expected, 1e-9 * expected) << delta;
  }
}

TEST(GreenwoodWilliamson, EmpiricalIsASumOfHertzContacts)
{
  const std::vector<double> z{-3e-6, 5e-6, 1e-6, 2e-6}, r{1e-3, 2e-3, 4e-3, 0.5e-3};
  const double area = 1e-5;
  EmpiricalSummits summits(z, r, area);
  EXPECT_DOUBLE_EQ(summits.summit_density(), 4 / area);
  EXPECT_DOUBLE_EQ(summits.mean_radius(), 1.875e-3);
  EXPECT_NEAR(summits.height_std(),
              std::sqrt((18.0625e-12 + 14.0625e-12 + 0.0625e-12 + 0.5625e-12) / 4), 1e-20);
  GreenwoodWilliamson law(Es, summits);
  EXPECT_EQ(law.reference_separation(), 5e-6); // highest summit: first contact
  EXPECT_EQ(law.seating_stress(), 0.0);
  EXPECT_EQ(law.asperity_parameters().summit_radius, summits.mean_radius());
  for (double d : {1e-8, 3.5e-6, 6e-6, 1e-5})
  {
    double s = 0, k = 0, a = 0;
    for (std::size_t i = 0; i < z.size(); ++i)
    {
      const double w = z[i] - (5e-6 - d);
      s += hertz::load(Es, r[i], w);
      k += hertz::stiffness(Es, r[i], w);
      a += hertz::contact_area(r[i], w);
    }
    const auto res = law.evaluate(d);
    EXPECT_NEAR(res.normal_stress, s / area, 1e-13 * s / area) << d;
    EXPECT_NEAR(res.normal_stiffness, k / area, 1e-13 * k / area) << d;
    EXPECT_NEAR(res.contact_area_ratio, a / area, 1e-13 * a / area) << d;
  }
  // A seating stress puts d0 where the sum equals it (here: within the top summit alone).
  const double target = hertz::load(Es, 2e-3, 1e-6) / area;
  GreenwoodWilliamson seated(Es, summits, SeatingReference::at_stress(target));
  EXPECT_NEAR(seated.reference_separation(), 4e-6, 1e-15);
  EXPECT_NEAR(seated.seating_stress(), target, 1e-12 * target);
}

TEST(GreenwoodWilliamson, SeatingStressReferenceSolvesForTheSeparation)
{
  for (auto dist : {HeightDistribution::gaussian, HeightDistribution::exponential})
    for (double target : {1.0, 1e3, 1e6, 1e8})
    {
      GreenwoodWilliamson law(example, dist, SeatingReference::at_stress(target));
      EXPECT_NEAR(law.seating_stress(), target, 1e-12 * target) << to_string(dist);
      EXPECT_NEAR(law.response_at_separation(law.reference_separation()).normal_stress, target,
                  1e-12 * target);
    }
  // Exponential closed form: σ0 = √π E* η β^½ σ_s^{3/2} e^{-d0/σ_s}.
  const double C = sqrt_pi * Es * eta * std::sqrt(beta) * std::pow(sigma_s, 1.5);
  GreenwoodWilliamson law(example, HeightDistribution::exponential,
                          SeatingReference::at_stress(1e4));
  EXPECT_NEAR(law.reference_separation(), sigma_s * std::log(C / 1e4), 1e-14 * sigma_s);
}

TEST(GreenwoodWilliamson, PassesCommonLawChecks)
{
  std::vector<std::pair<std::string, std::shared_ptr<ClosureLaw>>> laws;
  using D = HeightDistribution;
  laws.emplace_back("gaussian default", std::make_shared<GreenwoodWilliamson>(example));
  laws.emplace_back("gaussian seated at 1 kPa",
                    std::make_shared<GreenwoodWilliamson>(example, D::gaussian,
                                                          SeatingReference::at_stress(1e3)));
  laws.emplace_back("gaussian d0 = -σ_s",
                    std::make_shared<GreenwoodWilliamson>(
                        example, D::gaussian, SeatingReference::at_separation(-sigma_s)));
  laws.emplace_back("exponential default",
                    std::make_shared<GreenwoodWilliamson>(example, D::exponential));
  laws.emplace_back("exponential d0 = -σ_s (generic quadrature)",
                    std::make_shared<GreenwoodWilliamson>(
                        example, D::exponential, SeatingReference::at_separation(-sigma_s)));
  laws.emplace_back("exponential d0 = 0.1 σ_s",
                    std::make_shared<GreenwoodWilliamson>(
                        example, D::exponential, SeatingReference::at_separation(0.1 * sigma_s)));
  const double top = 6 * sigma_s;
  laws.emplace_back("empirical", std::make_shared<GreenwoodWilliamson>(Es, staggered_summits(top)));
  for (const auto& [label, law] : laws)
  {
    SCOPED_TRACE(label);
    rockjoint::testing::check_law(*law, top);
  }
}

TEST(GreenwoodWilliamson, HardCasesStayFiniteMonotoneAndInvertible)
{
  for (auto dist : {HeightDistribution::gaussian, HeightDistribution::exponential})
    for (double ss : {1e-7, 1e-5, 1e-3})
      for (double young : {1e9, 200e9})
      {
        SCOPED_TRACE(std::string(to_string(dist)) + " σ_s " + std::to_string(ss) + " E "
                     + std::to_string(young));
        GreenwoodWilliamson law({composite_modulus(young, 0.25), eta, beta, ss}, dist);
        const auto at0 = law.evaluate(0.0);
        EXPECT_EQ(at0.normal_stress, 0.0);
        EXPECT_EQ(at0.status, Status::open);
        rockjoint::testing::check_extreme_closures(law);
      }
}

TEST(GreenwoodWilliamson, ConcurrentEvaluationMatchesSerial)
{
  // Per-thread quadrature workspaces and root memo: a shared const law gives, in every
  // thread, exactly the serial results (GW and the substrate law, which memoises roots).
  const std::vector<std::shared_ptr<const ClosureLaw>> laws{
      std::make_shared<GreenwoodWilliamson>(example),
      std::make_shared<TangSubstrate>(example, HeightDistribution::gaussian,
                                      SubstrateParameters{substrate::centre_deflection, 1e-3})};
  const auto d = rockjoint::testing::log_closures(5 * sigma_s, 64);
  for (const auto& law : laws)
  {
    std::vector<double> serial(d.size());
    for (std::size_t i = 0; i < d.size(); ++i)
      serial[i] = law->normal_stress(d[i]) + law->contact_area_ratio(d[i]);
    std::vector<std::vector<double>> out(4, std::vector<double>(d.size()));
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
      threads.emplace_back(
          [&, t]
          {
            for (int rep = 0; rep < 3; ++rep)
              for (std::size_t i = 0; i < d.size(); ++i)
              {
                const double x = d[(i + 17 * t) % d.size()];
                out[t][i] = law->normal_stress(x) + law->contact_area_ratio(x);
              }
          });
    for (auto& th : threads)
      th.join();
    for (int t = 0; t < 4; ++t)
      for (std::size_t i = 0; i < d.size(); ++i)
        EXPECT_EQ(out[t][i], serial[(i + 17 * t) % d.size()]) << law->name();
  }
}

TEST(GreenwoodWilliamson, QuadratureFailureIsAFlagNotAnAbort)
{
  // sin(1/x) on (1e-12, 1]: GK cannot resolve the oscillations; GSL's default handler would
  // abort the process. The library returns its best estimate and converged = false.
  auto f = [](double x, void*) { return std::sin(1.0 / x) / x; };
  gsl_function F{f, nullptr};
  const auto r = quadrature::integrate(F, 1e-12, 1.0, 1e-12);
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(std::isfinite(r.value));
  // A smooth integrand converges: ∫_0^1 e^x dx = e - 1.
  auto g = [](double x, void*) { return std::exp(x); };
  gsl_function G{g, nullptr};
  const auto ok = quadrature::integrate(G, 0.0, 1.0, 1e-12);
  EXPECT_TRUE(ok.converged);
  EXPECT_NEAR(ok.value, std::expm1(1.0), 1e-15);
}

TEST(GreenwoodWilliamson, FinestToleranceIsClampedAndStillPassesTheChecks)
{
  // 1e-15 is below GSL's floor (50 ε): the law integrates at 1.2e-14 (and falls back to
  // CQUAD where GK61 reports round-off) and must still be a clean law.
  GreenwoodWilliamson law(example, HeightDistribution::gaussian, {}, 1e-15);
  EXPECT_EQ(law.quadrature_tolerance(), 1e-15);
  for (double d : {1e-12, 1e-6, 1e-4, 1e-3})
  {
    EXPECT_TRUE(GreenwoodWilliamson(example).quadrature_converged(d)) << d;
    EXPECT_TRUE(TangSubstrate(example).quadrature_converged(d)) << d;
  }
  rockjoint::testing::check_law(law, 6 * sigma_s);
  GreenwoodWilliamson coarse(example, HeightDistribution::gaussian, {}, 1e-6);
  GreenwoodWilliamson fine(example);
  for (double d : {1e-9, 1e-5, 2e-4})
    EXPECT_NEAR(coarse.normal_stress(d), fine.normal_stress(d), 1e-6 * fine.normal_stress(d));
}

TEST(GreenwoodWilliamson, NestedIntegrationOfTheLawIsSafe)
{
  // ∫_0^X σ(Δ) dΔ integrated with the library's own quadrature while every σ evaluation
  // integrates too. Reference: dM_n/dh = -n M_{n-1}, so with δ = X/σ_s
  // ∫_0^X σ dΔ = scale σ_s [(2/5)(M_{5/2}(h0 - δ) - M_{5/2}(h0)) - δ M_{3/2}(h0)].
  GreenwoodWilliamson law(example);
  const double X = 2 * sigma_s, h0 = 3.5, delta = X / sigma_s;
  auto f = [](double d, void* p) { return static_cast<GreenwoodWilliamson*>(p)->normal_stress(d); };
  gsl_function F{f, &law};
  const auto r = quadrature::integrate(F, 0.0, X, 1e-11);
  const double scale = (4.0 / 3.0) * Es * eta * std::sqrt(beta) * std::pow(sigma_s, 1.5);
  const double m52 = (double)gaussian_moment_quadrature(2.5L, h0 - delta)
                     - (double)gaussian_moment_quadrature(2.5L, h0);
  const double expected
      = scale * sigma_s * (0.4 * m52 - delta * (double)gaussian_moment_quadrature(1.5L, h0));
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.value, expected, 1e-9 * expected);
}

using rockjoint::testing::expect_error;

TEST(GreenwoodWilliamson, RejectsBadParametersWithNamedErrors)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : {nan, inf, -inf, -1.0, 0.0})
  {
    expect_error(
        [&] {
          GreenwoodWilliamson({bad, eta, beta, sigma_s});
        },
        "composite_modulus");
    expect_error([&] { GreenwoodWilliamson({Es, bad, beta, sigma_s}); }, "summit_density");
    expect_error([&] { GreenwoodWilliamson({Es, eta, bad, sigma_s}); }, "summit_radius");
    expect_error([&] { GreenwoodWilliamson({Es, eta, beta, bad}); }, "summit_height_std");
    expect_error(
        [&] {
          GreenwoodWilliamson(example, HeightDistribution::gaussian,
                              SeatingReference::at_stress(bad));
        },
        "seating_stress");
    expect_error([&] { EmpiricalSummits({0.0}, {1e-3}, bad); }, "area");
    expect_error([&] { EmpiricalSummits({0.0, 1e-6}, {1e-3, bad}, 1e-6); }, "radii[1]");
    expect_error([&] { GreenwoodWilliamson(bad, EmpiricalSummits({0.0}, {1e-3}, 1e-6)); },
                 "composite_modulus");
  }
  for (double bad : {nan, inf})
  {
    expect_error([&] { EmpiricalSummits({0.0, bad}, {1e-3, 1e-3}, 1e-6); }, "heights[1]");
    expect_error(
        [&]
        {
          GreenwoodWilliamson(example, HeightDistribution::gaussian,
                              SeatingReference::at_separation(bad));
        },
        "reference_separation");
  }
  for (double bad : {nan, 0.0, 1.0, -1e-10, 2.0})
    expect_error([&] { GreenwoodWilliamson(example, HeightDistribution::gaussian, {}, bad); },
                 "quadrature_tolerance");
  expect_error([&] { EmpiricalSummits({}, {}, 1e-6); }, "heights");
  expect_error([&] { EmpiricalSummits({0.0, 1.0}, {1e-3}, 1e-6); }, "radii");
  expect_error([&] { GreenwoodWilliamson(example, HeightDistribution::empirical); },
               "distribution");
  GreenwoodWilliamson law(example);
  EXPECT_TRUE(std::isinf(law.maximum_closure()));
  EXPECT_TRUE(law.provides_contact_area());
  EXPECT_EQ(law.evaluate(nan).status, Status::invalid_closure);
  EXPECT_EQ(law.evaluate(inf).status, Status::beyond_maximum_closure);
}
