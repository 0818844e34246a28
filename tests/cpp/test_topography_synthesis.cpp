// SPDX-License-Identifier: MIT
// Fourier-filtered self-affine surfaces: the DFT itself, determinism, the realised rms and
// Hurst exponent against the requested ones (tolerances derived from the statistics of the
// random Fourier amplitudes), and mated pairs.
#include <rockjoint/topography/fft2.hpp>
#include <rockjoint/topography/power_spectrum.hpp>
#include <rockjoint/topography/self_affine.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

using namespace rockjoint::topography;
using std::numbers::pi;

TEST(TopographyFFT, MatchesTheDefiningSumOnAMixedRadixGrid)
{
  const Eigen::Index rows = 6, cols = 5; // radix 2·3 and 5
  ComplexGrid z(rows, cols);
  for (Eigen::Index k = 0; k < z.size(); ++k)
    z.data()[k] = std::complex<double>(std::sin(1.3 * k + 0.2), std::cos(0.7 * k * k));
  ComplexGrid f = z;
  fft2(f);
  for (Eigen::Index p = 0; p < rows; ++p)
    for (Eigen::Index q = 0; q < cols; ++q)
    {
      std::complex<double> sum = 0.0;
      for (Eigen::Index i = 0; i < rows; ++i)
        for (Eigen::Index j = 0; j < cols; ++j)
          sum += z(i, j) * std::polar(1.0, -2 * pi * (double(p * i) / rows + double(q * j) / cols));
      EXPECT_NEAR(std::abs(f(p, q) - sum), 0.0, 1e-12) << p << "," << q;
    }
  fft2(f, true);
  EXPECT_LT((f - z).abs().maxCoeff(), 1e-14);
}

TEST(TopographySynthesis, SameSeedSameSurfaceOtherSeedOtherSurface)
{
  SelfAffineSpectrum spec{0.7, 1e-3, 20e-3, 0.0};
  SynthesisGrid g{64, 48, 0.5e-3, 42, true};
  const Surface a = self_affine_surface(spec, g), b = self_affine_surface(spec, g);
  EXPECT_TRUE((a.heights() == b.heights()).all()) << "not bit-identical for one seed";
  g.seed = 43;
  const Surface c = self_affine_surface(spec, g);
  EXPECT_GT((a.heights() - c.heights()).abs().maxCoeff(), 1e-5);
  EXPECT_NEAR(a.rms_height(), 1e-3, 1e-15) << "exact_rms rescales to the requested rms";
  EXPECT_NEAR(a.mean_height(), 0.0, 1e-17) << "the q = 0 mode is removed";
  EXPECT_EQ(a.rows(), 64);
  EXPECT_EQ(a.cols(), 48);
}

// Without rescaling, mean(z²) = Σ_k a_k X_k with a_k = F_k²/N (Σ a_k = rms²) and X_k = |W_k|²/N
// unit exponentials, X_k = X_{-k} (real noise), so Var[mean z²] = 2 Σ_k a_k² exactly. The
// realised rms must lie within 4 predicted standard deviations (relative std of rms ≈ half
// that of the variance). a_k is recomputed here from the spectrum formula, not from the code.
TEST(TopographySynthesis, RealisedRmsMatchesRequestedWithinSamplingError)
{
  const double h = 0.5e-3, rms = 0.8e-3, H = 0.75, lr = 16e-3, ls = 2e-3;
  const Eigen::Index n = 256;
  double sum = 0, sum2 = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
    {
      const double qx = 2 * pi * double(j <= (n - 1) / 2 ? j : j - n) / (n * h);
      const double qy = 2 * pi * double(i <= (n - 1) / 2 ? i : i - n) / (n * h);
      const double q = std::hypot(qx, qy), qr = 2 * pi / lr, qs = 2 * pi / ls;
      const double c = q == 0 || q > qs ? 0.0 : (q < qr ? 1.0 : std::pow(q / qr, -2 * (1 + H)));
      sum += c, sum2 += c * c;
    }
  const double rel_std_rms = 0.5 * std::sqrt(2 * sum2) / sum;
  ASSERT_LT(rel_std_rms, 0.05) << "test design: too few modes for a meaningful check";
  for (std::uint64_t seed : {1u, 2u, 3u})
  {
    const Surface s = self_affine_surface({H, rms, lr, ls}, {n, n, h, seed, false});
    EXPECT_NEAR(s.rms_height() / rms, 1.0, 4 * rel_std_rms)
        << "seed " << seed << ", predicted relative std " << rel_std_rms;
  }
}

