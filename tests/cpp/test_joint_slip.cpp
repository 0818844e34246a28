// SPDX-License-Identifier: MIT
// Joint strength: Coulomb/Barton slip with dilation and tension cut-off (joint/joint_slip.hpp),
// linked against the joint library alone (no PETSc, no MPI). Reference values are hand-worked
// closed forms of the return mapping (docs/joint-strength.md) and central finite differences of the traction. Also the closure at
// a total normal stress (pre-closure, joint_behaviour.hpp) against the series spring of a linear
// law and the root of Barton-Bandis's quadratic.
#include "expect_error.hpp"

#include "joint_test_laws.hpp"
#include <rockjoint/joint/joint_slip.hpp>

#include <rockjoint/constitutive/barton_bandis.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

using namespace rockjoint;
using namespace rockjoint::joint;
using namespace rockjoint::test;

namespace
{
LocalResponse respond(const JointBehaviour& b, int gdim, std::array<double, 3> jump,
                      const JointPointState& converged, JointPointState* out = nullptr)
{
  JointPointState trial;
  LocalResponse r = joint_response(b, gdim, jump, converged, trial);
  if (out)
    *out = trial;
  return r;
}

/// ∂t/∂j against central differences with step h [m] (the state must not switch within ±h).
void expect_tangent_matches_fd(const JointBehaviour& b, int gdim, std::array<double, 3> jump,
                               const JointPointState& converged, ShearState expected,
                               double h = 1e-9, double rtol = 1e-6)
{
  const LocalResponse r = respond(b, gdim, jump, converged);
  ASSERT_EQ(r.shear_state, expected) << "state of the reference point";
  double scale = 0.0;
  for (int i = 0; i < gdim; ++i)
    for (int j = 0; j < gdim; ++j)
      scale = std::max(scale, std::abs(r.tangent[i][j]));
  for (int j = 0; j < gdim; ++j)
  {
    auto up = jump, down = jump;
    up[j] += h;
    down[j] -= h;
    const LocalResponse rp = respond(b, gdim, up, converged);
    const LocalResponse rm = respond(b, gdim, down, converged);
    ASSERT_EQ(rp.shear_state, expected);
    ASSERT_EQ(rm.shear_state, expected);
    for (int i = 0; i < gdim; ++i)
    {
      const double fd = (rp.traction[i] - rm.traction[i]) / (2 * h);
      EXPECT_NEAR(r.tangent[i][j], fd, rtol * std::max(scale, 1.0))
          << "∂t" << i << "/∂j" << j << " (gdim " << gdim << ")";
    }
  }
}
} // namespace

TEST(JointSlip, ElasticInsideTheConeIsTheLinearSpring)
{
  const JointBehaviour b = coulomb(30 * deg, 1e5);
  JointPointState trial;
  // Δ = 1e-4 m: σ_n = 1 MPa, τ_y = 0.1 + tan 30° MPa ≈ 0.677 MPa; j_s = 1e-4 m: τ = 0.4 MPa.
  const LocalResponse r = joint_response(b, 2, {-1e-4, 1e-4, 0.0}, {}, trial);
  EXPECT_EQ(r.shear_state, ShearState::stick);
  EXPECT_DOUBLE_EQ(r.traction[0], -1e6);
  EXPECT_DOUBLE_EQ(r.traction[1], 4e5);
  EXPECT_EQ(trial.slip[0], 0.0);
  EXPECT_EQ(trial.accumulated_slip, 0.0);
}

TEST(JointSlip, ReturnMappingReachesTheCoulombStrengthWithTheClosedFormSlip)
{
  const double phi = 30 * deg, c = 1e5, closure = 1e-4, js = 5e-4;
  const JointBehaviour b = coulomb(phi, c);
  JointPointState trial;
  const LocalResponse r = joint_response(b, 2, {-closure, js, 0.0}, {}, trial);
  const double sigma = kn * closure, tau_y = c + sigma * std::tan(phi), tau_trial = ks * js;
  EXPECT_EQ(r.shear_state, ShearState::slip);
  EXPECT_NEAR(r.traction[1], tau_y, 1e-9 * tau_y);
  EXPECT_DOUBLE_EQ(r.traction[0], -sigma); // ψ = 0: the normal stress is unchanged
  EXPECT_NEAR(trial.slip[0], (tau_trial - tau_y) / ks, 1e-12 * js);
  EXPECT_NEAR(trial.accumulated_slip, (tau_trial - tau_y) / ks, 1e-12 * js);
  EXPECT_EQ(trial.dilation, 0.0);
  // Negative shear: the mirror image.
  const LocalResponse m = joint_response(b, 2, {-closure, -js, 0.0}, {}, trial);
  EXPECT_NEAR(m.traction[1], -tau_y, 1e-9 * tau_y);
  EXPECT_NEAR(trial.slip[0], -(tau_trial - tau_y) / ks, 1e-12 * js);
}

