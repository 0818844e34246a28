// SPDX-License-Identifier: MIT
// Equivalent-continuum material: closed forms for one and two joint sets with the nonlinear
// Barton-Bandis closure (plane strain and 3D), finite-difference checks of the consistent
// tangent in the stick, slip and open states, and bad input.
#include "expect_error.hpp"
#include "joint_test_laws.hpp"

#include <rockjoint/constitutive/barton_bandis.hpp>
#include <rockjoint/continuum/equivalent_continuum.hpp>
#include <rockjoint/joint/joint_slip.hpp>

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <tuple>
#include <vector>

namespace
{
using namespace rockjoint;
using continuum::EquivalentContinuum;
using continuum::JointSet;
using continuum::SetState;

constexpr double E = 20e9, nu = 0.25;     // rock [Pa], [-]
constexpr double Kni = 20e9, Vm = 0.5e-3; // Barton-Bandis K_ni [Pa/m], V_m [m]

/// Barton-Bandis closure at normal stress σ, written out here (Bandis et al. 1983):
/// σ = K_ni Δ / (1 - Δ/V_m)  ⇔  Δ = σ V_m / (K_ni V_m + σ).
double bb_closure(double sigma) { return sigma * Vm / (Kni * Vm + sigma); }

JointSet bb_set(std::array<double, 3> n, double spacing, double phi_deg = 40.0)
{
  JointSet set;
  set.normal = n;
  set.spacing = spacing;
  set.behaviour = test::coulomb(phi_deg * test::deg, 0.0, 0.0,
                                std::make_shared<constitutive::BartonBandis>(Kni, Vm));
  return set;
}

/// Strain at which the material carries `target` (Voigt) from the virgin state: Newton on
/// ε with the material's tangent (a stress-controlled test driver).
std::vector<double> strain_for_stress(const EquivalentContinuum& m, const std::vector<double>& target)
{
  const int nv = m.strain_size();
  std::vector<SetState> conv(m.num_sets()), trial(m.num_sets());
  Eigen::VectorXd eps = Eigen::VectorXd::Zero(nv);
  for (int it = 0; it < 100; ++it)
  {
    const auto r = m.evaluate({eps.data(), static_cast<std::size_t>(nv)}, conv, trial);
    EXPECT_TRUE(r.converged);
    Eigen::VectorXd res(nv);
    Eigen::MatrixXd c(nv, nv);
    for (int i = 0; i < nv; ++i)
    {
      res(i) = target[i] - r.stress[i];
      for (int j = 0; j < nv; ++j)
        c(i, j) = r.tangent[i * nv + j];
    }
    if (res.norm() < 1e-9 * (1.0 + Eigen::Map<const Eigen::VectorXd>(target.data(), nv).norm()))
      break;
    eps += c.fullPivLu().solve(res);
  }
  return {eps.data(), eps.data() + nv};
}

TEST(ContinuumMaterial, NoSetIsIsotropicElasticity)
{
  const EquivalentContinuum m(3, E, nu, {});
  const auto eps = strain_for_stress(m, {-10e6, 0, 0, 0, 0, 0});
  EXPECT_NEAR(eps[0], -10e6 / E, 1e-12);
  EXPECT_NEAR(eps[1], nu * 10e6 / E, 1e-12);
}

TEST(ContinuumMaterial, UniaxialOneSetPlaneStrain)
{
  const double s = 0.3;
  const EquivalentContinuum m(2, E, nu, {bb_set({0, 1, 0}, s)});
  for (double sigma : {1e6, 5e6, 20e6})
  {
    const auto eps = strain_for_stress(m, {0.0, -sigma, 0.0});
    // plane strain: ε_yy = -(1-ν²) σ / E - Δ(σ)/s, ε_xx = ν(1+ν) σ / E, no shear
    EXPECT_NEAR(eps[1], -(1 - nu * nu) * sigma / E - bb_closure(sigma) / s, 1e-10 * sigma / E * 1e2);
    EXPECT_NEAR(eps[0], nu * (1 + nu) * sigma / E, 1e-12);
    EXPECT_NEAR(eps[2], 0.0, 1e-14);
  }
}

TEST(ContinuumMaterial, UniaxialOneSet3D)
{
  const double s = 0.5;
  const EquivalentContinuum m(3, E, nu, {bb_set({0, 0, 1}, s)});
  const double sigma = 8e6;
  const auto eps = strain_for_stress(m, {0, 0, -sigma, 0, 0, 0});
  EXPECT_NEAR(eps[2], -sigma / E - bb_closure(sigma) / s, 1e-12);
  EXPECT_NEAR(eps[0], nu * sigma / E, 1e-12);
  EXPECT_NEAR(eps[1], nu * sigma / E, 1e-12);
  // The secant modulus of the mass, 1/E_m = 1/E + Δ/(σ s), is well below the rock's.
  EXPECT_LT(sigma / -eps[2], 0.5 * E);
}

TEST(ContinuumMaterial, BiaxialTwoSetsPlaneStrainAnd3D)
{
  const double s1 = 0.2, s2 = 0.6, p = 12e6, q = 4e6;
  {
    const EquivalentContinuum m(2, E, nu, {bb_set({1, 0, 0}, s1), bb_set({0, 1, 0}, s2)});
    const auto eps = strain_for_stress(m, {-p, -q, 0.0});
    // plane strain elastic part: ε = ((1+ν)/E) ((1-ν)σ_xx - ν σ_yy)
    EXPECT_NEAR(eps[0], (1 + nu) / E * (-(1 - nu) * p + nu * q) - bb_closure(p) / s1, 1e-12);
    EXPECT_NEAR(eps[1], (1 + nu) / E * (-(1 - nu) * q + nu * p) - bb_closure(q) / s2, 1e-12);
  }
  {
    const double r = 2e6;
    const EquivalentContinuum m(3, E, nu, {bb_set({1, 0, 0}, s1), bb_set({0, 1, 0}, s2)});
    const auto eps = strain_for_stress(m, {-p, -q, -r, 0, 0, 0});
    EXPECT_NEAR(eps[0], (-p + nu * (q + r)) / E - bb_closure(p) / s1, 1e-12);
    EXPECT_NEAR(eps[1], (-q + nu * (p + r)) / E - bb_closure(q) / s2, 1e-12);
    EXPECT_NEAR(eps[2], (-r + nu * (p + q)) / E, 1e-12);
  }
}

TEST(ContinuumMaterial, InclinedSetInStickShearsLikeTheJoint)
{
  // Set at 30° to the load: σ_n = σ cos²θ, τ = σ sinθ cosθ (stick: τ < tan40° σ_n).
  const double s = 0.4, sigma = 6e6, th = 30 * test::deg;
  const std::array<double, 3> n{-std::sin(th), std::cos(th), 0};
  const EquivalentContinuum m(2, E, nu, {bb_set(n, s)});
  const auto eps = strain_for_stress(m, {0.0, -sigma, 0.0});
  const double sn = sigma * std::cos(th) * std::cos(th), tau = sigma * std::sin(th) * std::cos(th);
  // global jump g = -Δ(σ_n) n + (τ/k_s) t with t along the shear traction on the plane
  const std::array<double, 2> traction{0.0, -sigma * n[1]}; // σ n
  const double tn = traction[0] * n[0] + traction[1] * n[1];
  std::array<double, 2> tt{traction[0] - tn * n[0], traction[1] - tn * n[1]};
  EXPECT_NEAR(std::hypot(tt[0], tt[1]), tau, 1e-6);
  const double delta = bb_closure(sn);
  std::array<double, 2> g{-delta * n[0] + tt[0] / test::ks, -delta * n[1] + tt[1] / test::ks};
  const double exx = nu * (1 + nu) * sigma / E + n[0] * g[0] / s;
  const double eyy = -(1 - nu * nu) * sigma / E + n[1] * g[1] / s;
  const double gxy = (n[0] * g[1] + n[1] * g[0]) / s;
  EXPECT_NEAR(eps[0], exx, 1e-12);
  EXPECT_NEAR(eps[1], eyy, 1e-12);
  EXPECT_NEAR(eps[2], gxy, 1e-12);
}

/// Central-difference tangent of the stress from the same converged states.
void expect_consistent_tangent(const EquivalentContinuum& m, const std::vector<SetState>& conv,
                               std::vector<double> eps, joint::ShearState expected_state,
                               double rtol = 1e-5)
{
  const int nv = m.strain_size();
  std::vector<SetState> trial(m.num_sets());
  const auto r = m.evaluate(eps, conv, trial);
  ASSERT_TRUE(r.converged);
  // the state of the (first) set at this strain, from the joint law at the converged jump
  joint::JointPointState tmp;
  const auto lr = joint::joint_response(m.sets()[0].behaviour, m.gdim(), trial[0].jump,
                                        conv[0].joint, tmp);
  EXPECT_EQ(lr.shear_state, expected_state);
  double cnorm = 0;
  for (int i = 0; i < nv * nv; ++i)
    cnorm = std::max(cnorm, std::abs(r.tangent[i]));
  for (int j = 0; j < nv; ++j)
  {
    const double h = 1e-7 * (std::abs(eps[j]) + 1e-4);
    auto up = eps, dn = eps;
    up[j] += h;
    dn[j] -= h;
    std::vector<SetState> t1(m.num_sets()), t2(m.num_sets());
    const auto ru = m.evaluate(up, conv, t1), rd = m.evaluate(dn, conv, t2);
    for (int i = 0; i < nv; ++i)
      EXPECT_NEAR(r.tangent[i * nv + j], (ru.stress[i] - rd.stress[i]) / (2 * h), rtol * cnorm)
          << "C(" << i << "," << j << ")";
  }
}

/// Voigt strain a n⊗n + b (n⊗t + t⊗n) + c I (engineering shear): compression a < 0 across
/// the plane, shear b along t, and a lateral part c.
std::vector<double> strain_on_plane(int gdim, const std::array<double, 3>& n,
                                    const std::array<double, 3>& t, double a, double b, double c)
{
  auto e = [&](int i, int j) { return a * n[i] * n[j] + b * (n[i] * t[j] + t[i] * n[j]) + (i == j ? c : 0.0); };
  if (gdim == 2)
    return {e(0, 0), e(1, 1), 2 * e(0, 1)};
  return {e(0, 0), e(1, 1), e(2, 2), 2 * e(1, 2), 2 * e(0, 2), 2 * e(0, 1)};
}

TEST(ContinuumMaterial, TangentStickSlipOpen2D)
{
  const double th = 35 * test::deg;
  const std::array<double, 3> n{-std::sin(th), std::cos(th), 0}, t{std::cos(th), std::sin(th), 0};
  const std::vector<SetState> conv(1);
  // stick: small shear; slip: shear above tan φ; open: tension across the set
  expect_consistent_tangent(EquivalentContinuum(2, E, nu, {bb_set(n, 0.3, 40)}), conv,
                            strain_on_plane(2, n, t, -8e-4, 1e-4, -1e-4), joint::ShearState::stick);
  expect_consistent_tangent(EquivalentContinuum(2, E, nu, {bb_set(n, 0.3, 15)}), conv,
                            strain_on_plane(2, n, t, -8e-4, 1e-3, -1e-4), joint::ShearState::slip);
  JointSet open = bb_set(n, 0.3);
  open.behaviour.residual_stiffness = 1e6;
  expect_consistent_tangent(EquivalentContinuum(2, E, nu, {open}), conv,
                            strain_on_plane(2, n, t, 3e-4, 1e-4, -2e-4), joint::ShearState::open);
}

TEST(ContinuumMaterial, TangentStickSlipOpen3DTwoSets)
{
  const double th = 35 * test::deg;
  const std::array<double, 3> n{0, -std::sin(th), std::cos(th)}, t{0.6, 0.8 * std::cos(th), 0.8 * std::sin(th)};
  const std::vector<SetState> conv(2);
  for (auto [phi, b, state] : {std::tuple{40.0, 1e-4, joint::ShearState::stick},
                               std::tuple{15.0, 1e-3, joint::ShearState::slip}})
  {
    const EquivalentContinuum m(3, E, nu, {bb_set(n, 0.3, phi), bb_set({1, 0, 0}, 0.5)});
    expect_consistent_tangent(m, conv, strain_on_plane(3, n, t, -8e-4, b, -1e-4), state);
  }
  JointSet open = bb_set(n, 0.3);
  open.behaviour.residual_stiffness = 1e6;
  const EquivalentContinuum m(3, E, nu, {open, bb_set({1, 0, 0}, 0.5)});
  expect_consistent_tangent(m, conv, strain_on_plane(3, n, t, 3e-4, 1e-4, -2e-4),
                            joint::ShearState::open);
}

TEST(ContinuumMaterial, SlipIsPathDependentThroughTheConvergedState)
{
  // Slip in one step and commit; re-evaluating the same strain from the committed state gives
  // the same stress with no further slip, and a partial unloading (elastic, stick) differs from
  // the virgin response at that strain (ubiquitous-joint plasticity keeps the slip).
  const double th = 35 * test::deg;
  const std::array<double, 3> n{-std::sin(th), std::cos(th), 0}, t{std::cos(th), std::sin(th), 0};
  const EquivalentContinuum m(2, E, nu, {bb_set(n, 0.3, 15)});
  std::vector<SetState> conv(1), trial(1);
  const auto loaded = strain_on_plane(2, n, t, -8e-4, 1e-3, -1e-4);
  const auto r1 = m.evaluate(loaded, conv, trial);
  ASSERT_TRUE(r1.converged);
  const double slip = trial[0].joint.slip[0];
  EXPECT_GT(std::abs(slip), 1e-5);
  conv = trial; // commit
  const auto r2 = m.evaluate(loaded, conv, trial);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(r2.stress[i], r1.stress[i], 1e-6 * std::abs(r1.stress[1]));
  EXPECT_NEAR(trial[0].joint.slip[0], slip, 1e-9 * std::abs(slip));
  const auto unloaded = strain_on_plane(2, n, t, -8e-4, 0.8e-3, -1e-4);
  const auto r3 = m.evaluate(unloaded, conv, trial);
  EXPECT_NEAR(trial[0].joint.slip[0], slip, 1e-9 * std::abs(slip)); // stick on unloading
  const std::vector<SetState> virgin(1);
  std::vector<SetState> trial0(1);
  const auto r0 = m.evaluate(unloaded, virgin, trial0);
  EXPECT_GT(std::abs(r3.stress[2] - r0.stress[2]), 1e4);
}

TEST(ContinuumMaterial, AFailedSolveFromTheConvergedJumpsIsRetriedFromTheTrialJumps)
{
  // The converged jumps carry a closure past V_m, where the law has no traction: the solve from
  // there fails at once. From the trial jumps passed in (here the virgin 0) it succeeds, with
  // the stress of a solve from a regular start (the same joint history, virgin).
  const EquivalentContinuum m(2, E, nu, {bb_set({0, 1, 0}, 0.3)});
  const std::vector<double> sigma{-2e6, -6e6, 0.4e6};
  std::vector<SetState> virgin(1), scratch(1);
  const auto eps = m.strain_at_stress(sigma, scratch);
  std::vector<SetState> reference_trial(1);
  const auto reference = m.evaluate(eps, virgin, reference_trial);
  ASSERT_TRUE(reference.converged);
  std::vector<SetState> bad(1);
  bad[0].jump = {-1.2 * Vm, 0.0, 0.0};
  std::vector<SetState> trial = bad; // no other start: fails
  EXPECT_FALSE(m.evaluate(eps, bad, trial).converged);
  trial.assign(1, SetState{}); // the last iterate's jumps: 0
  const auto retried = m.evaluate(eps, bad, trial);
  ASSERT_TRUE(retried.converged);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(retried.stress[i], reference.stress[i], 1e-9 * 6e6) << i;
}

TEST(ContinuumMaterial, StrainAtStressInvertsEvaluate)
{
  const EquivalentContinuum m(3, E, nu, {bb_set({0, 0, 1}, 0.3), bb_set({1, 0, 0}, 0.5)});
  const std::vector<double> sigma{-6e6, -3e6, -9e6, 0.5e6, 0.2e6, -0.3e6};
  std::vector<SetState> states(2), trial(2);
  const auto eps = m.strain_at_stress(sigma, states);
  const std::vector<SetState> virgin(2);
  const auto r = m.evaluate(eps, virgin, trial);
  ASSERT_TRUE(r.converged);
  for (int i = 0; i < 6; ++i)
    EXPECT_NEAR(r.stress[i], sigma[i], 1e-6 * 9e6);
}

TEST(ContinuumMaterial, BadInput)
{
  using rockjoint::testing::expect_error;
  expect_error([] { EquivalentContinuum(2, E, nu, {bb_set({0, 1, 0}, 0.0)}); },
               {"spacing", "0"});
  expect_error([] { EquivalentContinuum(2, E, nu, {bb_set({0, 1, 0}, -1.0)}); }, "spacing");
  expect_error([] { EquivalentContinuum(3, E, nu, {bb_set({0, 1, 1}, 0.3)}); }, "|normal|");
  expect_error([] { EquivalentContinuum(2, E, nu, {bb_set({0, 0.6, 0.8}, 0.3)}); }, "normal[2]");
  expect_error([] { EquivalentContinuum(2, -E, nu, {}); }, "young");
  expect_error([] { EquivalentContinuum(4, E, nu, {}); }, "gdim");
  const EquivalentContinuum m(2, E, nu, {bb_set({0, 1, 0}, 0.3)});
  std::vector<SetState> c(1), t(1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_error([&] { m.evaluate(std::vector<double>{0, nan, 0}, c, t); }, "strain[1]");
  std::vector<double> stress(3), tangent(9);
  expect_error([&] { continuum::evaluate_points(m, std::vector<double>{nan, 0, 0}, c, t, stress, tangent); },
               {"point 0", "finite"});
}
} // namespace
