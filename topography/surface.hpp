// SPDX-License-Identifier: MIT
#pragma once
/// @file surface.hpp
/// A height grid on a regular lattice: one joint wall, an aperture field or a composite
/// topography (theory §3). SI units inside: heights and spacings in metres.

#include <Eigen/Core>

#include <cstdint>

namespace rockjoint::topography
{

/// Heights on a regular lattice, row-major like numpy: entry (i, j) sits at
/// x = j·spacing_x, y = i·spacing_y. NaN marks a missing point (masked, never invented).
using HeightGrid = Eigen::Array<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// A sampled surface: heights [m] with lattice spacings [m].
class Surface
{
public:
  /// @param heights [m]; NaN = missing point; +-inf is rejected
  /// @param spacing_x lattice step along a row (x, column index j) [m], > 0
  /// @param spacing_y lattice step along a column (y, row index i) [m], > 0
  /// Throws std::invalid_argument for an empty grid, non-positive spacing or infinite heights.
  Surface(HeightGrid heights, double spacing_x, double spacing_y);

  /// Square lattice, spacing h [m].
  Surface(HeightGrid heights, double spacing) : Surface(std::move(heights), spacing, spacing) {}

  /// Heights [m], NaN where missing.
  const HeightGrid& heights() const { return _heights; }
  /// h_x [m].
  double spacing_x() const { return _spacing_x; }
  /// h_y [m].
  double spacing_y() const { return _spacing_y; }
  /// Rows (y).
  Eigen::Index rows() const { return _heights.rows(); }
  /// Columns (x).
  Eigen::Index cols() const { return _heights.cols(); }

  /// Number of valid (non-NaN) points.
  std::int64_t valid_count() const;
  /// Mean of the valid heights [m] (NaN if none).
  double mean_height() const;
  /// Root-mean-square deviation of the valid heights from their mean [m].
  double rms_height() const;
  /// Area of one lattice cell [m²].
  double cell_area() const { return _spacing_x * _spacing_y; }

private:
  HeightGrid _heights;
  double _spacing_x;
  double _spacing_y;
};

/// Every `factor`-th point in both directions, starting at (0, 0): the same surface scanned
/// with a `factor` times coarser sampling interval (no averaging: a profilometer's stylus
/// samples points). Throws for factor < 1 or a result with fewer than 3 x 3 points.
Surface decimate(const Surface& surface, int factor);

} // namespace rockjoint::topography
