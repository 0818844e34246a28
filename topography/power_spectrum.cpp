// SPDX-License-Identifier: MIT
#include "power_spectrum.hpp"

#include "fft2.hpp"

#include <gsl/gsl_fit.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace rockjoint::topography
{

namespace
{
std::vector<double> hann(Eigen::Index n)
{
  // Periodic Hann, scaled to mean w² = 1 so the windowed variance is unbiased.
  std::vector<double> w(n);
  double sum2 = 0.0;
  for (Eigen::Index k = 0; k < n; ++k)
  {
    w[k] = 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * static_cast<double>(k) / n));
    sum2 += w[k] * w[k];
  }
  const double scale = std::sqrt(static_cast<double>(n) / sum2);
  for (double& v : w)
    v *= scale;
  return w;
}
} // namespace

PowerSpectrum2D power_spectrum_2d(const Surface& surface, Window window)
{
  const Eigen::Index rows = surface.rows(), cols = surface.cols();
  if (surface.valid_count() != rows * cols)
  {
    std::ostringstream msg;
    msg << "power_spectrum_2d: the surface has " << rows * cols - surface.valid_count()
        << " missing points; a spectrum needs a complete grid (crop to a complete "
           "rectangle; missing points are never filled)";
    throw std::invalid_argument(msg.str());
  }
  const double mean = surface.mean_height();
  ComplexGrid z(rows, cols);
  const std::vector<double> wy = window == Window::hann ? hann(rows) : std::vector<double>(rows, 1.0);
  const std::vector<double> wx = window == Window::hann ? hann(cols) : std::vector<double>(cols, 1.0);
  for (Eigen::Index i = 0; i < rows; ++i)
    for (Eigen::Index j = 0; j < cols; ++j)
      z(i, j) = (surface.heights()(i, j) - mean) * wy[i] * wx[j];
  fft2(z);
  PowerSpectrum2D out;
  out.dqx = 2.0 * std::numbers::pi / (static_cast<double>(cols) * surface.spacing_x());
  out.dqy = 2.0 * std::numbers::pi / (static_cast<double>(rows) * surface.spacing_y());
  // Parseval: mean(z²) = Σ|Z_k|²/N², so C_k = |Z_k|² / (N² Δq_x Δq_y).
  const double n = static_cast<double>(rows * cols);
  out.psd = z.abs2() / (n * n * out.dqx * out.dqy);
  for (Eigen::Index j = 0; j < cols; ++j)
    out.qx.push_back(angular_frequency(j, cols, surface.spacing_x()));
  for (Eigen::Index i = 0; i < rows; ++i)
    out.qy.push_back(angular_frequency(i, rows, surface.spacing_y()));
  return out;
}

RadialSpectrum radial_average(const PowerSpectrum2D& s)
{
  const double width = std::max(s.dqx, s.dqy);
  const double qx_max = s.dqx * static_cast<double>(s.qx.size() / 2);
  const double qy_max = s.dqy * static_cast<double>(s.qy.size() / 2);
  const double q_max = std::min(qx_max, qy_max);
  const std::size_t nbins = static_cast<std::size_t>(q_max / width) + 1;
  std::vector<double> sq(nbins, 0.0), sc(nbins, 0.0);
  std::vector<std::int64_t> cnt(nbins, 0);
  for (std::size_t i = 0; i < s.qy.size(); ++i)
    for (std::size_t j = 0; j < s.qx.size(); ++j)
    {
      const double q = std::hypot(s.qx[j], s.qy[i]);
      if (q <= 0.0 || q > q_max)
        continue;
      // Bin b holds (b - ½, b + ½]·width; bin 0 (q < width/2) is empty by construction.
      const std::size_t b = static_cast<std::size_t>(std::lround(q / width));
      if (b >= nbins)
        continue;
      sq[b] += q;
      sc[b] += s.psd(i, j);
      ++cnt[b];
    }
  RadialSpectrum out;
  for (std::size_t b = 0; b < nbins; ++b)
    if (cnt[b] > 0)
    {
      out.q.push_back(sq[b] / cnt[b]);
      out.psd.push_back(sc[b] / cnt[b]);
      out.count.push_back(cnt[b]);
    }
  return out;
}

HurstFit fit_hurst_exponent(const RadialSpectrum& s, double q_min, double q_max)
{
  // ln C = ln C0 + slope ln q over the band, each bin weighted by its count of wavevectors.
  std::vector<double> x, y, w;
  for (std::size_t b = 0; b < s.q.size(); ++b)
    if (s.q[b] >= q_min && s.q[b] <= q_max && s.psd[b] > 0.0)
    {
      x.push_back(std::log(s.q[b]));
      y.push_back(std::log(s.psd[b]));
      w.push_back(static_cast<double>(s.count[b]));
    }
  const std::size_t used = x.size();
  if (used < 3)
  {
    std::ostringstream msg;
    msg << "fit_hurst_exponent: only " << used << " spectrum bins in [" << q_min << ", "
        << q_max << "] rad/m; at least 3 are needed";
    throw std::invalid_argument(msg.str());
  }
  double intercept, slope, cov00, cov01, cov11, chisq;
  gsl_fit_wlinear(x.data(), 1, w.data(), 1, y.data(), 1, used, &intercept, &slope, &cov00,
                  &cov01, &cov11, &chisq);
  // GSL's covariance takes the weights as 1/variance; counts are relative weights, so the
  // slope's standard error scales with the residual variance χ²/(n - 2).
  const double se = std::sqrt(cov11 * chisq / static_cast<double>(used - 2));
  return {-0.5 * slope - 1.0, slope, se, intercept, q_min, q_max, used};
}

} // namespace rockjoint::topography
