// SPDX-License-Identifier: MIT
#include "plane.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <stdexcept>

namespace rockjoint::topography
{

Plane fit_plane(const std::vector<const HeightGrid*>& grids, double spacing_x,
                double spacing_y)
{
  // Normal equations in index coordinates (better conditioned), converted at the end.
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (const HeightGrid* g : grids)
    for (Eigen::Index i = 0; i < g->rows(); ++i)
      for (Eigen::Index j = 0; j < g->cols(); ++j)
      {
        const double z = (*g)(i, j);
        if (std::isnan(z))
          continue;
        const Eigen::Vector3d phi(1.0, static_cast<double>(j), static_cast<double>(i));
        a.noalias() += phi * phi.transpose();
        b.noalias() += phi * z;
      }
  Eigen::FullPivLU<Eigen::Matrix3d> lu(a);
  if (lu.rank() < 3)
    throw std::invalid_argument("fit_plane: fewer than 3 non-collinear valid points; a mean "
                                "plane is undefined");
  const Eigen::Vector3d c = lu.solve(b);
  return {c(0), c(1) / spacing_x, c(2) / spacing_y};
}

void subtract_plane(HeightGrid& heights, const Plane& plane, double spacing_x,
                    double spacing_y)
{
  for (Eigen::Index i = 0; i < heights.rows(); ++i)
    for (Eigen::Index j = 0; j < heights.cols(); ++j)
      heights(i, j) -= plane.at(static_cast<double>(j) * spacing_x,
                                static_cast<double>(i) * spacing_y);
}

} // namespace rockjoint::topography
