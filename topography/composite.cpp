// SPDX-License-Identifier: MIT
#include "composite.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace rockjoint::topography
{

CompositeTopography composite_topography(const Surface& upper, const Surface& lower,
                                         const ContactState& state)
{
  const double dx = upper.spacing_x(), dy = upper.spacing_y();
  if (std::abs(lower.spacing_x() - dx) > 1e-9 * dx || std::abs(lower.spacing_y() - dy) > 1e-9 * dy)
  {
    std::ostringstream msg;
    msg.precision(12);
    msg << "composite_topography: mismatched grids: upper wall spacing (" << dx << ", " << dy
        << ") m, lower wall spacing (" << lower.spacing_x() << ", " << lower.spacing_y()
        << ") m; resample one wall first";
    throw std::invalid_argument(msg.str());
  }
  // Overlap in upper indices: 0 <= i < rows_u and 0 <= i + oy < rows_l.
  const Eigen::Index oy = state.offset_y, ox = state.offset_x;
  const Eigen::Index i0 = std::max<Eigen::Index>(0, -oy),
                     i1 = std::min<Eigen::Index>(upper.rows(), lower.rows() - oy);
  const Eigen::Index j0 = std::max<Eigen::Index>(0, -ox),
                     j1 = std::min<Eigen::Index>(upper.cols(), lower.cols() - ox);
  if (i1 - i0 < 3 || j1 - j0 < 3)
  {
    std::ostringstream msg;
    msg << "composite_topography: offset (" << ox << ", " << oy << ") grid steps leaves an "
        << "overlap of " << std::max<Eigen::Index>(0, i1 - i0) << " x "
        << std::max<Eigen::Index>(0, j1 - j0) << " points between a " << upper.rows() << " x "
        << upper.cols() << " upper and a " << lower.rows() << " x " << lower.cols()
        << " lower wall; at least 3 x 3 are needed";
    throw std::invalid_argument(msg.str());
  }
  const Eigen::Index rows = i1 - i0, cols = j1 - j0;
  HeightGrid zu = upper.heights().block(i0, j0, rows, cols);
  HeightGrid zl = lower.heights().block(i0 + oy, j0 + ox, rows, cols);

  Plane pu, pl;
  switch (state.plane_removal)
  {
  case PlaneRemoval::common:
    pu = pl = fit_plane({&zu, &zl}, dx, dy);
    break;
  case PlaneRemoval::separate:
    pu = fit_plane({&zu}, dx, dy);
    pl = fit_plane({&zl}, dx, dy);
    break;
  case PlaneRemoval::none:
    break;
  }
  subtract_plane(zu, pu, dx, dy);
  subtract_plane(zl, pl, dx, dy);

  HeightGrid e = zu - zl; // NaN wherever either wall is missing (masks propagate)
  double e_min = std::numeric_limits<double>::infinity();
  for (Eigen::Index k = 0; k < e.size(); ++k)
    if (!std::isnan(e.data()[k]))
      e_min = std::min(e_min, e.data()[k]);
  if (!std::isfinite(e_min))
    throw std::invalid_argument("composite_topography: no lattice point is valid on both walls "
                                "in this contact state");
  e -= e_min; // first contact: min e = 0 exactly
  for (Eigen::Index k = 0; k < e.size(); ++k) // -0.0 or rounding never below 0
    if (e.data()[k] < 0.0)
      e.data()[k] = 0.0;
  Surface aperture(e, dx, dy);
  const double mean_e = aperture.mean_height();
  HeightGrid s = mean_e - e;
  return {Surface(std::move(zu), dx, dy), Surface(std::move(zl), dx, dy), std::move(aperture),
          Surface(std::move(s), dx, dy), mean_e, -e_min, pu, pl, state};
}

} // namespace rockjoint::topography
