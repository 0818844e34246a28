// SPDX-License-Identifier: MIT
#include "local_frame.hpp"

#include <rockjoint/joint/joint_frame.hpp>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <stdexcept>
#include <string>

namespace rockjoint::fem_coupling
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
                       std::span<const double> minus_interior_point,
                       const std::array<double, 3>& reference)
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
  set_tangents(frame, gdim, reference);
  return frame;
}

void set_tangents(LocalFrame& frame, int gdim, const std::array<double, 3>& reference)
{
  const auto q = joint::joint_frame(gdim, frame.axes[0], reference);  // the one frame rule
  frame.axes[1] = q[1];
  if (gdim == 3)
    frame.axes[2] = q[2];
}

std::array<double, 3> joint_reference_direction(const std::array<double, 9>& normal_moment)
{
  Eigen::Matrix3d M;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      M(i, j) = normal_moment[3 * i + j];
  const double scale = M.trace();
  if (!M.allFinite() || !(scale > 0.0))
    throw std::invalid_argument("joint_reference_direction: the normal moment Σ A n nᵀ must be "
                                "finite with a positive trace (the total joint area), got trace "
                                + std::to_string(scale));
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (M + M.transpose()));
  Eigen::Vector3d m = eig.eigenvectors().col(2); // largest eigenvalue: the mean normal axis
  constexpr double tol = 1e-10;
  const double sign = m[2] > tol ? 1.0
                      : m[2] < -tol ? -1.0
                      : std::abs(m[0]) > tol ? (m[0] > 0.0 ? 1.0 : -1.0)
                                             : (m[1] > 0.0 ? 1.0 : -1.0);
  m *= sign;
  const double h = std::hypot(m[0], m[1]);
  if (h < tol)
    return {1.0, 0.0, 0.0}; // horizontal joint: the x axis
  return {-m[1] / h, m[0] / h, 0.0}; // e_z × m
}

} // namespace rockjoint::fem_coupling