TEST(JointSlip, ReevaluatingACommittedSlipStepReadsSlipWithoutMovingTheSlip)
{
  // The step slid: committed state = its trial state. Re-evaluated at the same jump (stage
  // results, output) the elastic predictor sits on the strength with a zero increment: still
  // "slip", the same traction, the slip unchanged. Just inside the strength it reads "stick".
  for (const double psi : {0.0, 5 * deg})
  {
    const JointBehaviour b = coulomb(30 * deg, 1e5, psi);
    const std::array<double, 3> jump{-1e-4, 5e-4, 0.0};
    JointPointState committed, again;
    const LocalResponse first = respond(b, 2, jump, {}, &committed);
    ASSERT_EQ(first.shear_state, ShearState::slip);
    const LocalResponse second = respond(b, 2, jump, committed, &again);
    EXPECT_EQ(second.shear_state, ShearState::slip) << "ψ = " << psi;
    EXPECT_NEAR(second.traction[1], first.traction[1], 1e-9 * std::abs(first.traction[1]));
    EXPECT_NEAR(again.slip[0], committed.slip[0], 1e-12 * jump[1]);
    // Unloading by 1 % of the elastic shear jump: strictly inside, elastic.
    const double elastic = jump[1] - committed.slip[0];
    const LocalResponse inside = respond(b, 2, {jump[0], jump[1] - 0.01 * elastic, 0.0}, committed);
    EXPECT_EQ(inside.shear_state, ShearState::stick) << "ψ = " << psi;
  }
}

TEST(JointSlip, AJointWithoutStrengthSticksAtAnyShear)
{
  // No strength model: τ_y = +∞, so a closed joint is elastic and reads "stick" however far it
  // is sheared (re-evaluated from a committed state too).
  JointBehaviour b;
  b.law = std::make_shared<LinearLaw>(kn);
  b.shear_stiffness = ks;
  JointPointState committed;
  for (const double js : {0.0, 1e-4, 1.0})
  {
    const LocalResponse r = respond(b, 3, {-1e-4, js, -js}, {}, &committed);
    EXPECT_EQ(r.shear_state, ShearState::stick) << "j_s = " << js;
    EXPECT_DOUBLE_EQ(r.traction[1], ks * js);
    EXPECT_EQ(respond(b, 3, {-1e-4, js, -js}, committed).shear_state, ShearState::stick);
  }
}

TEST(JointSlip, DilationGivesTheClosedFormSlipIncrementAndNormalStress)
{
  // Linear law: G(Δλ) = c + tanφ k_n (Δ + tanψ Δλ) - k_s (e - Δλ) = 0
  //   ⇒ Δλ = f_trial / (k_s + k_n tanφ tanψ).
  const double phi = 35 * deg, psi = 10 * deg, c = 2e5, closure = 2e-4, js = 1e-3;
  const JointBehaviour b = coulomb(phi, c, psi);
  JointPointState trial;
  const LocalResponse r = joint_response(b, 2, {-closure, js, 0.0}, {}, trial);
  const double f = ks * js - c - kn * closure * std::tan(phi);
  const double dl = f / (ks + kn * std::tan(phi) * std::tan(psi));
  const double sigma = kn * (closure + std::tan(psi) * dl);
  EXPECT_EQ(r.shear_state, ShearState::slip);
  EXPECT_NEAR(trial.slip[0], dl, 1e-12 * js);
  EXPECT_NEAR(trial.dilation, std::tan(psi) * dl, 1e-12 * js);
  EXPECT_NEAR(-r.traction[0], sigma, 1e-9 * sigma);
  EXPECT_NEAR(r.traction[1], c + sigma * std::tan(phi), 1e-9 * sigma);
  EXPECT_NEAR(r.traction[1], ks * (js - dl), 1e-9 * sigma);
}

TEST(JointSlip, DilationStopsAtTheLimitingSlip)
{
  // Converged accumulated slip 0.9 ℓ: the increment passes the limit, so the opening is
  // tanψ (ℓ - κ_n) and then Δλ = (k_s e - c - tanφ k_n (Δ + opening)) / k_s.
  const double phi = 35 * deg, psi = 10 * deg, c = 0.0, closure = 2e-4, limit = 1e-4;
  JointBehaviour b = coulomb(phi, c, psi);
  b.strength.dilation_limit = limit;
  JointPointState converged;
  converged.accumulated_slip = 0.9 * limit;
  converged.dilation = 0.9 * limit * std::tan(psi);
  const double js = 2e-3;
  JointPointState trial;
  const LocalResponse r = joint_response(b, 2, {-closure, js, 0.0}, converged, trial);
  const double opening = std::tan(psi) * 0.1 * limit;
  const double sigma = kn * (closure + converged.dilation + opening);
  const double dl = (ks * js - c - std::tan(phi) * sigma) / ks;
  ASSERT_GT(dl, 0.1 * limit) << "the case must cross the limit";
  EXPECT_NEAR(trial.dilation, limit * std::tan(psi), 1e-12 * limit);
  EXPECT_NEAR(trial.slip[0], dl, 1e-12 * js);
  EXPECT_NEAR(-r.traction[0], sigma, 1e-9 * sigma);
  // Past the limit the normal stress no longer follows the slip: ∂t_n/∂j_s = 0.
  EXPECT_NEAR(r.tangent[0][1], 0.0, 1e-12 * kn);
  expect_tangent_matches_fd(b, 2, {-closure, js, 0.0}, converged, ShearState::slip);
}

