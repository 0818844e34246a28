// SPDX-License-Identifier: MIT
#pragma once
/// @file surface_io.hpp
/// Plain-text height grids and XYZ point lists. Both carry their units; NaN (written "nan",
/// read as nan/NaN/NA) marks a missing point. Errors name the file and the line.
///
/// Height grid (".txt", ".grid"):
///     # rockjoint height grid
///     # spacing_x: 0.5          (or "spacing: 0.5" for a square lattice)
///     # spacing_y: 0.5
///     # lateral_unit: mm        (unit of the spacings)
///     # height_unit: mm
///     # rows: 200               (optional; checked against the data)
///     # cols: 300               (optional; checked against the data)
///     0.012 0.034 nan ...       (row i = y index, whitespace or comma separated)
///
/// XYZ point list (".xyz"): "x y z" per line (whitespace or comma separated), optional
/// "# lateral_unit:" and "# height_unit:" lines. The points must lie on a regular lattice
/// (any order, lattice points may be absent: they become NaN); the lattice step in x and y is
/// the smallest gap between distinct coordinates. The lattice the points span may have at most
/// 100 lattice points per point given (a mistyped coordinate is an error, not a huge grid).

#include "surface.hpp"

#include <optional>
#include <string>

namespace rockjoint::topography
{

/// What the caller supplies when a file does not say it (or to override the file).
struct ReadOptions
{
  std::optional<double> spacing_x;          ///< in lateral_unit
  std::optional<double> spacing_y;          ///< in lateral_unit
  std::optional<std::string> lateral_unit;  ///< unit of x, y and the spacings
  std::optional<std::string> height_unit;   ///< unit of the heights
};

/// A surface read from a file (SI inside) and the units the file used.
struct SurfaceFile
{
  Surface surface; ///< heights and spacings [m]
  std::string lateral_unit; ///< unit of the file's lateral coordinates
  std::string height_unit; ///< unit of the file's heights
};

/// Read a plain-text height grid. Options override the header. Throws std::invalid_argument
/// "<path>:<line>: ..." for ragged rows, non-numbers, a rows/cols header that does not match
/// the data, missing spacing or units; std::runtime_error if the file cannot be opened.
SurfaceFile read_height_grid(const std::string& path, const ReadOptions& options = {});

/// Write a plain-text height grid with its header, heights and spacings in the given units.
void write_height_grid(const std::string& path, const Surface& surface,
                       const std::string& lateral_unit = "mm",
                       const std::string& height_unit = "mm");

/// Read an XYZ point list on a regular lattice. Throws std::invalid_argument
/// "<path>:<line>: ..." for lines that are not three numbers, points off the lattice,
/// duplicated lattice points and a lattice far larger than the points given.
SurfaceFile read_xyz(const std::string& path, const ReadOptions& options = {});

/// Write every lattice point as "x y z" (missing heights as "nan"), origin at (0, 0).
void write_xyz(const std::string& path, const Surface& surface,
               const std::string& lateral_unit = "mm", const std::string& height_unit = "mm");

} // namespace rockjoint::topography
