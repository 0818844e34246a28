// SPDX-License-Identifier: MIT
// The monotone cubic Hermite interpolant (monotone_hermite.hpp) shared by tabulated laws,
// the overlap curve and the exact contact law: segments reproduce the polynomials they are
// built for, Fritsch-Carlson limiting and the data slopes keep monotone data monotone.
// References: polynomials in closed form, the PCHIP slopes worked by hand from Fritsch &
// Butland (1984) and SciPy's PchipInterpolator (an independent implementation).
#include <rockjoint/constitutive/monotone_hermite.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace rockjoint::constitutive;

namespace
{
/// Values and slopes of the segment sampled at n + 1 points of [x0, x1].
template <class Check>
void sample(const hermite::Segment& seg, double x0, double x1, int n, Check check)
{
  for (int k = 0; k <= n; ++k)
  {
    const double x = x0 + (x1 - x0) * k / n;
    double v, dv;
    hermite::evaluate(seg, x, v, dv);
    check(x, v, dv);
  }
}
} // namespace

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

TEST(MonotoneHermite, ACubicSegmentReproducesTheCubicItInterpolates)
{
  // p(x) = 1 + 2x - 0.5x² + 0.3x³ on [0.4, 1.1], built from its end values and slopes.
  auto p = [](double x) { return 1.0 + x * (2.0 + x * (-0.5 + 0.3 * x)); };
  auto dp = [](double x) { return 2.0 + x * (-1.0 + 0.9 * x); };
  const double a = 0.4, b = 1.1;
  const auto seg = hermite::make_segment(a, b, p(a), p(b), dp(a), dp(b));
  sample(seg, a, b, 70,
         [&](double x, double v, double dv)
         {
           EXPECT_NEAR(v, p(x), 1e-14) << x;
           EXPECT_NEAR(dv, dp(x), 1e-13) << x;
         });
}

TEST(MonotoneHermite, TheFirstSegmentReproducesLinearPlusHertzianOnset)
{
  // σ = a Δ + b Δ^{3/2} + c Δ² is a quartic in t = √Δ with no constant or linear term: the
  // first segment, built from k(0+) = a and σ, k at Δ1, reproduces it and its slope
  // k = a + (3/2) b √Δ + 2cΔ down to Δ → 0.
  const double a = 3.0, b = 5.0, c = -0.7, d1 = 0.8;
  auto s = [&](double d) { return a * d + b * d * std::sqrt(d) + c * d * d; };
  auto k = [&](double d) { return a + 1.5 * b * std::sqrt(d) + 2.0 * c * d; };
  const auto seg = hermite::make_first_segment(d1, s(d1), k(d1), a);
  EXPECT_TRUE(hermite::first_segment_is_monotone(seg));
  for (double d : {1e-12, 1e-6, 0.01, 0.2, 0.5, 0.8})
  {
    double v, dv;
    hermite::evaluate_first(seg, d, v, dv);
    EXPECT_NEAR(v, s(d), 1e-14 * (1.0 + s(d))) << d;
    EXPECT_NEAR(dv, k(d), 1e-13 * k(d)) << d;
  }
}

TEST(MonotoneHermite, FritschCarlsonLimitingMakesAnOvershootingSegmentMonotone)
{
  // Knots (0, 0), (1, 0), (2, 1), (3, 1.1), slopes 0, 0, 6, 0.1: on [1, 2] the secant is 1
  // and (α, β) = (0, 6) lies outside the disc α² + β² <= 9; the cubic is p(τ) = -3τ² + 4τ³,
  // which dips to -1/4 at τ = 1/2. Limiting scales (0, 6) into the disc; the segment [2, 3]
  // (secant 0.1, α = k_2/0.1 >= 30) is then scaled into it as well.
  std::vector<double> x{0.0, 1.0, 2.0, 3.0}, y{0.0, 0.0, 1.0, 1.1}, k{0.0, 0.0, 6.0, 0.1};
  EXPECT_FALSE(hermite::is_monotone(x[1], x[2], y[1], y[2], k[1], k[2]));
  double lowest = 1.0;
  sample(hermite::make_segment(x[1], x[2], y[1], y[2], k[1], k[2]), x[1], x[2], 100,
         [&](double, double v, double) { lowest = std::min(lowest, v); });
  EXPECT_NEAR(lowest, -0.25, 1e-15); // the unlimited cubic overshoots (τ = 1/2 is sampled)
  hermite::limit_slopes(x, y, k);
  EXPECT_EQ(k[1], 0.0);
  for (std::size_t i = 1; i + 1 < x.size(); ++i)
  {
    EXPECT_TRUE(hermite::is_monotone(x[i], x[i + 1], y[i], y[i + 1], k[i], k[i + 1])) << i;
    double previous = y[i];
    sample(hermite::make_segment(x[i], x[i + 1], y[i], y[i + 1], k[i], k[i + 1]), x[i],
           x[i + 1], 200,
           [&](double at, double v, double dv)
           {
             EXPECT_GE(v, previous - 1e-15) << at;
             EXPECT_GE(dv, -1e-13) << at;
             previous = v;
           });
  }
  // A segment already inside the disc keeps its slopes.
  std::vector<double> xs{0.0, 1.0, 2.0}, ys{0.0, 1.0, 2.0}, ks{1.0, 2.0, 1.5};
  hermite::limit_slopes(xs, ys, ks);
  EXPECT_EQ(ks[1], 2.0);
  EXPECT_EQ(ks[2], 1.5);
}

TEST(MonotoneHermite, DataSlopesAreThePchipSlopes)
{
  // y = x² at x = 0, 1, 2: interior slope the harmonic mean of the secants 1 and 3 (equal
  // spacing), 2/(1 + 1/3) = 1.5; end slopes from the three-point formula
  // ((2h0 + h1) d0 - h0 d1)/(h0 + h1): (3·1 - 3)/2 = 0 and (3·3 - 1)/2 = 4 (< 3·3, kept).
  std::vector<double> x{0.0, 1.0, 2.0}, y{0.0, 1.0, 4.0}, m(3);
  hermite::data_slopes(x, y, m);
  EXPECT_NEAR(m[0], 0.0, 1e-15);
  EXPECT_NEAR(m[1], 1.5, 1e-15);
  EXPECT_NEAR(m[2], 4.0, 1e-15);
  // Unequal spacing with a plateau; reference: SciPy 1.10 PchipInterpolator on the same data.
  std::vector<double> xp{0.0, 0.1, 0.35, 0.4, 1.0}, yp{0.0, 0.9, 1.0, 1.0, 1.0}, mp(5);
  hermite::data_slopes(xp, yp, mp);
  const std::vector<double> scipy{11.457142857142857, 0.8811188811188809, 0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < mp.size(); ++i)
    EXPECT_NEAR(mp[i], scipy[i], 1e-14 * (1.0 + scipy[i])) << i;
  const std::vector<double> at{0.05, 0.2, 0.3};
  const std::vector<double> value{0.5822002997002996, 0.9669202797202797, 0.9966489510489509};
  const std::vector<double> slope{10.415434565434564, 0.4702657342657342, 0.13728671328671335};
  for (std::size_t j = 0; j < at.size(); ++j)
  {
    const std::size_t i = at[j] < 0.1 ? 0 : 1;
    double v, dv;
    hermite::evaluate(
        hermite::make_segment(xp[i], xp[i + 1], yp[i], yp[i + 1], mp[i], mp[i + 1]), at[j], v,
        dv);
    EXPECT_NEAR(v, value[j], 1e-14) << at[j];
    EXPECT_NEAR(dv, slope[j], 1e-12) << at[j];
  }
}