TEST(JointSlip, BartonPeakStrength)
{
  // τ = σ_n tan(φ_r + JRC log10(JCS/σ_n)), JRC 10, JCS 100 MPa, φ_r 28°, σ_n = 2 MPa:
  // angle = 28 + 10 log10(50) = 44.99°.
  JointBehaviour b = coulomb(28 * deg, 0.0);
  b.strength.model = StrengthModel::barton;
  b.strength.jrc = 10.0;
  b.strength.jcs = 100e6;
  const double closure = 2e-4, sigma = kn * closure; // 2 MPa
  const double angle = (28.0 + 10.0 * std::log10(100e6 / sigma)) * deg;
  JointPointState trial;
  const LocalResponse r = joint_response(b, 2, {-closure, 2e-3, 0.0}, {}, trial);
  EXPECT_EQ(r.shear_state, ShearState::slip);
  EXPECT_NEAR(r.traction[1], sigma * std::tan(angle), 1e-9 * sigma);
  // At very low stress the angle is capped at 70°.
  const double low = 1e-9; // σ_n = 10 Pa: 28 + 10 log10(1e7) = 98° > 70°
  const LocalResponse q = joint_response(b, 2, {-low, 1e-6, 0.0}, {}, trial);
  EXPECT_NEAR(q.traction[1], kn * low * std::tan(70 * deg), 1e-9 * kn * low);
  expect_tangent_matches_fd(b, 2, {-closure, 2e-3, 0.0}, {}, ShearState::slip);
  expect_tangent_matches_fd(b, 3, {-closure, 2e-3, -1e-3}, {}, ShearState::slip);
}

TEST(JointSlip, TangentMatchesFiniteDifferencesInStickSlipAndOpenStates)
{
  const auto bb = std::make_shared<constitutive::BartonBandis>(2e10, 1e-3);
  for (int g : {2, 3})
  {
    SCOPED_TRACE("gdim " + std::to_string(g));
    JointPointState converged;
    converged.slip = {1e-5, -2e-5};
    converged.dilation = 1e-6;
    converged.accumulated_slip = 4e-5;
    for (double psi : {0.0, 12 * deg})
    {
      SCOPED_TRACE("psi " + std::to_string(psi));
      const JointBehaviour b = coulomb(30 * deg, 1e5, psi, bb);
      expect_tangent_matches_fd(b, g, {-2e-4, 2e-5, 1e-5}, converged, ShearState::stick);
      expect_tangent_matches_fd(b, g, {-2e-4, 8e-4, -5e-4}, converged, ShearState::slip);
      expect_tangent_matches_fd(b, g, {5e-5, 8e-4, -5e-4}, converged, ShearState::open);
      JointBehaviour p = b; // proportional shear stiffness: k_s follows k_n(Δ_e)
      p.shear_model = ShearModel::proportional;
      p.shear_stiffness_ratio = 0.2;
      expect_tangent_matches_fd(p, g, {-2e-4, 3e-5, 1e-5}, converged, ShearState::stick);
      expect_tangent_matches_fd(p, g, {-2e-4, 8e-4, -5e-4}, converged, ShearState::slip);
    }
    // The slip tangent is unsymmetric: ∂τ/∂j_n = -tanφ k_n m, ∂t_n/∂j_s = 0 without dilation.
    const LocalResponse r = respond(coulomb(30 * deg, 0.0), g, {-2e-4, 8e-4, 0.0}, {});
    EXPECT_NEAR(r.tangent[1][0], -std::tan(30 * deg) * kn, 1e-6 * kn);
    EXPECT_EQ(r.tangent[0][1], 0.0);
  }
}

TEST(JointSlip, OpenJointTransmitsNoTractionAndKeepsItsSlip)
{
  JointPointState converged;
  converged.slip = {3e-4, 1e-4};
  for (int g : {2, 3})
  {
    JointPointState trial;
    const LocalResponse r =
        joint_response(coulomb(30 * deg, 1e6), g, {1e-4, 1e-3, -1e-3}, converged, trial);
    EXPECT_EQ(r.shear_state, ShearState::open);
    for (int i = 0; i < g; ++i)
    {
      EXPECT_EQ(r.traction[i], 0.0) << i;
      for (int j = 0; j < g; ++j)
        EXPECT_EQ(r.tangent[i][j], 0.0);
    }
    EXPECT_EQ(trial.slip, converged.slip);
  }
  // Without a strength too: the constant k_s no longer acts across an open joint.
  JointBehaviour elastic;
  elastic.law = std::make_shared<LinearLaw>(kn);
  elastic.shear_stiffness = ks;
  const LocalResponse e = local_response(elastic, 2, {1e-4, 1e-3, 0.0});
  EXPECT_EQ(e.traction[1], 0.0);
  EXPECT_EQ(e.shear_state, ShearState::open);
  // The residual spring k_r acts in every direction of an open joint, on the elastic slip.
  JointBehaviour residual = coulomb(30 * deg, 0.0);
  residual.residual_stiffness = 1e6;
  const LocalResponse k = respond(residual, 3, {1e-4, 1e-3, -2e-3}, converged);
  EXPECT_DOUBLE_EQ(k.traction[0], 1e6 * 1e-4);
  EXPECT_DOUBLE_EQ(k.traction[1], 1e6 * (1e-3 - 3e-4));
  EXPECT_DOUBLE_EQ(k.traction[2], 1e6 * (-2e-3 - 1e-4));
}

