// SPDX-License-Identifier: MIT
#include "spectral_moments.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace rockjoint::topography
{

SpectralMoments finite_difference_moments(const Surface& surface)
{
  const HeightGrid& z = surface.heights();
  const Eigen::Index rows = z.rows(), cols = z.cols();
  const double dx = surface.spacing_x(), dy = surface.spacing_y();
  double s2x = 0, s2y = 0, s4x = 0, s4y = 0;
  std::int64_t n2x = 0, n2y = 0, n4x = 0, n4y = 0;
  for (Eigen::Index i = 0; i < rows; ++i)
    for (Eigen::Index j = 0; j < cols; ++j)
    {
      const double c = z(i, j);
      if (std::isnan(c))
        continue;
      if (j + 1 < cols && !std::isnan(z(i, j + 1)))
      {
        const double d = (z(i, j + 1) - c) / dx;
        s2x += d * d, ++n2x;
        if (j > 0 && !std::isnan(z(i, j - 1)))
        {
          const double k = (z(i, j + 1) - 2.0 * c + z(i, j - 1)) / (dx * dx);
          s4x += k * k, ++n4x;
        }
      }
      if (i + 1 < rows && !std::isnan(z(i + 1, j)))
      {
        const double d = (z(i + 1, j) - c) / dy;
        s2y += d * d, ++n2y;
        if (i > 0 && !std::isnan(z(i - 1, j)))
        {
          const double k = (z(i + 1, j) - 2.0 * c + z(i - 1, j)) / (dy * dy);
          s4y += k * k, ++n4y;
        }
      }
    }
  if (n4x == 0 && n4y == 0)
    throw std::invalid_argument("finite_difference_moments: no three consecutive valid points "
                                "along x or y");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  SpectralMoments m;
  const double rms = surface.rms_height();
  m.m0 = rms * rms;
  m.m2x = n2x ? s2x / n2x : nan, m.m2y = n2y ? s2y / n2y : nan;
  m.m4x = n4x ? s4x / n4x : nan, m.m4y = n4y ? s4y / n4y : nan;
  // Average the directions that have data (a single-row grid has only x).
  m.m2 = n2x && n2y ? 0.5 * (m.m2x + m.m2y) : (n2x ? m.m2x : m.m2y);
  m.m4 = n4x && n4y ? 0.5 * (m.m4x + m.m4y) : (n4x ? m.m4x : m.m4y);
  return m;
}

SpectralMoments psd_moments(const Surface& surface, Window window)
{
  const PowerSpectrum2D s = power_spectrum_2d(surface, window);
  const double da = s.dqx * s.dqy;
  SpectralMoments m;
  for (std::size_t i = 0; i < s.qy.size(); ++i)
    for (std::size_t j = 0; j < s.qx.size(); ++j)
    {
      const double c = s.psd(i, j) * da, qx2 = s.qx[j] * s.qx[j], qy2 = s.qy[i] * s.qy[i];
      m.m0 += c;
      m.m2x += qx2 * c, m.m2y += qy2 * c;
      m.m4x += qx2 * qx2 * c, m.m4y += qy2 * qy2 * c;
    }
  m.m2 = 0.5 * (m.m2x + m.m2y);
  m.m4 = 0.5 * (m.m4x + m.m4y);
  return m;
}

NayakEstimates nayak_estimates(const SpectralMoments& m, double sampling_interval)
{
  NayakEstimates e;
  e.moments = m;
  e.sampling_interval = sampling_interval;
  e.bandwidth = m.bandwidth();
  // Nayak (1971) summit density, McCool (1986) mean summit radius and summit-height std.
  e.summit_density = m.m4 / (6.0 * std::numbers::pi * std::sqrt(3.0) * m.m2);
  e.summit_radius = 0.375 * std::sqrt(std::numbers::pi / m.m4);
  const double f = 1.0 - 0.8968 / e.bandwidth;
  e.summit_height_std = f >= 0.0 ? std::sqrt(f * m.m0) : std::numeric_limits<double>::quiet_NaN();
  return e;
}

} // namespace rockjoint::topography
