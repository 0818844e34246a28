// SPDX-License-Identifier: MIT
#pragma once
/// @file connectivity.hpp
/// The connected open regions of an aperture grid and whether each can carry a mean flow.
///
/// Why: a region of open cells that no pressure difference reaches (a pocket closed off by
/// contact spots) makes the flow system singular: its pressure is defined up to a constant. A
/// region carries a mean flow along x only if it spans the grid along x: for sealed sides it
/// touches the inlet and the outlet columns; for a periodic grid it winds round the torus along
/// x (the pressure p = -x + φ, φ periodic, can then not be made constant on it). Every other
/// region has p constant at the minimum of the dissipation, no flux, and is left out of the
/// system, so a field with no open path gives T = 0 exactly.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace rockjoint::flow
{

/// 4-connected regions of the open cells of a rows x cols grid (row-major, x along a row).
struct OpenRegions
{
  std::vector<std::int32_t> label; ///< region of each cell; -1 for a closed cell
  std::vector<std::size_t> first_cell; ///< per region: its first cell (row-major)
  std::vector<unsigned char> spans_x;  ///< per region: carries a mean flow along x (see file)
  std::vector<unsigned char> spans_y;  ///< per region: along y
  /// Number of regions.
  std::size_t count() const { return first_cell.size(); }
};

/// Regions of the cells with open[k] != 0, neighbours joined where `face_open` says so:
/// face_open_x[k] is the face between cell k and its +x neighbour (the last column's joins the
/// first when `periodic`, and is ignored otherwise), face_open_y[k] likewise along y.
/// Periodic: a region spans x when it winds round the torus along x, found as two paths to one
/// cell whose unwrapped positions differ by a multiple of the grid length (Machta et al. 1996's
/// wrapping test, Phys. Rev. E 54, 1332). Sealed sides: it touches column 0 and column cols-1.
OpenRegions open_regions(std::span<const unsigned char> open,
                         std::span<const unsigned char> face_open_x,
                         std::span<const unsigned char> face_open_y, std::size_t rows,
                         std::size_t cols, bool periodic);

} // namespace rockjoint::flow