TEST(JointSlip, ResidualFloorMakesTheShearTractionContinuousAtOpeningAndAcrossTheFloor)
{
  // k_r = 1e6 Pa/m, 1 mm of elastic slip: the residual spring alone carries k_r e = 1000 Pa.
  JointBehaviour b = coulomb(30 * deg, 0.0);
  b.residual_stiffness = 1e6;
  JointPointState converged;
  converged.slip = {3e-4, 0.0};
  const double e = 1e-3, spring = 1e6 * e, mu = std::tan(30 * deg);
  const double js = converged.slip[0] + e;
  // Across opening (Δ_e = +1e-12 → -1e-12 m): in contact the Coulomb strength is ~6e-3 Pa, below
  // the spring, so the joint carries the spring as the open joint does.
  JointPointState closed_trial, open_trial;
  const LocalResponse closed = respond(b, 2, {-1e-12, js, 0.0}, converged, &closed_trial);
  const LocalResponse open = respond(b, 2, {1e-12, js, 0.0}, converged, &open_trial);
  EXPECT_EQ(closed.shear_state, ShearState::slip);
  EXPECT_EQ(open.shear_state, ShearState::open);
  EXPECT_NEAR(closed.traction[1], spring, 1e-9 * spring);
  EXPECT_NEAR(open.traction[1], spring, 1e-9 * spring);
  EXPECT_EQ(closed_trial.slip, converged.slip); // on the floor the slip is frozen
  // Across the floor: τ_y = tanφ (k_n + k_r) Δ = k_r e at Δ*; just below, the floor (k_r e);
  // just above, the return mapping (τ_y): the same traction to the relative change of Δ.
  const double star = spring / (mu * (kn + 1e6));
  const LocalResponse below = respond(b, 2, {-star * (1 - 1e-9), js, 0.0}, converged);
  const LocalResponse above = respond(b, 2, {-star * (1 + 1e-9), js, 0.0}, converged);
  EXPECT_EQ(below.shear_state, ShearState::slip);
  EXPECT_EQ(above.shear_state, ShearState::slip);
  EXPECT_NEAR(below.traction[1], spring, 2e-9 * spring);
  EXPECT_NEAR(above.traction[1], spring, 2e-9 * spring);
  // Well above, the ordinary return mapping: |τ| = tanφ σ_n.
  const LocalResponse contact = respond(b, 2, {-10 * star, js, 0.0}, converged);
  EXPECT_NEAR(contact.traction[1], mu * (kn + 1e6) * 10 * star, 1e-9 * spring);
  // The floor's tangent is consistent.
  for (int g : {2, 3})
    expect_tangent_matches_fd(b, g, {-0.5 * star, js, 2e-4}, converged, ShearState::slip);
}

TEST(JointSlip, FrictionAngleTowardsZeroLeavesCohesionOnly)
{
  const double c = 3e5;
  for (double phi : {0.0, 1e-10})
  {
    const JointBehaviour b = coulomb(phi, c);
    const LocalResponse r = respond(b, 2, {-1e-4, 1e-3, 0.0}, {});
    EXPECT_NEAR(r.traction[1], c, 1e-9 * c + kn * 1e-4 * phi * 1.01);
    EXPECT_NEAR(r.tangent[1][0], 0.0, 2.0 * phi * kn);
    expect_tangent_matches_fd(b, 2, {-1e-4, 1e-3, 0.0}, {}, ShearState::slip);
    expect_tangent_matches_fd(b, 3, {-1e-4, 1e-3, 4e-4}, {}, ShearState::slip);
  }
}

TEST(JointSlip, NoCohesionAtVanishingNormalStressSlipsFreely)
{
  const JointBehaviour b = coulomb(30 * deg, 0.0);
  for (double closure : {1e-6, 1e-12, 1e-300, 0.0})
  {
    JointPointState trial;
    const LocalResponse r = joint_response(b, 3, {-closure, 1e-3, -1e-3}, {}, trial);
    const double tau_y = kn * closure * std::tan(30 * deg);
    const double tau = std::hypot(r.traction[1], r.traction[2]);
    EXPECT_TRUE(std::isfinite(tau)) << closure;
    EXPECT_NEAR(tau, tau_y, 1e-9 * tau_y + 1e-300) << closure;
    EXPECT_NEAR(std::hypot(trial.slip[0], trial.slip[1]), std::sqrt(2.0) * 1e-3 - tau_y / ks,
                1e-15) << closure;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        EXPECT_TRUE(std::isfinite(r.tangent[i][j])) << closure;
  }
}

