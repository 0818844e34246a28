// SPDX-License-Identifier: MIT
// The boundary-element contact reference (contact/) against Hertz: a paraboloid of radius R
// pressed on a half-space of modulus E* (theory §1; docs/contact.md).
#include <rockjoint/contact/elastic_contact.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace rockjoint;
using contact::ContactOptions;
using contact::ElasticContact;
using contact::Kernel;

namespace
{
constexpr double pi = std::numbers::pi;
constexpr double radius = 10e-3;      // R [m]
constexpr double modulus = 50e9;      // E* [Pa]
constexpr double side = 4e-3;         // L [m], the square patch or period
// 4 ζ(½) β(½) / π: the approach shift of a square lattice of Hertz contacts per P/(E* L)
// (ζ(½) = -1.4603545088095868, Dirichlet β(½) = 0.6676914571896092).
constexpr double lattice_constant = 4.0 * -1.4603545088095868 * 0.6676914571896092 / pi;

struct Hertz
{
  double a, approach, peak;
};
Hertz hertz(double load)
{
  const double a = std::cbrt(3.0 * load * radius / (4.0 * modulus));
  return {a, a * a / radius, 3.0 * load / (2.0 * pi * a * a)};
}

/// Paraboloid r²/(2R) on an n × n grid of side L, apex on node (n/2, n/2).
topography::Surface paraboloid(int n)
{
  const double h = side / n;
  topography::HeightGrid e(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
    {
      const double x = (j - n / 2) * h, y = (i - n / 2) * h;
      e(i, j) = (x * x + y * y) / (2.0 * radius);
    }
  return topography::Surface(e, h);
}
} // namespace

TEST(ContactHertz, NonPeriodicApproachConvergesToHertz)
{
  const double load = 20.0; // P [N]: a = 0.144 mm, a/L = 0.036
  const Hertz ref = hertz(load);
  double previous = 1.0;
  for (int n : {64, 128, 256})
  {
    ElasticContact bem(paraboloid(n), modulus, Kernel::non_periodic);
    const auto st = bem.solve(load / (side * side));
    ASSERT_TRUE(st.converged) << n;
    const double error = std::abs(st.approach / ref.approach - 1.0);
    std::printf("non-periodic n = %d, a/h = %.1f: approach error %.3e, A/A0 %.4e vs %.4e\n", n,
                ref.a / (side / n), error, st.contact_area_ratio,
                pi * ref.a * ref.a / (side * side));
    EXPECT_LT(error, previous) << "the error must fall as the grid is refined";
    previous = error;
  }
  EXPECT_LT(previous, 2e-3) << "finest grid within 0.2 % of Hertz";
}

TEST(ContactHertz, PeriodicApproachIsHertzPlusTheLatticeCorrection)
{
  const double load = 100.0; // a = 0.247 mm, a/L = 0.062, a/h = 15.8
  const Hertz ref = hertz(load);
  const int n = 256;
  ASSERT_GE(ref.a / (side / n), 15.0);
  ElasticContact bem(paraboloid(n), modulus, Kernel::periodic);
  const auto st = bem.solve(load / (side * side));
  ASSERT_TRUE(st.converged);
  const double expected = ref.approach + lattice_constant * load / (modulus * side);
  std::printf("periodic a/h = %.1f: approach %.6e, Hertz %.6e, Hertz + lattice %.6e\n",
              ref.a / (side / n), st.approach, ref.approach, expected);
  // docs/contact.md states 0.03 % (measured 2.7e-4 on both Debian userlands).
  EXPECT_NEAR(st.approach, expected, 3e-4 * expected);
}

TEST(ContactHertz, LoadBalanceComplementarityAndSigns)
{
  ElasticContact bem(paraboloid(128), modulus, Kernel::periodic);
  for (double load : {5.0, 20.0, 60.0})
  {
    const double sigma = load / (side * side);
    const auto st = bem.solve(sigma);
    ASSERT_TRUE(st.converged);
    double sum = 0.0, pmin = 0.0;
    for (double p : st.pressure)
    {
      sum += p;
      pmin = std::min(pmin, p);
    }
    EXPECT_NEAR(sum / st.pressure.size(), sigma, 1e-12 * sigma) << "mean(p) = σ";
    EXPECT_EQ(pmin, 0.0) << "p >= 0";
    const double scale = hertz(load).approach;
    EXPECT_GT(st.minimum_gap, -1e-6 * scale) << "no interpenetration off contact";
    EXPECT_LT(st.complementarity, 1e-6 * sigma * scale) << "p g = 0";
    EXPECT_EQ(st.contact_patches, 1);
  }
}
