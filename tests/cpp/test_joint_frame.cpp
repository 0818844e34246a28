// SPDX-License-Identifier: MIT
// The joint frame (joint/joint_frame.hpp), the rule the joint element and the equivalent
// continuum share: expected axes written out for planes whose frame is known in closed form.
#include <rockjoint/joint/joint_frame.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

using rockjoint::joint::joint_frame;
using Vec = std::array<double, 3>;

namespace
{
void expect_vec(const Vec& a, const Vec& b, double tol = 1e-14)
{
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(a[c], b[c], tol) << "component " << c;
}
} // namespace

TEST(JointFrame, TwoDimensionsRotateTheNormalByMinusNinetyDegrees)
{
  auto q = joint_frame(2, {0.0, 1.0, 0.0});           // horizontal joint: t1 = +x
  expect_vec(q[1], {1.0, 0.0, 0.0});
  const double c = std::cos(0.3), s = std::sin(0.3);
  q = joint_frame(2, {-s, c, 0.0});                   // dipping 0.3 rad: t1 along the trace
  expect_vec(q[1], {c, s, 0.0});
  expect_vec(q[2], {0.0, 0.0, 0.0});
}

TEST(JointFrame, ThreeDimensionsProjectTheReferenceAndCompleteARightHandedFrame)
{
  const double c = std::cos(0.4), s = std::sin(0.4);
  const Vec n{s, 0.0, c};                            // dipping 0.4 rad towards +x
  const auto q = joint_frame(3, n);                   // reference e_x: t1 = the dip direction
  expect_vec(q[0], n);
  expect_vec(q[1], {c, 0.0, -s});
  expect_vec(q[2], {0.0, 1.0, 0.0});                 // n × t1
  const auto r = joint_frame(3, n, {0.0, 2.0, 0.0}); // reference e_y (any length): the strike
  expect_vec(r[1], {0.0, 1.0, 0.0});
  expect_vec(r[2], {-c, 0.0, s});
}

TEST(JointFrame, ANormalAlongTheReferenceUsesTheAxisLeastAlignedWithIt)
{
  const auto q = joint_frame(3, {1.0, 0.0, 0.0});      // n = e_x = the reference: t1 from e_y
  expect_vec(q[1], {0.0, 1.0, 0.0});
  expect_vec(q[2], {0.0, 0.0, 1.0});
}

TEST(JointFrame, ABadReferenceIsANamedError)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(joint_frame(3, {0.0, 0.0, 1.0}, {0.0, 0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(joint_frame(3, {0.0, 0.0, 1.0}, {nan, 0.0, 0.0}), std::invalid_argument);
}