TEST(JointSlip, LoadReversalSlipsBackOnlyAtTheStrengthAndKeepsThePermanentSlip)
{
  const double phi = 30 * deg, closure = 1e-4;
  const JointBehaviour b = coulomb(phi, 0.0);
  const double tau_y = kn * closure * std::tan(phi);
  // Load forward to j_s = 1 mm: permanent slip s1 = j_s - τ_y/k_s.
  JointPointState s1;
  respond(b, 2, {-closure, 1e-3, 0.0}, {}, &s1);
  const double slip1 = 1e-3 - tau_y / ks;
  ASSERT_NEAR(s1.slip[0], slip1, 1e-15);
  // Unload to zero shear stress (j_s = s1): elastic, the slip stays.
  JointPointState s2;
  const LocalResponse unloaded = respond(b, 2, {-closure, slip1, 0.0}, s1, &s2);
  EXPECT_EQ(unloaded.shear_state, ShearState::stick);
  EXPECT_NEAR(unloaded.traction[1], 0.0, 1e-9 * tau_y);
  EXPECT_EQ(s2.slip[0], s1.slip[0]);
  // Reverse: elastic until τ = -τ_y, i.e. j_s = s1 - τ_y/k_s.
  const double back = slip1 - tau_y / ks;
  const LocalResponse before = respond(b, 2, {-closure, back + 1e-9, 0.0}, s2);
  EXPECT_EQ(before.shear_state, ShearState::stick);
  JointPointState s3;
  const LocalResponse after = respond(b, 2, {-closure, back - 2e-4, 0.0}, s2, &s3);
  EXPECT_EQ(after.shear_state, ShearState::slip);
  EXPECT_NEAR(after.traction[1], -tau_y, 1e-9 * tau_y);
  EXPECT_NEAR(s3.slip[0], slip1 - 2e-4, 1e-15);
  // The path length counts both directions.
  EXPECT_NEAR(s3.accumulated_slip, slip1 + 2e-4, 1e-15);
}

TEST(JointSlip, SlipIsIrreversibleAndTheTrialDependsOnlyOnConvergedStateAndJump)
{
  const JointBehaviour b = coulomb(30 * deg, 1e5, 5 * deg);
  JointPointState converged;
  respond(b, 3, {-1e-4, 2e-3, 1e-3}, {}, &converged);
  // Going back to zero jump from that state: elastic, no slip reversal for free.
  JointPointState back;
  const LocalResponse r = respond(b, 3, {-1e-4, converged.slip[0], converged.slip[1]}, converged,
                                  &back);
  EXPECT_EQ(r.shear_state, ShearState::stick);
  EXPECT_EQ(back.slip, converged.slip);
  EXPECT_EQ(back.dilation, converged.dilation);
  EXPECT_EQ(back.accumulated_slip, converged.accumulated_slip);
  // Evaluations at other jumps (Newton iterates) in between do not change the answer.
  JointPointState first, second, scratch;
  const std::array<double, 3> jump{-1.2e-4, 3e-3, 0.0};
  const LocalResponse a = respond(b, 3, jump, converged, &first);
  respond(b, 3, {-5e-4, -4e-3, 2e-3}, converged, &scratch);
  const LocalResponse c = respond(b, 3, jump, converged, &second);
  EXPECT_EQ(a.traction, c.traction);
  EXPECT_EQ(first.slip, second.slip);
  EXPECT_EQ(first.dilation, second.dilation);
}

TEST(JointSlip, RotatingTheShearPlaneLeavesShearAndSlipMagnitudesUnchanged)
{
  const JointBehaviour b = coulomb(32 * deg, 5e4, 8 * deg);
  const std::array<double, 2> shear{7e-4, -3e-4};
  JointPointState ref;
  const LocalResponse r0 = respond(b, 3, {-1.5e-4, shear[0], shear[1]}, {}, &ref);
  ASSERT_EQ(r0.shear_state, ShearState::slip);
  for (double angle : {17.0, 90.0, 200.0})
  {
    const double cs = std::cos(angle * deg), sn = std::sin(angle * deg);
    JointPointState rotated;
    const LocalResponse r = respond(
        b, 3, {-1.5e-4, cs * shear[0] - sn * shear[1], sn * shear[0] + cs * shear[1]}, {},
        &rotated);
    EXPECT_NEAR(std::hypot(r.traction[1], r.traction[2]),
                std::hypot(r0.traction[1], r0.traction[2]), 1e-9 * std::abs(r0.traction[1]));
    EXPECT_NEAR(r.traction[0], r0.traction[0], 1e-9 * std::abs(r0.traction[0]));
    EXPECT_NEAR(std::hypot(rotated.slip[0], rotated.slip[1]), std::hypot(ref.slip[0], ref.slip[1]),
                1e-15);
    // The traction turns with the shear: τ_rotated = R τ.
    EXPECT_NEAR(r.traction[1], cs * r0.traction[1] - sn * r0.traction[2],
                1e-9 * std::abs(r0.traction[1]));
    EXPECT_NEAR(rotated.dilation, ref.dilation, 1e-18);
  }
}

TEST(JointSlip, TensileStrengthHoldsABondedJointUntilItBreaks)
{
  JointBehaviour b = coulomb(30 * deg, 1e6);
  b.strength.tensile_strength = 5e5; // <= c / tan 30° = 1.73 MPa
  // Bonded: the contact-side spring k_n carries tension up to T (opening T/k_n = 50 µm).
  JointPointState trial;
  const LocalResponse held = joint_response(b, 2, {2e-5, 1e-5, 0.0}, {}, trial);
  EXPECT_DOUBLE_EQ(held.traction[0], kn * 2e-5);
  EXPECT_DOUBLE_EQ(held.traction[1], ks * 1e-5); // the bond carries shear as well
  EXPECT_EQ(held.shear_state, ShearState::stick);
  EXPECT_FALSE(trial.bond_broken);
  expect_tangent_matches_fd(b, 2, {2e-5, 1e-5, 0.0}, {}, ShearState::stick);
  // Past T the bond fails: no traction, and the failure is kept in the state.
  const LocalResponse broken = joint_response(b, 2, {6e-5, 1e-5, 0.0}, {}, trial);
  EXPECT_EQ(broken.traction[0], 0.0);
  EXPECT_EQ(broken.traction[1], 0.0);
  EXPECT_TRUE(trial.bond_broken);
  // Reclosed after failure: no tension any more, and no cohesion either.
  const JointPointState failed = trial;
  const LocalResponse reopened = respond(b, 2, {2e-5, 0.0, 0.0}, failed);
  EXPECT_EQ(reopened.traction[0], 0.0);
  const LocalResponse sheared = respond(b, 2, {-1e-4, 1e-3, 0.0}, failed);
  EXPECT_NEAR(sheared.traction[1], kn * 1e-4 * std::tan(30 * deg), 1e-3);
}

