// SPDX-License-Identifier: MIT
// Summits, curvature and spectral moments against closed forms: i.i.d. noise (exactly 1/9 of
// the eligible points are 8-neighbour summits), paraboloids (the 5-point Laplacian is exact),
// planted summits and sinusoids.
#include <rockjoint/topography/closure_parameters.hpp>
#include <rockjoint/topography/self_affine.hpp>
#include <rockjoint/topography/spectral_moments.hpp>
#include <rockjoint/topography/summits.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

using namespace rockjoint::topography;
using std::numbers::pi;

// For i.i.d. continuous heights a point is the strict maximum of its 3 x 3 window with
// probability p = 1/9 (each of the 9 is equally likely to be the largest; with 4 neighbours
// it would be 1/5, and 4/9 is a classic misquote). The count S over N eligible points is a sum of
// 2-dependent indicators; its variance per point is exact:
//   p(1-p)                                   (self)
//   + 8 (0 - p²)                             (Chebyshev distance 1: both maxima impossible)
//   + Σ_{distance 2} (P(both) - p²),  P(both) = 2/(9 (18-k)), k = shared window points:
//     4 offsets (2,0)-type share k = 3, 8 offsets (2,1)-type k = 2, 4 offsets (2,2) k = 1
// (the larger of the two centres is the max of the 18-k union with prob. 2/(18-k), then the
// other is the max of its own 9-window with prob 1/9). The binomial bound √(p(1-p)/N) is
// about 2x larger (the neighbours are negatively correlated). Tolerance: 4 exact σ.
TEST(TopographySummits, WhiteNoiseSummitDensityIsOneNinthPerPoint)
{
  const Eigen::Index n = 502;
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  HeightGrid z(n, n);
  for (Eigen::Index k = 0; k < z.size(); ++k)
    z.data()[k] = u(rng);
  const double h = 0.5e-3;
  const SummitStatistics st = analyse_summits(Surface(z, h)).statistics;
  ASSERT_EQ(st.eligible_points, (n - 2) * (n - 2));
  const double p = 1.0 / 9.0, N = double(st.eligible_points);
  const double var = p * (1 - p) - 8 * p * p + 4 * (2.0 / (9 * 15) - p * p)
                     + 8 * (2.0 / (9 * 16) - p * p) + 4 * (2.0 / (9 * 17) - p * p);
  const double sigma = std::sqrt(var / N);
  const double per_point = double(st.summit_count) / N;
  EXPECT_NEAR(per_point, p, 4 * sigma) << "σ = " << sigma << " (binomial bound "
                                        << std::sqrt(p * (1 - p) / N) << ")";
  EXPECT_NEAR(st.summit_density * h * h, per_point, 1e-15);
}

TEST(TopographySummits, CurvatureOfASampledParaboloidIsExact)
{
  // s = c - (x-x0)²/(2 R1) - (y-y0)²/(2 R2): κ = -½∇²s = (1/R1 + 1/R2)/2 everywhere.
  const double dx = 0.5e-3, dy = 0.3e-3, r1 = 2e-3, r2 = 5e-3;
  const Eigen::Index rows = 21, cols = 17;
  HeightGrid z(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i)
    for (Eigen::Index j = 0; j < cols; ++j)
    {
      const double x = (j - 8) * dx, y = (i - 10) * dy;
      z(i, j) = 1e-4 - x * x / (2 * r1) - y * y / (2 * r2);
    }
  const Surface s(z, dx, dy);
  const double kappa = 0.5 * (1 / r1 + 1 / r2);
  const SummitAnalysis a = analyse_summits(s);
  ASSERT_EQ(a.summits.size(), 1u);
  EXPECT_EQ(a.summits.rows[0], 10);
  EXPECT_EQ(a.summits.cols[0], 8);
  EXPECT_NEAR(a.summits.curvatures[0], kappa, 1e-11 * kappa);
  EXPECT_NEAR(a.statistics.summit_radius, 1 / kappa, 1e-11 / kappa);
  EXPECT_NEAR(a.summits.heights[0], 1e-4 - s.mean_height(), 1e-18);
  const HeightGrid k = curvature_field(s);
  EXPECT_TRUE(std::isnan(k(0, 3)) && std::isnan(k(5, cols - 1)));
  EXPECT_NEAR((k.block(1, 1, rows - 2, cols - 2) - kappa).abs().maxCoeff(), 0.0, 1e-9 * kappa);
}

