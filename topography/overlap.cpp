// SPDX-License-Identifier: MIT
#include "overlap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rockjoint::topography
{

ApertureDistribution::ApertureDistribution(const Surface& aperture)
{
  const HeightGrid& e = aperture.heights();
  _sorted.reserve(static_cast<std::size_t>(e.size()));
  for (Eigen::Index k = 0; k < e.size(); ++k)
    if (!std::isnan(e.data()[k]))
      _sorted.push_back(e.data()[k]);
  if (_sorted.empty())
    throw std::invalid_argument("ApertureDistribution: the aperture field has no valid point");
  std::sort(_sorted.begin(), _sorted.end());
}

double ApertureDistribution::overlap_ratio(double closure) const
{
  if (std::isnan(closure))
    return std::numeric_limits<double>::quiet_NaN();
  const auto it = std::upper_bound(_sorted.begin(), _sorted.end(), closure);
  return static_cast<double>(it - _sorted.begin()) / static_cast<double>(_sorted.size());
}

void ApertureDistribution::overlap_ratio(std::span<const double> closure,
                                         std::span<double> ratio) const
{
  if (ratio.size() != closure.size())
    throw std::invalid_argument("ApertureDistribution::overlap_ratio: output size differs "
                                "from input size");
  for (std::size_t k = 0; k < closure.size(); ++k)
    ratio[k] = overlap_ratio(closure[k]);
}

} // namespace rockjoint::topography
