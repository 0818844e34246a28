// SPDX-License-Identifier: MIT
// The transmissivity of an aperture field (flow/reynolds_flow.hpp) against closed forms:
// parallel plates (e_h = e), apertures varying across the flow only (arithmetic mean of e³) and
// along it only (harmonic mean), a separable conductance k1(x) k2(y) (p = p(x) is exact), the
// two-phase checkerboard (Dykhne 1971, Keller 1964: √(k1 k2)); a smooth field converges at second
// order; T is symmetric; pockets, closed paths, masked points and near-zero cells; bad input.
#include "expect_error.hpp"

#include <rockjoint/flow/reynolds_flow.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

using namespace rockjoint::flow;
using rockjoint::testing::expect_error;

namespace
{
constexpr double pi = std::numbers::pi;

struct Case
{
  Boundary boundary;
  LinearSolver solver;
};

std::string case_name(const Case& c)
{
  return std::string(c.boundary == Boundary::periodic ? "periodic" : "sealed")
         + (c.solver == LinearSolver::cholesky              ? "_cholmod"
            : c.solver == LinearSolver::simplicial_cholesky ? "_simplicial"
                                                            : "_cg");
}

/// A rows x cols field e(i, j) [m].
std::vector<double> field(std::size_t rows, std::size_t cols,
                          const std::function<double(std::size_t, std::size_t)>& e)
{
  std::vector<double> out(rows * cols);
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t j = 0; j < cols; ++j)
      out[i * cols + j] = e(i, j);
  return out;
}

FlowResult solve(const std::vector<double>& e, std::size_t rows, std::size_t cols, double hx,
                 double hy, const Case& c)
{
  FlowOptions options;
  options.solver = c.solver;
  options.tolerance = 1e-12;
  return transmissivity(e, rows, cols, hx, hy, c.boundary, options);
}

double cube(double x) { return x * x * x; }

class FlowCases : public ::testing::TestWithParam<Case>
{
};

/// Two parallel plates at spacing e: T = e³/12 along both axes, e_h = e, no cross flux.
TEST_P(FlowCases, ParallelPlatesGiveTheirSpacing)
{
  const double e = 1.7e-4, hx = 2e-4, hy = 3e-4;
  const std::size_t rows = 23, cols = 31;
  const FlowResult r = solve(field(rows, cols, [&](auto, auto) { return e; }), rows, cols, hx, hy,
                             GetParam());
  ASSERT_TRUE(r.converged);
  const double t = cube(e) / 12.0;
  EXPECT_NEAR(r.transmissivity[0], t, 1e-10 * t);
  EXPECT_NEAR(r.transmissivity[3], t, 1e-10 * t);
  EXPECT_NEAR(hydraulic_aperture(r.transmissivity[0]), e, 1e-10 * e);
  EXPECT_NEAR(r.transmissivity[1], 0.0, 1e-10 * t);
  EXPECT_NEAR(r.transmissivity[2], 0.0, 1e-10 * t);
  EXPECT_NEAR(r.mechanical_aperture, e, 1e-12 * e);
  EXPECT_TRUE(r.percolates[0] && r.percolates[1]);
}

/// e(y) only: flow along x sees layers side by side (arithmetic mean of e³), flow along y the
/// same layers in series (harmonic mean); swapping the axes swaps the two. Off-diagonals 0.
TEST_P(FlowCases, LayeredAperturesGiveArithmeticAcrossAndHarmonicAlong)
{
  const std::size_t n_layered = 40, n_uniform = 17;
  const double hx = 1e-4, hy = 1.5e-4;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> aperture(2e-5, 3e-4);
  std::vector<double> layer(n_layered);
  double arithmetic = 0.0, resistance = 0.0;
  for (double& e : layer)
  {
    e = aperture(rng);
    arithmetic += cube(e) / 12.0 / double(n_layered);
    resistance += 12.0 / cube(e) / double(n_layered);
  }
  const double harmonic = 1.0 / resistance;
  for (const bool along_y : {true, false}) // layers stacked along y (e(y)), then along x (e(x))
  {
    const std::size_t rows = along_y ? n_layered : n_uniform, cols = along_y ? n_uniform : n_layered;
    const auto e = field(rows, cols, [&](std::size_t i, std::size_t j) { return layer[along_y ? i : j]; });
    const FlowResult r = solve(e, rows, cols, hx, hy, GetParam());
    ASSERT_TRUE(r.converged);
    const double t_across = along_y ? r.transmissivity[0] : r.transmissivity[3];
    const double t_along = along_y ? r.transmissivity[3] : r.transmissivity[0];
    EXPECT_NEAR(t_across, arithmetic, 1e-10 * arithmetic) << "arithmetic mean of e³/12";
    EXPECT_NEAR(t_along, harmonic, 1e-10 * harmonic) << "harmonic mean of e³/12";
    EXPECT_LT(harmonic, 0.5 * arithmetic); // the two means differ: the check can fail
    EXPECT_NEAR(r.transmissivity[1], 0.0, 1e-10 * arithmetic);
    EXPECT_NEAR(r.transmissivity[2], 0.0, 1e-10 * arithmetic);
  }
}

