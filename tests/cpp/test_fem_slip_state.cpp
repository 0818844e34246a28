// SPDX-License-Identifier: MIT
// The assembler keeps a joint point's slip as a trial state until commit_state() (the per-point
// return mapping is joint/joint_slip.hpp, tested in test_joint_slip.cpp).
#include "joint_test_laws.hpp"

#include <rockjoint/fem_coupling/interface_assembler.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace rockjoint;
using namespace rockjoint::fem_coupling;
using namespace rockjoint::test;
using joint::ShearState;

TEST(FemSlipState, AssemblerKeepsTheSlipOnlyWhenCommitted)
{
  // One 2D pair on the segment (0,0)-(1,0), minus cell below: n = (0, 1). The plus side moves
  // by (a, -b): closure b at both nodal points, shear j_s = a t1_x.
  const double phi = 30 * deg, c = 1e5, b_closure = 1e-4, a = 1e-3;
  InterfaceAssembler asm_(2, 1, QuadratureRule::nodal, std::vector<std::int32_t>{0, 1, 2, 3, 4, 5, 6, 7},
                          std::vector<double>{0.0, 0.0, 1.0, 0.0}, std::vector<double>{0.5, -0.5},
                          std::vector<std::int32_t>{7}, {{7, coulomb(phi, c)}});
  const auto& t1 = asm_.frame(0).axes[1];
  const double js = a * t1[0] - b_closure * t1[1];
  const double tau_y = c + kn * b_closure * std::tan(phi);
  const double slip = std::copysign(std::abs(js) - tau_y / ks, js);
  std::vector<double> u{0, 0, 0, 0, a, -b_closure, a, -b_closure}, r(8, 0.0);

  ASSERT_TRUE(asm_.assemble_residual(u, r));
  for (std::size_t q = 0; q < asm_.trial_state().size(); ++q)
  {
    EXPECT_NEAR(asm_.trial_state()[q].slip[0], slip, 1e-15) << q;
    EXPECT_EQ(asm_.converged_state()[q].slip[0], 0.0);
    EXPECT_EQ(asm_.shear_state()[q], static_cast<std::int32_t>(ShearState::slip));
  }
  // The joint force on the plus side along t1 is the strength times the length (1 m).
  EXPECT_NEAR(r[4] * t1[0] + r[5] * t1[1] + r[6] * t1[0] + r[7] * t1[1], std::copysign(tau_y, js),
              1e-9 * tau_y);
  asm_.revert_state();
  EXPECT_EQ(asm_.trial_state()[0].slip[0], 0.0);

  asm_.assemble_residual(u, r);
  asm_.commit_state();
  EXPECT_NEAR(asm_.converged_state()[1].slip[0], slip, 1e-15);
  // Back to a shear jump equal to the slip: zero shear traction, the slip stays.
  const double back = slip / t1[0] + b_closure * t1[1] / t1[0]; // plus-side x giving j_s = slip
  std::vector<double> u_back{0, 0, 0, 0, back, -b_closure, back, -b_closure};
  std::fill(r.begin(), r.end(), 0.0);
  asm_.assemble_residual(u_back, r);
  EXPECT_NEAR(asm_.shear_traction()[0], 0.0, 1e-6 * tau_y);
  EXPECT_NEAR(asm_.trial_state()[0].slip[0], slip, 1e-15);
  EXPECT_EQ(asm_.shear_state()[0], static_cast<std::int32_t>(ShearState::stick));
  asm_.reset_state();
  EXPECT_EQ(asm_.converged_state()[0].slip[0], 0.0);
  EXPECT_EQ(asm_.trial_state()[0].slip[0], 0.0);
}