// The radial periodogram of a periodic synthetic surface is C(q)·E with E unit exponentials
// (two per ± pair), so ln C of a bin of n modes has variance ≈ 2/n. The weighted LS slope then
// has std σ_slope = 1/√(Σ (n_b/2)(ln q_b - mean)²), σ_H = σ_slope/2; the fitted H must be
// within 4 σ_H + 0.01 (the 0.01 bounds the Jensen bias of averaging q^{-2(1+H)} over a bin,
// < 0.5 % in ln C for bins beyond the 10th).
TEST(TopographySynthesis, FittedHurstExponentMatchesRequested)
{
  const double h = 0.5e-3;
  const Eigen::Index n = 512;
  for (double H : {0.5, 0.8})
  {
    const Surface s = self_affine_surface({H, 1e-3, 25.6e-3, 4 * h}, {n, n, h, 7, false});
    const RadialSpectrum r = radial_average(power_spectrum_2d(s, Window::none));
    const double q_lo = 2 * pi / 25.6e-3 * 1.5, q_hi = 2 * pi / (4 * h) / 1.1;
    const HurstFit fit = fit_hurst_exponent(r, q_lo, q_hi);
    double sw = 0, sx = 0, sxx = 0;
    for (std::size_t b = 0; b < r.q.size(); ++b)
      if (r.q[b] >= q_lo && r.q[b] <= q_hi)
      {
        const double w = 0.5 * r.count[b], x = std::log(r.q[b]);
        sw += w, sx += w * x, sxx += w * x * x;
      }
    const double sigma_h = 0.5 / std::sqrt(sxx - sx * sx / sw);
    EXPECT_NEAR(fit.hurst_exponent, H, 4 * sigma_h + 0.01)
        << "predicted σ_H = " << sigma_h << ", fit bins " << fit.bins;
  }
}

TEST(TopographySynthesis, PerfectlyMatedPairIsIdenticalAndMismatchIsShortWavelengthOnly)
{
  const SelfAffineSpectrum spec{0.8, 1e-3, 0.0, 0.0};
  const SynthesisGrid g{128, 96, 0.5e-3, 5, true};
  const auto [u0, l0] = mated_pair(spec, g, 0.0);
  EXPECT_TRUE((u0.heights() == l0.heights()).all());
  const double lm = 4e-3;
  const auto [u, l] = mated_pair(spec, g, lm);
  EXPECT_TRUE((u.heights() == self_affine_surface(spec, g).heights()).all())
      << "the upper wall of a pair is the single wall of the same seed";
  // The difference has no Fourier content at wavelengths above λ_m.
  ComplexGrid d = (u.heights() - l.heights()).cast<std::complex<double>>();
  fft2(d);
  double low = 0, total = 0;
  for (Eigen::Index i = 0; i < d.rows(); ++i)
    for (Eigen::Index j = 0; j < d.cols(); ++j)
    {
      const double q = std::hypot(angular_frequency(i, d.rows(), g.spacing),
                                  angular_frequency(j, d.cols(), g.spacing));
      (q <= 2 * pi / lm ? low : total) += std::norm(d(i, j));
    }
  EXPECT_GT(total, 0.0);
  EXPECT_LT(low, 1e-24 * total);
}

TEST(TopographySynthesis, BadParametersAreNamed)
{
  const SynthesisGrid g{32, 32, 0.5e-3, 1, true};
  EXPECT_THROW(self_affine_surface({1.2, 1e-3, 0, 0}, g), std::invalid_argument);
  EXPECT_THROW(self_affine_surface({0.8, -1e-3, 0, 0}, g), std::invalid_argument);
  try
  {
    self_affine_surface({0.8, 1e-3, 0, 0.5e-3}, g); // below Nyquist 1 mm
    ADD_FAILURE();
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("cutoff_wavelength"), std::string::npos) << e.what();
  }
}