TEST(TopographySummits, PlantedSummitsGiveTheirCountHeightsAndStd)
{
  // Flat ground (not summits: not strictly higher) with four peaks of known height.
  const double h = 1e-3;
  HeightGrid z = HeightGrid::Zero(20, 20);
  const double peaks[4] = {1e-5, 2e-5, 4e-5, 7e-5};
  const int at[4][2] = {{3, 3}, {3, 12}, {12, 3}, {12, 12}};
  for (int k = 0; k < 4; ++k)
    z(at[k][0], at[k][1]) = peaks[k];
  const Surface s(z, h);
  const SummitAnalysis a = analyse_summits(s);
  ASSERT_EQ(a.statistics.summit_count, 4);
  EXPECT_EQ(a.statistics.eligible_points, 18 * 18);
  EXPECT_NEAR(a.statistics.summit_density, 4 / (18 * 18 * h * h), 1e-9);
  const double mean = 14e-5 / 400; // surface mean
  double m = 0, ss = 0;
  for (double p : peaks)
    m += (p - mean) / 4;
  for (double p : peaks)
    ss += (p - mean - m) * (p - mean - m);
  EXPECT_NEAR(a.statistics.mean_summit_height, m, 1e-18);
  EXPECT_NEAR(a.statistics.summit_height_std, std::sqrt(ss / 3), 1e-18);
  // A single spike of height p: ∇²s = -4p/h², κ = 2p/h².
  EXPECT_NEAR(a.summits.curvatures[0], 2 * peaks[0] / (h * h), 1e-9);
  EXPECT_NEAR(a.statistics.highest_summit, 7e-5 - mean, 1e-18);
}

TEST(TopographySummits, MissingNeighboursMakeAPointIneligible)
{
  HeightGrid z = HeightGrid::Zero(7, 7);
  z(2, 2) = 1e-5;                                     // a summit
  z(4, 4) = 1e-5;                                     // would be one, but...
  z(5, 5) = std::numeric_limits<double>::quiet_NaN(); // ... a neighbour is missing
  const SummitAnalysis a = analyse_summits(Surface(z, 1e-3));
  EXPECT_EQ(a.statistics.summit_count, 1);
  EXPECT_EQ(a.summits.rows[0], 2);
  // 25 interior points, minus the 4 interior points touching (5,5): (4,4),(4,5),(5,4),(5,5).
  EXPECT_EQ(a.statistics.eligible_points, 25 - 4);
}

TEST(TopographySummits, NoSummitsMeansZeroDensityAndNoParameters)
{
  const SummitAnalysis a = analyse_summits(Surface(HeightGrid::Zero(10, 10), 1e-3));
  EXPECT_EQ(a.statistics.summit_count, 0);
  EXPECT_EQ(a.statistics.summit_density, 0.0);
  EXPECT_TRUE(std::isnan(a.statistics.summit_radius));
  EXPECT_THROW(asperity_parameters(a.statistics, 20e9), std::invalid_argument);
}