/// k = k1(x) k2(y): p = p(x) with k1 p' constant solves ∇·(k∇p) = 0 under a gradient along x,
/// so T_xx = <k2> H(k1) and T_yy = <k1> H(k2) (H: harmonic mean), also on the grid (the face
/// conductance factors the same way).
TEST_P(FlowCases, SeparableConductanceIsExact)
{
  const std::size_t rows = 24, cols = 36;
  const double hx = 1e-4, hy = 1e-4;
  auto k1 = [&](std::size_t j) { return 1.0 + 0.8 * std::sin(2 * pi * double(j) / double(cols)) + 0.3 * (j % 3); };
  auto k2 = [&](std::size_t i) { return 2.0 + std::cos(4 * pi * double(i) / double(rows)); };
  const double scale = cube(1e-4) / 12.0; // k [m³] = scale k1 k2
  const auto e = field(rows, cols, [&](std::size_t i, std::size_t j)
                       { return std::cbrt(12.0 * scale * k1(j) * k2(i)); });
  double mean1 = 0, mean2 = 0, inv1 = 0, inv2 = 0;
  for (std::size_t j = 0; j < cols; ++j)
  {
    mean1 += k1(j) / double(cols);
    inv1 += 1.0 / k1(j) / double(cols);
  }
  for (std::size_t i = 0; i < rows; ++i)
  {
    mean2 += k2(i) / double(rows);
    inv2 += 1.0 / k2(i) / double(rows);
  }
  const FlowResult r = solve(e, rows, cols, hx, hy, GetParam());
  ASSERT_TRUE(r.converged);
  const double txx = scale * mean2 / inv1, tyy = scale * mean1 / inv2;
  EXPECT_NEAR(r.transmissivity[0], txx, 1e-9 * txx);
  EXPECT_NEAR(r.transmissivity[3], tyy, 1e-9 * tyy);
}

/// Pockets (open regions no gradient drives) neither make the system singular nor carry flow;
/// an open channel along x carries its own e³/12 times its share of the width.
TEST_P(FlowCases, PocketsAreHarmlessAndAChannelCarriesItsShare)
{
  const std::size_t rows = 20, cols = 30;
  const double e = 1e-4, h = 1e-4;
  // rows 4-6 open across the grid (a channel along x); an open 4 x 4 pocket; isolated single
  // open cells; the rest closed
  const auto f = field(rows, cols, [&](std::size_t i, std::size_t j)
                       {
                         const bool channel = i >= 4 && i <= 6;
                         const bool pocket = i >= 10 && i < 14 && j >= 10 && j < 14;
                         const bool dot = i == 17 && j % 2 == 0;
                         return channel || pocket || dot ? e : 0.0;
                       });
  const FlowResult r = solve(f, rows, cols, h, h, GetParam());
  ASSERT_TRUE(r.converged);
  const double channel = 3.0 / double(rows) * cube(e) / 12.0;
  EXPECT_NEAR(r.transmissivity[0], channel, 1e-10 * channel);
  EXPECT_EQ(r.transmissivity[3], 0.0) << "no open path along y: exactly 0";
  EXPECT_EQ(r.transmissivity[1], 0.0);
  EXPECT_TRUE(r.percolates[0]);
  EXPECT_FALSE(r.percolates[1]);
}

