// SPDX-License-Identifier: MIT
// The influence operator u = K p of the contact reference (contact/half_space.hpp) against
// references that do not use its transforms: the direct sum of Love's coefficients (zero-padded
// kernel) and the exact response to a sinusoidal pressure (periodic kernel). Grids from 256²
// up run the threaded, column-blocked transform; odd sizes leave a partial column block.
#include <rockjoint/contact/half_space.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

using rockjoint::contact::HalfSpace;
using rockjoint::contact::Kernel;

namespace
{
constexpr double modulus = 50e9; // E* [Pa]

struct Grid
{
  std::size_t rows, cols;
};

class NonPeriodicConvolution : public ::testing::TestWithParam<Grid>
{
};

/// Non-periodic: sparse random pressures; u at every node against Σ_b influence(x_a - x_b) p_b.
TEST_P(NonPeriodicConvolution, EqualsTheDirectSumOfLoveCoefficients)
{
  const auto [rows, cols] = GetParam();
  const double hx = 1e-4, hy = 1.3e-4;
  HalfSpace hs(rows, cols, hx, hy, modulus, Kernel::non_periodic);
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::size_t> node(0, rows * cols - 1);
  std::uniform_real_distribution<double> value(1e6, 5e7);
  std::vector<double> p(rows * cols, 0.0);
  std::vector<std::size_t> loaded;
  for (int k = 0; k < 12; ++k)
  {
    const std::size_t b = node(rng);
    p[b] += value(rng);
    loaded.push_back(b);
  }
  loaded.push_back(0); // the corners: the longest offsets of the padded kernel
  loaded.push_back(rows * cols - 1);
  p[0] = 2e7;
  p[rows * cols - 1] = 3e7;
  std::vector<double> u(rows * cols);
  hs.displacement(p, u);
  double largest = 0.0, worst = 0.0;
  for (std::size_t a = 0; a < rows * cols; a += 97) // a spread sample of nodes
  {
    const double ia = double(a / cols), ja = double(a % cols);
    double sum = 0.0;
    for (std::size_t b = 0; b < rows * cols; ++b)
      if (p[b] != 0.0)
        sum += hs.influence((ja - double(b % cols)) * hx, (ia - double(b / cols)) * hy) * p[b];
    largest = std::max(largest, std::abs(sum));
    worst = std::max(worst, std::abs(u[a] - sum));
  }
  EXPECT_GT(largest, 0.0);
  EXPECT_LE(worst, 1e-12 * largest) << rows << " x " << cols;
}

INSTANTIATE_TEST_SUITE_P(Grids, NonPeriodicConvolution,
                         ::testing::Values(Grid{16, 16}, Grid{37, 53}, Grid{256, 300},
                                           Grid{301, 257}),
                         [](const auto& info)
                         { return std::to_string(info.param.rows) + "x" + std::to_string(info.param.cols); });

/// Periodic: p = cos(2π (m x/L_x + k y/L_y)) gives u = 2 p/(E* |q|) exactly.
TEST(PeriodicConvolution, SinusoidalPressureGivesTheExactDisplacement)
{
  for (const Grid g : {Grid{64, 48}, Grid{256, 320}})
  {
    const double hx = 1e-4, hy = 2e-4;
    HalfSpace hs(g.rows, g.cols, hx, hy, modulus, Kernel::periodic);
    const double lx = hx * double(g.cols), ly = hy * double(g.rows);
    const double qx = 2.0 * std::numbers::pi * 3.0 / lx, qy = 2.0 * std::numbers::pi * 5.0 / ly;
    std::vector<double> p(g.rows * g.cols), u(p.size());
    for (std::size_t i = 0; i < g.rows; ++i)
      for (std::size_t j = 0; j < g.cols; ++j)
        p[i * g.cols + j] = 1e6 * std::cos(qx * double(j) * hx + qy * double(i) * hy);
    hs.displacement(p, u);
    const double gain = 2.0 / (modulus * std::hypot(qx, qy));
    double worst = 0.0;
    for (std::size_t k = 0; k < p.size(); ++k)
      worst = std::max(worst, std::abs(u[k] - gain * p[k]));
    EXPECT_LE(worst, 1e-12 * gain * 1e6) << g.rows << " x " << g.cols;
  }
}

/// The direct sums of the contact solver against the transform: K p on a node set
/// (displacement_on, sorted into row pairs, on two threads from 512² transform points) and the
/// carried update u ← s (u - τ r) + K c (carry_displacement), both kernels, the 512² grid
/// threaded, nodes in no order and one repeated (its two loads add).
TEST(HalfSpaceDirectSums, EqualTheTransform)
{
  for (const auto kernel : {Kernel::periodic, Kernel::non_periodic})
    for (const Grid g : {Grid{40, 30}, Grid{512, 512}})
    {
      HalfSpace hs(g.rows, g.cols, 1e-4, 1.2e-4, modulus, kernel);
      const std::size_t n = g.rows * g.cols;
      std::mt19937 rng(11);
      std::uniform_int_distribution<std::size_t> node(0, n - 1);
      std::uniform_real_distribution<double> value(1e6, 5e7);
      std::vector<std::size_t> nodes{n - 1, 0, g.cols - 1, (g.rows - 1) * g.cols};
      for (int k = 0; k < 60; ++k)
        nodes.push_back(node(rng));
      nodes.push_back(nodes[5]);
      std::vector<double> values(nodes.size()), p(n, 0.0), r(n), u(n), v(n), sums(nodes.size());
      for (std::size_t a = 0; a < nodes.size(); ++a)
      {
        values[a] = value(rng);
        p[nodes[a]] += values[a];
      }
      hs.displacement(p, u);
      hs.displacement_on(nodes, values, sums);
      double worst = 0.0, scale = 0.0;
      for (std::size_t a = 0; a < nodes.size(); ++a)
      {
        worst = std::max(worst, std::abs(sums[a] - u[nodes[a]]));
        scale = std::max(scale, std::abs(u[nodes[a]]));
      }
      EXPECT_GT(scale, 0.0);
      EXPECT_LE(worst, 1e-12 * scale) << "displacement_on " << g.rows << " x " << g.cols;
      // carried: v = K q for a dense q, r = K w; then v ← s (v - τ r) + K c must be K (s (q - τ w) + c)
      std::vector<double> q(n), w(n), exact(n);
      for (std::size_t k = 0; k < n; ++k)
      {
        q[k] = value(rng);
        w[k] = value(rng);
      }
      hs.displacement(q, v);
      hs.displacement(w, r);
      const double s = 0.93, tau = 0.37;
      hs.carry_displacement(s, tau, r, nodes, values, v);
      for (std::size_t k = 0; k < n; ++k)
        q[k] = s * (q[k] - tau * w[k]) + p[k];
      hs.displacement(q, exact);
      worst = scale = 0.0;
      for (std::size_t k = 0; k < n; ++k)
      {
        worst = std::max(worst, std::abs(v[k] - exact[k]));
        scale = std::max(scale, std::abs(exact[k]));
      }
      EXPECT_LE(worst, 1e-12 * scale) << "carry_displacement " << g.rows << " x " << g.cols;
    }
}

/// A size's first transforms are planned by FFTW_ESTIMATE, those planned after
/// measure_after_plans plans of the size (and every transform of 1024² points up) by
/// FFTW_MEASURE (contact/half_space.hpp, detail::measure_plans): the two plans must give the same
/// operator. A size no other test uses, so the first object here is the first of its size.
TEST(HalfSpacePlans, EstimatedAndMeasuredPlansGiveTheSameOperator)
{
  using rockjoint::contact::detail::measure_after_plans;
  using rockjoint::contact::detail::measure_from_points;
  using rockjoint::contact::detail::measure_plans;
  EXPECT_FALSE(measure_plans(256 * 256, 0));
  EXPECT_FALSE(measure_plans(256 * 256, measure_after_plans - 1));
  EXPECT_TRUE(measure_plans(256 * 256, measure_after_plans));
  EXPECT_TRUE(measure_plans(measure_from_points, 0));
  for (const auto kernel : {Kernel::periodic, Kernel::non_periodic})
  {
    const std::size_t rows = 94, cols = 70;
    HalfSpace estimated(rows, cols, 1e-4, 1.2e-4, modulus, kernel);
    for (std::size_t k = 1; k < measure_after_plans; ++k)
      HalfSpace(rows, cols, 1e-4, 1.2e-4, modulus, kernel);
    HalfSpace measured(rows, cols, 1e-4, 1.2e-4, modulus, kernel);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> value(0.0, 5e7);
    std::vector<double> p(rows * cols), u(p.size()), v(p.size());
    for (double& x : p)
      x = value(rng);
    estimated.displacement(p, u);
    measured.displacement(p, v);
    double worst = 0.0, scale = 0.0;
    for (std::size_t k = 0; k < p.size(); ++k)
    {
      worst = std::max(worst, std::abs(u[k] - v[k]));
      scale = std::max(scale, std::abs(u[k]));
    }
    EXPECT_GT(scale, 0.0);
    EXPECT_LE(worst, 1e-12 * scale) << (kernel == Kernel::periodic ? "periodic" : "non-periodic");
  }
}

} // namespace
