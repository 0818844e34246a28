#include "local_frame.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rockjoint::fem
{

namespace
{
double norm(const std::array<double, 3>& a)
{
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

std::array<double, 3> cross(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
} // namespace

LocalFrame facet_frame(int gdim, std::span<const double> vertices,
                       std::span<const double> minus_interior_point)
{
  if (gdim != 2 && gdim != 3)
    throw std::invalid_argument("facet_frame: gdim = " + std::to_string(gdim)
                                + " is invalid; it must be 2 or 3");
  if (vertices.size() < static_cast<std::size_t>(gdim * gdim)
      || minus_interior_point.size() < static_cast<std::size_t>(gdim))
    throw std::invalid_argument("facet_frame: expected " + std::to_string(gdim)
                                + " vertices of " + std::to_string(gdim) + " coordinates");

  LocalFrame frame;
  std::array<double, 3> n{}, centroid{};
  for (int v = 0; v < gdim; ++v)
    for (int c = 0; c < gdim; ++c)
      centroid[c] += vertices[v * gdim + c] / gdim;

  if (gdim == 2)
  {
    const std::array<double, 3> t{vertices[2] - vertices[0], vertices[3] - vertices[1], 0.0};
    frame.measure = norm(t);
    n = {t[1], -t[0], 0.0};
  }
  else
  {
    std::array<double, 3> e1{}, e2{};
    for (int c = 0; c < 3; ++c)
    {
      e1[c] = vertices[3 + c] - vertices[c];
      e2[c] = vertices[6 + c] - vertices[c];
    }
    n = cross(e1, e2);
    frame.measure = 0.5 * norm(n);
  }
  const double nn = norm(n);
  if (!(frame.measure > 0.0) || !(nn > 0.0))
    throw std::invalid_argument("facet_frame: degenerate joint facet (measure "
                                + std::to_string(frame.measure) + ")");
  for (auto& c : n)
    c /= nn;

  // Orientation from the cell side, not from the vertex order (docs/fem.md, pitfall 3).
  double side = 0.0;
  for (int c = 0; c < gdim; ++c)
    side += n[c] * (centroid[c] - minus_interior_point[c]);
  if (side == 0.0 || !std::isfinite(side))
    throw std::invalid_argument("facet_frame: the minus-cell interior point lies in the facet plane");
  if (side < 0.0)
    for (auto& c : n)
      c = -c;

  frame.axes[0] = n;
  if (gdim == 2)
    frame.axes[1] = {-n[1], n[0], 0.0};
  else
  {
    // t1 ⟂ n built from the coordinate axis least aligned with n; t2 = n × t1.
    int k = 0;
    for (int c = 1; c < 3; ++c)
      if (std::abs(n[c]) < std::abs(n[k]))
        k = c;
    std::array<double, 3> e{};
    e[k] = 1.0;
    auto t1 = cross(n, e);
    const double l = norm(t1);
    for (auto& c : t1)
      c /= l;
    frame.axes[1] = t1;
    frame.axes[2] = cross(n, t1);
  }
  return frame;
}

} // namespace rockjoint::fem