/// No open path at all: cells open on a checkerboard touch only at corners (no face is open),
/// and a closed field carries nothing. T = 0 exactly, no system is solved.
TEST_P(FlowCases, NoOpenPathGivesZero)
{
  const std::size_t rows = 16, cols = 16;
  const auto checker = field(rows, cols, [](std::size_t i, std::size_t j) { return (i + j) % 2 ? 1e-4 : 0.0; });
  const auto closed = field(rows, cols, [](auto, auto) { return 0.0; });
  for (const auto* f : {&checker, &closed})
  {
    const FlowResult r = solve(*f, rows, cols, 1e-4, 1e-4, GetParam());
    for (const double t : r.transmissivity)
      EXPECT_EQ(t, 0.0);
    EXPECT_FALSE(r.percolates[0] || r.percolates[1]);
  }
}

/// Masked points (NaN) are impermeable like closed ones, but are not part of the scanned area
/// of the mechanical aperture.
TEST_P(FlowCases, MaskedPointsAreImpermeable)
{
  const std::size_t rows = 18, cols = 22;
  auto e = [](std::size_t i, std::size_t j) { return 1e-4 * (1.0 + 0.3 * std::sin(0.7 * double(i + 2 * j))); };
  const auto masked = field(rows, cols, [&](std::size_t i, std::size_t j)
                            { return j == 7 || (i == 3 && j > 10) ? std::nan("") : e(i, j); });
  const auto closed = field(rows, cols, [&](std::size_t i, std::size_t j)
                            { return j == 7 || (i == 3 && j > 10) ? 0.0 : e(i, j); });
  const FlowResult a = solve(masked, rows, cols, 1e-4, 1e-4, GetParam());
  const FlowResult b = solve(closed, rows, cols, 1e-4, 1e-4, GetParam());
  EXPECT_EQ(a.transmissivity[0], 0.0) << "a masked column blocks flow along x";
  EXPECT_GT(a.transmissivity[3], 0.0);
  for (std::size_t k = 0; k < 4; ++k)
    EXPECT_NEAR(a.transmissivity[k], b.transmissivity[k], 1e-9 * b.transmissivity[3]);
  EXPECT_GT(a.mechanical_aperture, b.mechanical_aperture); // the masked points are not zeros
  EXPECT_DOUBLE_EQ(a.open_fraction, 1.0);
}

/// Two blocks of open cells joined only by columns of near-zero cells (1e-13 m beside 1e-4 m:
/// the residual gaps a contact solver leaves at its contact points, issue 39). Those cells'
/// conductance is 1e-27 of the blocks': the system cannot resolve it, and a block that reaches
/// the inlet or the pinned cell only through them made CHOLMOD stop and LDLᵀ return T < 0.
/// They are closed: across them T_xx = 0 (the exact value, ~1e-40 m³, is below any resolution),
/// along them the blocks are layers, T_yy = (14/16) e³/12; the field stays 100 % open.
TEST_P(FlowCases, BlocksJoinedOnlyByNearZeroCellsCarryNothingAcrossThem)
{
  const std::size_t rows = 16, cols = 16;
  const double e = 1e-4, h = 1e-4;
  const auto f = field(rows, cols, [&](std::size_t i, std::size_t j)
                       { return j == 3 || j == 11 ? 1e-13 * double(1 + i % 3) : e; });
  const FlowResult r = solve(f, rows, cols, h, h, GetParam());
  ASSERT_TRUE(r.converged);
  EXPECT_EQ(r.transmissivity[0], 0.0);
  EXPECT_EQ(r.transmissivity[2], 0.0);
  const double layers = 14.0 / 16.0 * cube(e) / 12.0;
  EXPECT_NEAR(r.transmissivity[3], layers, 1e-10 * layers);
  EXPECT_NEAR(r.transmissivity[1], 0.0, 1e-10 * layers);
  EXPECT_FALSE(r.percolates[0]);
  EXPECT_TRUE(r.percolates[1]);
  EXPECT_DOUBLE_EQ(r.open_fraction, 1.0);
}

INSTANTIATE_TEST_SUITE_P(Boundaries, FlowCases,
                         ::testing::Values(Case{Boundary::periodic, LinearSolver::cholesky},
                                           Case{Boundary::periodic, LinearSolver::simplicial_cholesky},
                                           Case{Boundary::periodic, LinearSolver::conjugate_gradient},
                                           Case{Boundary::sealed_sides, LinearSolver::cholesky},
                                           Case{Boundary::sealed_sides, LinearSolver::simplicial_cholesky},
                                           Case{Boundary::sealed_sides, LinearSolver::conjugate_gradient}),
                         [](const auto& info) { return case_name(info.param); });