TEST(JointSlip, BadParametersGiveNamedErrors)
{
  using rockjoint::testing::expect_error;
  auto check = [](JointBehaviour b) { validate(b, "set A"); };
  expect_error([&] { check(coulomb(90 * deg, 0.0)); }, {"set A", "friction_angle", "[0, pi/2)"});
  expect_error([&] { check(coulomb(-0.1, 0.0)); }, {"friction_angle", "-0.1"});
  expect_error([&] { check(coulomb(std::nan(""), 0.0)); }, "friction_angle");
  expect_error([&] { check(coulomb(30 * deg, -1.0)); }, {"cohesion", ">= 0"});
  expect_error([&] { check(coulomb(30 * deg, 0.0, 31 * deg)); }, {"dilation_angle", "psi"});
  expect_error([&] { check(coulomb(30 * deg, 0.0, -1 * deg)); }, "dilation_angle");
  JointBehaviour b = coulomb(30 * deg, 1e5);
  b.strength.tensile_strength = 2e5; // > c / tan 30° = 1.73e5
  expect_error([&] { check(b); }, {"tensile_strength", "apex"});
  b = coulomb(30 * deg, 1e5);
  b.strength.dilation_limit = 0.0;
  expect_error([&] { check(b); }, {"dilation_limit", "> 0"});
  b = coulomb(30 * deg, 0.0);
  b.strength.model = StrengthModel::barton;
  b.strength.jrc = 25.0;
  b.strength.jcs = 1e8;
  expect_error([&] { check(b); }, {"jrc", "[0, 20]"});
  b.strength.jrc = 10.0;
  b.strength.jcs = 0.0;
  expect_error([&] { check(b); }, {"jcs", "> 0"});
  // The elastic joint (no strength) ignores the strength fields.
  JointBehaviour elastic = coulomb(95 * deg, -1.0);
  elastic.strength.model = StrengthModel::none;
  EXPECT_NO_THROW(check(elastic));
}

// ---- Pre-closure: the closure at a total normal stress σ(Δ) + k_r Δ = σ_t -------------------

namespace
{
/// σ = k_n Δ up to Δ_lim, frozen there beyond (status validity_limit): a law whose inverse
/// refuses targets above k_n Δ_lim.
class LimitedLinearLaw : public LinearLaw
{
public:
  LimitedLinearLaw(double stiffness, double limit) : LinearLaw(stiffness), _k(stiffness), _limit(limit) {}
  std::string name() const override { return "limited_linear_test_law"; }
  double maximum_closure() const override { return _limit; }

protected:
  constitutive::ClosureResponse evaluate_contact(double d) const override
  {
    if (d >= _limit)
      return {_k * _limit, 0.0, 0.0, 0.0, constitutive::Status::validity_limit};
    return LinearLaw::evaluate_contact(d);
  }

private:
  double _k, _limit;
};

JointBehaviour elastic_joint(std::shared_ptr<const constitutive::ClosureLaw> law, double kr)
{
  JointBehaviour b;
  b.law = std::move(law);
  b.residual_stiffness = kr;
  return b;
}
} // namespace

TEST(FemJointBehaviour, ClosureAtNormalStressOfALinearLawIsTheSeriesOfBothSprings)
{
  const double kr = 2e9;
  const JointBehaviour b = elastic_joint(std::make_shared<LinearLaw>(kn), kr);
  for (double s : {1.0, 5e6, 80e6})
    EXPECT_NEAR(closure_at_normal_stress(b, s), s / (kn + kr), 1e-14 * s / (kn + kr)) << s;
  EXPECT_EQ(closure_at_normal_stress(b, 0.0), 0.0);
}

TEST(FemJointBehaviour, ClosureAtNormalStressOfBartonBandisSolvesTheQuadratic)
{
  // K Δ / (1 - Δ/V) + k_r Δ = σ  <=>  k_r Δ² - b Δ + σ V = 0, b = K V + k_r V + σ; the root
  // below V, in the cancellation-free form Δ = 2 σ V / (b + sqrt(b² - 4 k_r σ V)).
  const double K = 2e10, V = 0.5e-3;
  auto law = std::make_shared<constitutive::BartonBandis>(K, V);
  for (double kr : {1e8, 1e10, 1e12})
  {
    const JointBehaviour b = elastic_joint(law, kr);
    for (double s : {1e3, 1e6, 10e6, 100e6})
    {
      const double bq = K * V + kr * V + s;
      const double expected = 2.0 * s * V / (bq + std::sqrt(bq * bq - 4.0 * kr * s * V));
      const double d = closure_at_normal_stress(b, s);
      EXPECT_NEAR(d, expected, 1e-12 * expected) << "k_r " << kr << " σ " << s;
      EXPECT_LT(d, law->closure_at_stress(s)) << "k_r carries part of σ: less closure";
    }
  }
}