TEST(TopographySpectralMoments, SinusoidMomentsFromDifferencesAndSpectrum)
{
  // z = A sin(k x) on a periodic grid: continuous m0 = A²/2, m2x = A²k²/2, m4x = A²k⁴/2;
  // the forward difference sees (2 sin(kh/2)/h)² instead of k², the second difference its
  // square. Along y the moments vanish.
  const double A = 1e-4, h = 0.5e-3;
  const Eigen::Index n = 64;
  const double k = 2 * pi * 5 / (n * h);
  HeightGrid z(8, n);
  for (Eigen::Index i = 0; i < 8; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      z(i, j) = A * std::sin(k * j * h);
  const Surface s(z, h);
  const SpectralMoments p = psd_moments(s, Window::none);
  EXPECT_NEAR(p.m0, A * A / 2, 1e-12 * A * A);
  EXPECT_NEAR(p.m2x, A * A * k * k / 2, 1e-10 * A * A * k * k);
  EXPECT_NEAR(p.m4x, A * A * std::pow(k, 4) / 2, 1e-10 * A * A * std::pow(k, 4));
  EXPECT_NEAR(p.m2y, 0.0, 1e-20);
  const SpectralMoments f = finite_difference_moments(s);
  const double kd2 = std::pow(2 * std::sin(k * h / 2) / h, 2);
  // Exact identities of the sampled sine: the forward difference is
  // 2A sin(kh/2) cos(k(j+½)h), the second difference -kd2·A sin(kjh); the moments are their
  // mean squares over the n-1 pairs and n-2 interior points of each row.
  double c2 = 0, s2 = 0;
  for (Eigen::Index j = 0; j + 1 < n; ++j)
    c2 += std::pow(std::cos(k * (j + 0.5) * h), 2) / double(n - 1);
  for (Eigen::Index j = 1; j + 1 < n; ++j)
    s2 += std::pow(std::sin(k * j * h), 2) / double(n - 2);
  EXPECT_NEAR(f.m2x, A * A * kd2 * c2, 1e-12 * A * A * kd2);
  EXPECT_NEAR(f.m4x, A * A * kd2 * kd2 * s2, 1e-12 * A * A * kd2 * kd2);
  EXPECT_NEAR(f.m2y, 0.0, 1e-20);
  // Nayak/McCool from moments: closed forms.
  SpectralMoments m;
  m.m0 = 1e-7, m.m2 = 1e-3, m.m4 = 50.0;
  const NayakEstimates e = nayak_estimates(m, 0.5e-3);
  EXPECT_NEAR(e.summit_density, 50.0 / (6 * pi * std::sqrt(3.0) * 1e-3), 1e-9);
  EXPECT_NEAR(e.summit_radius, 0.375 * std::sqrt(pi / 50.0), 1e-15);
  EXPECT_NEAR(e.bandwidth, 1e-7 * 50 / 1e-6, 1e-12);
  EXPECT_NEAR(e.summit_height_std, std::sqrt((1 - 0.8968 / 5.0) * 1e-7), 1e-15);
}

// Nayak (1971) / McCool (1986) are continuum results for isotropic Gaussian surfaces. A
// periodic synthetic surface whose shortest wavelength spans 16 grid steps is resolved well
// enough for the 8-neighbour count to see the continuum summits, and its periodogram (no
// window: periodic) gives the exact moments of the realised spectrum. Tolerances: counting
// noise 4/√n on η (n summits; Poisson bound), 4 cv(κ)/√n on β = 1/mean κ, 4/√(2n) on σ_s,
// each plus (πh/λ_s)² ≈ 3.9 % for the discretisation of the stencils at λ_s = 16 h.
TEST(TopographySpectralMoments, CountedSummitsOfAResolvedGaussianSurfaceMatchNayakMcCool)
{
  const double h = 1e-3, ls = 16 * h;
  const Surface s = self_affine_surface({0.8, 1e-3, 128 * h, ls}, {1024, 1024, h, 1, true});
  const SummitAnalysis a = analyse_summits(s);
  const NayakEstimates e = nayak_estimates(psd_moments(s, Window::none), h);
  const double n = double(a.summits.size());
  ASSERT_GT(n, 500);
  double k1 = 0, k2 = 0;
  for (double k : a.summits.curvatures)
    k1 += k / n, k2 += k * k / n;
  const double cv = std::sqrt(k2 - k1 * k1) / k1;
  const double disc = std::pow(pi * h / ls, 2);
  const SummitStatistics& st = a.statistics;
  EXPECT_NEAR(st.summit_density / e.summit_density, 1.0, 4 / std::sqrt(n) + disc);
  EXPECT_NEAR(st.summit_radius / e.summit_radius, 1.0, 4 * cv / std::sqrt(n) + disc);
  EXPECT_NEAR(st.summit_height_std / e.summit_height_std, 1.0, 4 / std::sqrt(2 * n) + disc);
}

TEST(TopographyResampling, DecimationKeepsEveryKthPointAndScalesTheSpacing)
{
  HeightGrid z(7, 10);
  for (Eigen::Index k = 0; k < z.size(); ++k)
    z.data()[k] = double(k);
  const Surface s(z, 0.5e-3, 0.25e-3);
  const Surface d = decimate(s, 3);
  ASSERT_EQ(d.rows(), 3); // rows 0, 3, 6
  ASSERT_EQ(d.cols(), 4); // cols 0, 3, 6, 9
  EXPECT_DOUBLE_EQ(d.spacing_x(), 1.5e-3);
  EXPECT_DOUBLE_EQ(d.spacing_y(), 0.75e-3);
  EXPECT_EQ(d.heights()(2, 3), z(6, 9));
  EXPECT_THROW(decimate(s, 4), std::invalid_argument) << "2 x 3 points left";
  EXPECT_THROW(decimate(s, 0), std::invalid_argument);
  // The study records h with every row; on white noise the counted summit fraction per
  // eligible point stays 1/9 at every h (decimated i.i.d. noise is i.i.d. noise), so η ∝ h⁻².
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  HeightGrid w(400, 400);
  for (Eigen::Index k = 0; k < w.size(); ++k)
    w.data()[k] = u(rng);
  const auto rows = resampling_study(Surface(w, 1e-3), {1, 2, 4});
  ASSERT_EQ(rows.size(), 3u);
  for (const auto& r : rows)
  {
    EXPECT_DOUBLE_EQ(r.sampling_interval, 1e-3 * r.factor);
    EXPECT_DOUBLE_EQ(r.summits.sampling_interval_x, 1e-3 * r.factor);
    const double N = double(r.summits.eligible_points);
    // 4 exact σ of the count (see WhiteNoiseSummitDensityIsOneNinthPerPoint): √(0.0251/N).
    EXPECT_NEAR(r.summits.summit_density * std::pow(1e-3 * r.factor, 2), 1.0 / 9.0,
                4 * std::sqrt(0.02513 / N));
  }
}

TEST(TopographySurface, RejectsInfiniteHeightsAndBadSpacing)
{
  HeightGrid z = HeightGrid::Zero(3, 3);
  EXPECT_THROW(Surface(z, 0.0), std::invalid_argument);
  EXPECT_THROW(Surface(z, std::nan("")), std::invalid_argument);
  z(1, 1) = std::numeric_limits<double>::infinity();
  try
  {
    Surface s(z, 1e-3);
    ADD_FAILURE();
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("row 1, column 1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Surface(HeightGrid(0, 0), 1e-3), std::invalid_argument);
}