/// The two-phase checkerboard of conductances k1, k2 (squares of m x m cells, periodic):
/// effective conductivity √(k1 k2) exactly (Keller 1964, J. Math. Phys. 5, 548; Dykhne 1971,
/// Sov. Phys. JETP 32, 63). The grid answer converges to it as the squares are refined (the
/// field is singular at the corners, so slowly: the error falls as m^-0.77 at contrast
/// k2/k1 = 10, from 20 % at m = 4): it falls by at least a factor 1.5 with every refinement, is
/// within 3 % at m = 64 (a 128² grid), and the Richardson extrapolation of the last three grids
/// with their observed order is within 0.5 %.
TEST(Checkerboard, ConvergesToTheGeometricMeanOfTheConductances)
{
  const double k1 = cube(1e-4) / 12.0, k2 = 10.0 * k1, exact = std::sqrt(k1 * k2);
  const double e1 = std::cbrt(12.0 * k1), e2 = std::cbrt(12.0 * k2);
  double previous = std::numeric_limits<double>::infinity();
  std::vector<double> t;
  for (const std::size_t m : {4, 8, 16, 32, 64})
  {
    const std::size_t n = 2 * m;
    const auto e = field(n, n, [&](std::size_t i, std::size_t j) { return (i / m + j / m) % 2 ? e2 : e1; });
    const FlowResult r = transmissivity(e, n, n, 1e-4, 1e-4, Boundary::periodic);
    const double error = std::abs(r.transmissivity[0] - exact) / exact;
    std::cout << "checkerboard m = " << m << ": T_xx/√(k1 k2) - 1 = "
              << r.transmissivity[0] / exact - 1.0 << "\n";
    EXPECT_NEAR(r.transmissivity[0], r.transmissivity[3], 1e-10 * exact) << "isotropic";
    EXPECT_NEAR(r.transmissivity[1], 0.0, 1e-10 * exact);
    EXPECT_LT(1.5 * error, previous) << "m = " << m;
    previous = error;
    t.push_back(r.transmissivity[0]);
  }
  EXPECT_LT(previous, 0.03);
  const double ratio = (t[3] - t[2]) / (t[4] - t[3]); // 2^order
  const double extrapolated = t[4] + (t[4] - t[3]) / (ratio - 1.0);
  std::cout << "checkerboard: observed order " << std::log2(ratio) << ", extrapolated "
            << extrapolated / exact - 1.0 << "\n";
  EXPECT_NEAR(extrapolated, exact, 0.005 * exact);
}

/// A smooth field (no contact): the grid answer converges at second order. The differences
/// between successive refinements fall by about 4 (observed order 1.8-2.2).
TEST(SmoothField, ConvergesAtSecondOrder)
{
  const double length = 0.05, e0 = 2e-4;
  std::vector<double> t;
  for (const std::size_t n : {16, 32, 64, 128, 256})
  {
    const double h = length / double(n);
    // cell centres at (j + 1/2) h: the same points of the field on every grid
    const auto e = field(n, n, [&](std::size_t i, std::size_t j)
                         {
                           const double x = (double(j) + 0.5) * h / length, y = (double(i) + 0.5) * h / length;
                           return e0 * (1.0 + 0.6 * std::sin(2 * pi * x) * std::cos(2 * pi * y)
                                        + 0.2 * std::cos(2 * pi * (x + 2 * y)));
                         });
    t.push_back(transmissivity(e, n, n, h, h, Boundary::periodic).transmissivity[0]);
  }
  for (std::size_t i = 0; i + 2 < t.size(); ++i)
  {
    const double order = std::log2((t[i + 1] - t[i]) / (t[i + 2] - t[i + 1]));
    std::cout << "smooth field: observed order " << order << " (grids " << (16 << i) << "-"
              << (16 << (i + 2)) << ")\n";
    EXPECT_GT(order, 1.8);
    EXPECT_LT(order, 2.2);
  }
  EXPECT_LT(std::abs(t[4] - t[3]) / t[4], 1e-3);
}

