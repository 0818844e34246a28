// SPDX-License-Identifier: MIT
#include "joint_frame.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rockjoint::joint
{
namespace
{
double norm(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
} // namespace

JointFrame joint_frame(int gdim, const std::array<double, 3>& n, const std::array<double, 3>& reference)
{
  JointFrame q{};
  q[0] = n;
  if (gdim == 2)
  {
    q[0][2] = 0.0;
    q[1] = {n[1], -n[0], 0.0};
    return q;
  }
  // t1 = (I - n nᵀ) r / |(I - n nᵀ) r|: the reference direction in the joint plane.
  auto project = [&](const std::array<double, 3>& r)
  {
    const double rn = r[0] * n[0] + r[1] * n[1] + r[2] * n[2];
    return std::array<double, 3>{r[0] - rn * n[0], r[1] - rn * n[1], r[2] - rn * n[2]};
  };
  const double rr = norm(reference);
  if (!(rr > 0.0) || !std::isfinite(rr))
    throw std::invalid_argument("joint_frame: the reference direction must be a finite non-zero "
                                "vector (got norm " + std::to_string(rr) + ")");
  auto t1 = project(reference);
  if (!(norm(t1) > 1e-3 * rr))
  {
    // Normal along the reference (a strongly curved joint's facet): the axis least aligned with n.
    int k = 0;
    for (int c = 1; c < 3; ++c)
      if (std::abs(n[c]) < std::abs(n[k]))
        k = c;
    std::array<double, 3> e{};
    e[k] = 1.0;
    t1 = project(e);
  }
  const double l = norm(t1);
  for (auto& c : t1)
    c /= l;
  q[1] = t1;
  q[2] = {n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2], n[0] * t1[1] - n[1] * t1[0]};
  return q;
}

} // namespace rockjoint::joint