TEST(FemJointBehaviour, ClosureAtNormalStressWithoutResidualStiffnessIsTheLawsInverse)
{
  auto bb = std::make_shared<constitutive::BartonBandis>(2e10, 0.5e-3);
  auto linear = std::make_shared<LinearLaw>(kn);
  for (double s : {1e3, 10e6, 100e6})
  {
    EXPECT_EQ(closure_at_normal_stress(elastic_joint(bb, 0.0), s), bb->closure_at_stress(s));
    EXPECT_EQ(closure_at_normal_stress(elastic_joint(linear, 0.0), s), linear->closure_at_stress(s));
  }
}

TEST(FemJointBehaviour, ClosureAtNormalStressRefusesBadTargetsWithNamedErrors)
{
  using rockjoint::testing::expect_error;
  const JointBehaviour b = elastic_joint(std::make_shared<LimitedLinearLaw>(kn, 1e-3), 1e9);
  for (double bad : {std::nan(""), -1.0, std::numeric_limits<double>::infinity()})
    expect_error([&] { closure_at_normal_stress(b, bad); },
                 {"joint normal stress", "limited_linear_test_law", "finite and >= 0"});
  expect_error([&] { closure_at_normal_stress(b, -2.5e6); }, "-2.5e+06 Pa");
  // Beyond the law's validity limit σ = k_n Δ_lim = 1e7 Pa: refused with the law's reason.
  expect_error<std::domain_error>([&] { closure_at_normal_stress(b, 2e7); },
                                  {"joint normal stress 2e+07 Pa", "admissible range"});
  // Inside it: the linear closed form.
  EXPECT_NEAR(closure_at_normal_stress(b, 5e6), 5e6 / (kn + 1e9), 1e-14 * 5e6 / (kn + 1e9));
  expect_error([&] { closure_at_normal_stress(JointBehaviour{}, 1e6); }, "no closure law");
}

// Water in the joint (joint_behaviour.hpp): the law and the strength see σ' = σ_n - α p, the
// water pushes the walls apart with α p; the closed forms of the linear test law (σ' = k_n Δ).
TEST(JointSlip, WaterPressureActsThroughTheEffectiveStress)
{
  const double phi = 30 * deg, c = 1e5, closure = 1e-4, p = 4e5;
  JointBehaviour b = coulomb(phi, c);
  JointPointState trial;
  const double sigma_eff = kn * closure;               // the law's σ' at this closure
  // Inside the cone: t_n = -(σ' + α p), the tangent is the dry one (p is a given load).
  const LocalResponse dry = joint_response(b, 2, {-closure, 1e-5, 0.0}, {}, trial);
  const LocalResponse wet = joint_response(b, 2, {-closure, 1e-5, 0.0}, {}, trial, p);
  EXPECT_DOUBLE_EQ(wet.traction[0], -(sigma_eff + p));
  EXPECT_DOUBLE_EQ(wet.normal_stress, sigma_eff);
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 2; ++k)
      EXPECT_EQ(wet.tangent[i][k], dry.tangent[i][k]);
  // Sliding: the strength is c + σ' tan φ, not c + (σ' + p) tan φ.
  const LocalResponse slip = joint_response(b, 2, {-closure, 5e-4, 0.0}, {}, trial, p);
  EXPECT_EQ(slip.shear_state, ShearState::slip);
  EXPECT_NEAR(slip.traction[1], c + sigma_eff * std::tan(phi), 1e-9 * sigma_eff);
  // α scales the water's push; α outside [0, 1] is refused, named.
  b.effective_stress_coefficient = 0.5;
  EXPECT_DOUBLE_EQ(joint_response(b, 2, {-closure, 1e-5, 0.0}, {}, trial, p).traction[0],
                   -(sigma_eff + 0.5 * p));
  b.effective_stress_coefficient = 1.5;
  rockjoint::testing::expect_error([&] { validate(b, "fault"); }, "effective_stress_coefficient");
}