/// An anisotropic rough field with contact spots (periodic): T is symmetric to the solver's
/// tolerance though T_xy is far from 0, and both solvers agree.
TEST(RoughField, TransmissivityIsSymmetricAndTheSolversAgree)
{
  const std::size_t n = 96;
  const double h = 1e-4;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> phase(0.0, 2 * pi);
  // (kx, ky, amplitude, phase): strong waves along (1, 1) (ridges along x = -y, so T has its
  // principal axes at 45°) over a weaker isotropic roughness
  std::vector<std::array<double, 4>> modes;
  for (int kx = -6; kx <= 6; ++kx)
    for (int ky = 0; ky <= 6; ++ky)
      if (ky > 0 || kx > 0)
        modes.push_back({double(kx), double(ky), (kx == ky ? 1.0 : 0.25) / std::hypot(kx, ky), phase(rng)});
  const auto e = field(n, n, [&](std::size_t i, std::size_t j)
                       {
                         double z = 0.0;
                         for (const auto& m : modes)
                           z += m[2] * std::cos(2 * pi * (m[0] * double(j) + m[1] * double(i)) / double(n) + m[3]);
                         return 1e-4 * std::max(0.0, 0.5 + 0.5 * z); // some points at contact
                       });
  FlowOptions cg;
  cg.solver = LinearSolver::conjugate_gradient;
  cg.tolerance = 1e-12;
  const FlowResult a = transmissivity(e, n, n, h, h, Boundary::periodic);
  const FlowResult b = transmissivity(e, n, n, h, h, Boundary::periodic, cg);
  const auto& t = a.transmissivity;
  ASSERT_GT(a.open_fraction, 0.5);
  ASSERT_LT(a.open_fraction, 0.99);
  std::cout << "rough field: open " << a.open_fraction << ", T / (1e-4 m)³/12 = " << t[0] / (1e-12 / 12) << " "
            << t[1] / (1e-12 / 12) << " " << t[2] / (1e-12 / 12) << " " << t[3] / (1e-12 / 12) << "\n";
  EXPECT_GT(std::abs(t[1]), 0.1 * t[0]) << "the field is anisotropic off the axes";
  EXPECT_NEAR(t[1], t[2], 1e-10 * t[0]);
  EXPECT_NEAR(b.transmissivity[1], b.transmissivity[2], 1e-8 * t[0]);
  for (std::size_t k = 0; k < 4; ++k)
    EXPECT_NEAR(a.transmissivity[k], b.transmissivity[k], 1e-8 * t[0]);
  EXPECT_GT(b.iterations[0], 0);
  EXPECT_LE(a.relative_residual, 1e-10);
  EXPECT_TRUE(a.converged && b.converged);
}

TEST(BadInput, IsNamed)
{
  const std::vector<double> ok(12, 1e-4);
  expect_error([&] { transmissivity(ok, 3, 5, 1e-4, 1e-4, Boundary::periodic); },
               {"12 values", "3 x 5", "15"});
  expect_error([&] { transmissivity(std::vector<double>(4, 1e-4), 1, 4, 1e-4, 1e-4, Boundary::periodic); },
               "at least 2 rows");
  auto with = [&](std::size_t k, double v)
  {
    auto f = ok;
    f[k] = v;
    return f;
  };
  expect_error([&] { transmissivity(with(7, -1e-6), 3, 4, 1e-4, 1e-4, Boundary::periodic); },
               {"row 1, column 3", "-9.99", ">= 0"});
  expect_error([&] { transmissivity(with(2, INFINITY), 3, 4, 1e-4, 1e-4, Boundary::sealed_sides); },
               {"row 0, column 2", "inf"});
  expect_error([&] { transmissivity(std::vector<double>(12, NAN), 3, 4, 1e-4, 1e-4, Boundary::periodic); },
               "no scanned point");
  expect_error([&] { transmissivity(ok, 3, 4, 0.0, 1e-4, Boundary::periodic); }, {"spacing_x", "> 0"});
  expect_error([&] { transmissivity(ok, 3, 4, 1e-4, NAN, Boundary::periodic); }, {"spacing_y", "nan"});
  FlowOptions bad;
  bad.solver = LinearSolver::conjugate_gradient;
  bad.tolerance = 0.0;
  expect_error([&] { transmissivity(ok, 3, 4, 1e-4, 1e-4, Boundary::periodic, bad); }, "tolerance");
}

} // namespace
