// SPDX-License-Identifier: MIT
#include "summits.hpp"

#include <cmath>
#include <limits>

namespace rockjoint::topography
{

std::vector<double> SummitList::radii() const
{
  std::vector<double> r(curvatures.size());
  for (std::size_t k = 0; k < r.size(); ++k)
    r[k] = 1.0 / curvatures[k];
  return r;
}

SummitAnalysis analyse_summits(const Surface& surface)
{
  const HeightGrid& s = surface.heights();
  const Eigen::Index rows = s.rows(), cols = s.cols();
  const double dx = surface.spacing_x(), dy = surface.spacing_y();
  const double cx = 1.0 / (dx * dx), cy = 1.0 / (dy * dy);
  const double mean = surface.mean_height();
  SummitAnalysis out;
  SummitList& list = out.summits;
  std::int64_t eligible = 0;
  for (Eigen::Index i = 1; i + 1 < rows; ++i)
  {
    const double* up = s.data() + (i - 1) * cols;
    const double* mid = s.data() + i * cols;
    const double* down = s.data() + (i + 1) * cols;
    for (Eigen::Index j = 1; j + 1 < cols; ++j)
    {
      const double c = mid[j];
      const double n[8] = {up[j - 1],  up[j],     up[j + 1], mid[j - 1],
                           mid[j + 1], down[j - 1], down[j], down[j + 1]};
      // NaN compares false: "c > v" fails for a missing neighbour, so count validity apart.
      bool valid = !std::isnan(c), higher = true;
      for (double v : n)
      {
        valid = valid && !std::isnan(v);
        higher = higher && c > v;
      }
      if (!valid)
        continue;
      ++eligible;
      if (!higher)
        continue;
      const double laplacian = (mid[j - 1] - 2.0 * c + mid[j + 1]) * cx
                               + (up[j] - 2.0 * c + down[j]) * cy;
      list.rows.push_back(static_cast<std::int32_t>(i));
      list.cols.push_back(static_cast<std::int32_t>(j));
      list.heights.push_back(c - mean);
      list.curvatures.push_back(-0.5 * laplacian);
    }
  }

  SummitStatistics& st = out.statistics;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  st.sampling_interval_x = dx;
  st.sampling_interval_y = dy;
  st.summit_count = static_cast<std::int64_t>(list.size());
  st.eligible_points = eligible;
  st.scanned_area = static_cast<double>(eligible) * dx * dy;
  st.summit_density = eligible > 0 ? static_cast<double>(st.summit_count) / st.scanned_area : 0.0;
  st.surface_rms = surface.rms_height();
  const std::size_t n = list.size();
  if (n == 0)
  {
    st.summit_radius = st.mean_summit_radius = st.mean_curvature = nan;
    st.summit_height_std = st.mean_summit_height = st.highest_summit = nan;
    return out;
  }
  double sum_k = 0.0, sum_r = 0.0, sum_z = 0.0, max_z = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < n; ++k)
  {
    sum_k += list.curvatures[k];
    sum_r += 1.0 / list.curvatures[k];
    sum_z += list.heights[k];
    max_z = std::max(max_z, list.heights[k]);
  }
  const double dn = static_cast<double>(n);
  st.mean_curvature = sum_k / dn;
  st.summit_radius = 1.0 / st.mean_curvature;
  st.mean_summit_radius = sum_r / dn;
  st.mean_summit_height = sum_z / dn;
  st.highest_summit = max_z;
  double ss = 0.0;
  for (double z : list.heights)
    ss += (z - st.mean_summit_height) * (z - st.mean_summit_height);
  st.summit_height_std = n > 1 ? std::sqrt(ss / (dn - 1.0)) : nan;
  return out;
}

HeightGrid curvature_field(const Surface& surface)
{
  const HeightGrid& s = surface.heights();
  const double cx = 1.0 / (surface.spacing_x() * surface.spacing_x());
  const double cy = 1.0 / (surface.spacing_y() * surface.spacing_y());
  HeightGrid k = HeightGrid::Constant(s.rows(), s.cols(), std::numeric_limits<double>::quiet_NaN());
  for (Eigen::Index i = 1; i + 1 < s.rows(); ++i)
    for (Eigen::Index j = 1; j + 1 < s.cols(); ++j)
      k(i, j) = -0.5 * ((s(i, j - 1) - 2.0 * s(i, j) + s(i, j + 1)) * cx
                        + (s(i - 1, j) - 2.0 * s(i, j) + s(i + 1, j)) * cy);
  return k; // NaN propagates from any missing stencil point
}

} // namespace rockjoint::topography