// Strength reduction (joint_strength.hpp): Barton's peak divided by F at every σ'_n, i.e.
// τ_F = σ'_n tan(φ_r + JRC log10(JCS/σ'_n)) / F (the angle capped before the division), c and T
// divided by F, the dilation kept within the reduced friction. Closed forms of the linear test law.
TEST(JointSlip, StrengthReductionDividesBartonsPeakByTheFactorAtEveryNormalStress)
{
  const double factor = 1.6, jrc = 12.0, jcs = 80e6, phi_r = 27 * deg;
  JointBehaviour b = coulomb(phi_r, 0.0);
  b.strength.model = StrengthModel::barton;
  b.strength.jrc = jrc;
  b.strength.jcs = jcs;
  b.strength.reduction_factor = factor;
  EXPECT_NO_THROW(validate(b, "reduced"));
  // σ'_n from 0.05 MPa (angle 27 + 12 log10(1600) = 65.5°) to 50 MPa (29.4°), and 100 MPa past
  // JCS (φ_r alone); at 1 kPa the 70° cap acts before the division.
  for (double sigma : {1e3, 5e4, 3e5, 2e6, 1e7, 5e7, 1e8})
  {
    const double closure = sigma / kn;
    double angle = sigma >= jcs ? phi_r : phi_r + jrc * std::log10(jcs / sigma) * deg;
    angle = std::min(angle, 70 * deg);
    const double expected = sigma * std::tan(angle) / factor;
    JointPointState trial;
    const double js = 10.0 * expected / ks + 1e-6;  // well past the strength: sliding
    const LocalResponse r = joint_response(b, 2, {-closure, js, 0.0}, {}, trial);
    EXPECT_EQ(r.shear_state, ShearState::slip) << "σ'_n = " << sigma;
    EXPECT_NEAR(r.traction[1], expected, 1e-9 * expected) << "σ'_n = " << sigma;
    EXPECT_NEAR(shear_strength(b.strength, sigma, true).strength, expected, 1e-12 * expected);
  }
  expect_tangent_matches_fd(b, 2, {-2e6 / kn, 2e-3, 0.0}, {}, ShearState::slip);
  expect_tangent_matches_fd(b, 3, {-2e6 / kn, 2e-3, -1e-3}, {}, ShearState::slip);
  // F = 1 is the strength itself; F <= 0 or not finite is refused by name.
  b.strength.reduction_factor = 1.0;
  EXPECT_NEAR(shear_strength(b.strength, 2e6, true).strength,
              2e6 * std::tan(phi_r + jrc * std::log10(jcs / 2e6) * deg), 1e-6);
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::infinity()})
  {
    b.strength.reduction_factor = bad;
    rockjoint::testing::expect_error([&] { validate(b, "set B"); }, {"set B", "reduction_factor"});
  }
}

TEST(JointSlip, StrengthReductionDividesCohesionTensionAndBoundsTheDilation)
{
  // Coulomb with F = 2: c/F + σ tanφ/F; a bond of T holds to T/F; ψ = 30° on φ = 35°:
  // tan ψ_F = min(tan 30°, tan 35° / 2) = 0.350 (ψ_F = 19.3°), the closed-form increment of the
  // linear law with it (as DilationGivesTheClosedFormSlipIncrementAndNormalStress).
  const double phi = 35 * deg, psi = 30 * deg, c = 2e5, closure = 2e-4, js = 1e-3, factor = 2.0;
  JointBehaviour b = coulomb(phi, c, psi);
  b.strength.reduction_factor = factor;
  JointPointState trial;
  const LocalResponse r = joint_response(b, 2, {-closure, js, 0.0}, {}, trial);
  const double mu = std::tan(phi) / factor, tan_psi = std::min(std::tan(psi), mu);
  const double f = ks * js - c / factor - kn * closure * mu;
  const double dl = f / (ks + kn * mu * tan_psi);
  EXPECT_EQ(r.shear_state, ShearState::slip);
  EXPECT_NEAR(trial.dilation, tan_psi * dl, 1e-12 * js);
  EXPECT_NEAR(r.traction[1], c / factor + kn * (closure + tan_psi * dl) * mu, 1e-9 * c);
  // Tension: T = 1e5 Pa reduced to T/F = 0.5e5: a tension of 0.4e5 Pa holds, 0.6e5 Pa breaks it.
  JointBehaviour bond = coulomb(phi, c);
  bond.strength.tensile_strength = 1e5;
  bond.strength.reduction_factor = factor;
  const LocalResponse holds = joint_response(bond, 2, {0.4e5 / kn, 0.0, 0.0}, {}, trial);
  EXPECT_FALSE(trial.bond_broken);
  EXPECT_NEAR(holds.traction[0], 0.4e5, 1e-6);
  joint_response(bond, 2, {0.6e5 / kn, 0.0, 0.0}, {}, trial);
  EXPECT_TRUE(trial.bond_broken);
}

// Δ_m (JointPointState::maximum_closure) is kept for every closure law, not only hysteretic
// ones: the trial follows the elastic closure Δ_e = -j_n + d, the converged one only by commit.
TEST(JointSlip, EveryLawKeepsTheLargestElasticClosureInItsTrialState)
{
  const JointBehaviour b = coulomb(30 * deg, 0.0, 10 * deg);  // linear law: no history
  ASSERT_FALSE(b.law->has_history());
  JointPointState converged, trial;
  converged.maximum_closure = 3e-4;
  joint_response(b, 2, {-1e-4, 0.0, 0.0}, converged, trial);  // unloaded: Δ_m stays
  EXPECT_EQ(trial.maximum_closure, 3e-4);
  joint_response(b, 2, {-5e-4, 0.0, 0.0}, converged, trial);  // past it: Δ_m = Δ
  EXPECT_EQ(trial.maximum_closure, 5e-4);
  EXPECT_EQ(converged.maximum_closure, 3e-4);                  // the converged copy is untouched
  // Sliding with dilation: Δ_m is the elastic closure after the return, -j_n + dilation.
  const LocalResponse s = joint_response(b, 2, {-5e-4, 5e-3, 0.0}, converged, trial);
  ASSERT_EQ(s.shear_state, ShearState::slip);
  ASSERT_GT(trial.dilation, 0.0);
  EXPECT_NEAR(trial.maximum_closure, 5e-4 + trial.dilation, 1e-18);
  EXPECT_NEAR(-s.traction[0], kn * trial.maximum_closure, 1e-6);
}
