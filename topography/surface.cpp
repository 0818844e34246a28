// SPDX-License-Identifier: MIT
#include "surface.hpp"

#include <rockjoint/constitutive/validation.hpp>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace rockjoint::topography
{

namespace validation = rockjoint::constitutive::validation;

Surface::Surface(HeightGrid heights, double spacing_x, double spacing_y)
    : _heights(std::move(heights)),
      _spacing_x(validation::positive("Surface", "spacing_x", spacing_x, "m")),
      _spacing_y(validation::positive("Surface", "spacing_y", spacing_y, "m"))
{
  if (_heights.size() == 0)
    throw std::invalid_argument("Surface: the height grid is empty (0 points)");
  for (Eigen::Index i = 0; i < _heights.rows(); ++i)
    for (Eigen::Index j = 0; j < _heights.cols(); ++j)
      if (std::isinf(_heights(i, j)))
      {
        std::ostringstream msg;
        msg << "Surface: height at row " << i << ", column " << j
            << " is infinite; heights must be finite or NaN (missing)";
        throw std::invalid_argument(msg.str());
      }
}

std::int64_t Surface::valid_count() const
{
  return static_cast<std::int64_t>((_heights == _heights).count());
}

double Surface::mean_height() const
{
  double sum = 0.0;
  std::int64_t n = 0;
  for (Eigen::Index k = 0; k < _heights.size(); ++k)
  {
    const double z = _heights.data()[k];
    if (!std::isnan(z))
    {
      sum += z;
      ++n;
    }
  }
  return n > 0 ? sum / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
}

double Surface::rms_height() const
{
  const double mean = mean_height();
  double sum = 0.0;
  std::int64_t n = 0;
  for (Eigen::Index k = 0; k < _heights.size(); ++k)
  {
    const double z = _heights.data()[k];
    if (!std::isnan(z))
    {
      sum += (z - mean) * (z - mean);
      ++n;
    }
  }
  return n > 0 ? std::sqrt(sum / static_cast<double>(n))
               : std::numeric_limits<double>::quiet_NaN();
}

Surface decimate(const Surface& surface, int factor)
{
  if (factor < 1)
    validation::fail("decimate", "factor", factor, "", ">= 1");
  const Eigen::Index rows = (surface.rows() + factor - 1) / factor;
  const Eigen::Index cols = (surface.cols() + factor - 1) / factor;
  if (rows < 3 || cols < 3)
  {
    std::ostringstream msg;
    msg << "decimate: factor " << factor << " leaves a " << rows << " x " << cols
        << " grid from " << surface.rows() << " x " << surface.cols()
        << "; at least 3 x 3 points are needed";
    throw std::invalid_argument(msg.str());
  }
  HeightGrid out(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i)
    for (Eigen::Index j = 0; j < cols; ++j)
      out(i, j) = surface.heights()(i * factor, j * factor);
  return Surface(std::move(out), surface.spacing_x() * factor, surface.spacing_y() * factor);
}

} // namespace rockjoint::topography
