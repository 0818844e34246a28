// SPDX-License-Identifier: MIT
#include "connectivity.hpp"

#include <cassert>

namespace rockjoint::flow
{

OpenRegions open_regions(std::span<const unsigned char> open,
                         std::span<const unsigned char> face_open_x,
                         std::span<const unsigned char> face_open_y, std::size_t rows,
                         std::size_t cols, bool periodic)
{
  const std::size_t n = rows * cols;
  assert(open.size() == n && face_open_x.size() == n && face_open_y.size() == n);
  OpenRegions out;
  out.label.assign(n, -1);
  // Unwrapped position of each visited cell (periodic): the cell's column and row plus the
  // periods crossed along the search tree's path to it.
  std::vector<std::int64_t> ux(periodic ? n : 0), uy(periodic ? n : 0);
  std::vector<std::size_t> stack;
  for (std::size_t seed = 0; seed < n; ++seed)
  {
    if (!open[seed] || out.label[seed] >= 0)
      continue;
    const auto region = static_cast<std::int32_t>(out.count());
    out.first_cell.push_back(seed);
    bool wind_x = false, wind_y = false;
    bool left = false, right = false, bottom = false, top = false;
    out.label[seed] = region;
    if (periodic)
    {
      ux[seed] = std::int64_t(seed % cols);
      uy[seed] = std::int64_t(seed / cols);
    }
    stack.assign(1, seed);
    while (!stack.empty())
    {
      const std::size_t k = stack.back();
      stack.pop_back();
      const std::size_t i = k / cols, j = k % cols;
      left |= j == 0;
      right |= j + 1 == cols;
      bottom |= i == 0;
      top |= i + 1 == rows;
      // The four faces of k: (neighbour, face open, step of the unwrapped position).
      struct Step
      {
        std::size_t cell;
        bool face;
        int dx, dy;
      };
      const std::size_t west = j > 0 ? k - 1 : k + cols - 1;
      const std::size_t east = j + 1 < cols ? k + 1 : k + 1 - cols;
      const std::size_t south = i > 0 ? k - cols : k + n - cols;
      const std::size_t north = i + 1 < rows ? k + cols : k + cols - n;
      const Step steps[4] = {
          {east, face_open_x[k] && (periodic || j + 1 < cols), 1, 0},
          {west, face_open_x[west] && (periodic || j > 0), -1, 0},
          {north, face_open_y[k] && (periodic || i + 1 < rows), 0, 1},
          {south, face_open_y[south] && (periodic || i > 0), 0, -1}};
      for (const Step& s : steps)
      {
        if (!s.face)
          continue;
        if (out.label[s.cell] < 0)
        {
          out.label[s.cell] = region;
          if (periodic)
          {
            ux[s.cell] = ux[k] + s.dx;
            uy[s.cell] = uy[k] + s.dy;
          }
          stack.push_back(s.cell);
        }
        else if (periodic)
        {
          wind_x |= ux[s.cell] != ux[k] + s.dx;
          wind_y |= uy[s.cell] != uy[k] + s.dy;
        }
      }
    }
    out.spans_x.push_back(periodic ? wind_x : (left && right));
    out.spans_y.push_back(periodic ? wind_y : (bottom && top));
  }
  return out;
}

} // namespace rockjoint::flow
