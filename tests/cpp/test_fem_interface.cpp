// Interface assembler kernels (plain arrays, no PETSc objects): local frame, quadrature,
// residual balance, and the consistent pair Jacobian against central finite differences.
#include <rockjoint/fem_coupling/facet_quadrature.hpp>
#include <rockjoint/fem_coupling/interface_assembler.hpp>
#include <rockjoint/fem_coupling/local_frame.hpp>

#include <rockjoint/constitutive/barton_bandis.hpp>
#include <rockjoint/constitutive/empirical_laws.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

using namespace rockjoint;
using namespace rockjoint::fem;

namespace
{
/// One pair: minus nodes 0..n-1, plus nodes n..2n-1 at the same positions.
struct PairFixture
{
  int gdim;
  std::vector<std::int32_t> minus, plus, tags{7};
  std::vector<double> vertices, interior;

  explicit PairFixture(int g) : gdim(g)
  {
    for (int a = 0; a < g; ++a)
    {
      minus.push_back(a);
      plus.push_back(g + a);
    }
    if (g == 2)
    { // inclined segment, minus cell below-left of it
      vertices = {0.0, 0.0, 2.0, 1.0};
      interior = {1.0, -0.5};
    }
    else
    {
      vertices = {0.0, 0.0, 0.0, 1.5, 0.2, 0.1, 0.3, 1.2, -0.2};
      interior = {0.3, 0.3, -1.0};
    }
  }

  InterfaceAssembler make(JointBehaviour b, QuadratureRule rule = QuadratureRule::nodal) const
  {
    return InterfaceAssembler(gdim, 1, rule, minus, plus, vertices, interior, tags,
                              {{7, std::move(b)}});
  }
};

/// A displacement with the plus side pushed towards the minus side (closure > 0 everywhere)
/// plus a random shear, so that every point is in contact and away from the kink at Δ = 0.
std::vector<double> closing_displacement(const InterfaceAssembler& a, double closure, int seed)
{
  const int g = a.gdim();
  std::vector<double> n = a.normals();
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-0.2, 0.2);
  std::vector<double> u(2 * g * g);
  for (int node = 0; node < 2 * g; ++node)
  {
    const double side = node < g ? 0.5 : -0.5; // minus moves +n, plus moves -n
    for (int c = 0; c < g; ++c)
      u[node * g + c] = closure * (side * n[c] * (1.0 + d(gen)) + d(gen));
  }
  return u;
}

void expect_jacobian_matches_fd(InterfaceAssembler& a, std::vector<double> u, double tol)
{
  const int n = a.pair_size();
  std::vector<double> K(n * n);
  a.pair_matrix(0, u, K);
  std::vector<std::int32_t> dofs(n);
  a.pair_dofs(0, dofs);
  const double scale = std::abs(*std::max_element(u.begin(), u.end(), [](double x, double y)
                                                  { return std::abs(x) < std::abs(y); }));
  double kmax = 0.0;
  for (double k : K)
    kmax = std::max(kmax, std::abs(k));
  for (int j = 0; j < n; ++j)
  {
    const double h = 1e-6 * scale;
    std::vector<double> up = u, um = u, rp(u.size(), 0.0), rm(u.size(), 0.0);
    up[dofs[j]] += h;
    um[dofs[j]] -= h;
    a.assemble_residual(up, rp);
    a.assemble_residual(um, rm);
    for (int i = 0; i < n; ++i)
    {
      const double fd = (rp[dofs[i]] - rm[dofs[i]]) / (2 * h);
      EXPECT_NEAR(K[i * n + j], fd, tol * kmax) << "entry (" << i << ", " << j << ")";
    }
  }
}
} // namespace

TEST(FemLocalFrame, NormalPointsAwayFromMinusCellAndFrameIsOrthonormal)
{
  for (int g : {2, 3})
  {
    PairFixture f(g);
    const LocalFrame fr = facet_frame(g, f.vertices, f.interior);
    double side = 0.0;
    for (int c = 0; c < g; ++c)
      side += fr.axes[0][c] * (f.vertices[c] - f.interior[c]);
    EXPECT_GT(side, 0.0) << "gdim " << g;
    for (int i = 0; i < g; ++i)
      for (int j = 0; j < g; ++j)
      {
        double dot = 0.0;
        for (int c = 0; c < 3; ++c)
          dot += fr.axes[i][c] * fr.axes[j][c];
        EXPECT_NEAR(dot, i == j ? 1.0 : 0.0, 1e-14);
      }
  }
  // Segment (0,0)-(2,1): length √5. Triangle: |e1 × e2| / 2 from the vertices above.
  EXPECT_NEAR(facet_frame(2, PairFixture(2).vertices, PairFixture(2).interior).measure,
              std::sqrt(5.0), 1e-14);
  const double e1[3] = {1.5, 0.2, 0.1}, e2[3] = {0.3, 1.2, -0.2};
  const double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
               cz = e1[0] * e2[1] - e1[1] * e2[0];
  EXPECT_NEAR(facet_frame(3, PairFixture(3).vertices, PairFixture(3).interior).measure,
              0.5 * std::sqrt(cx * cx + cy * cy + cz * cz), 1e-14);
}

TEST(FemLocalFrame, DegenerateFacetIsRejected)
{
  const std::vector<double> v{0.0, 0.0, 0.0, 0.0}, p{1.0, 1.0};
  EXPECT_THROW(facet_frame(2, v, p), std::invalid_argument);
}

TEST(FemQuadrature, WeightsSumToOneAndReproduceLinearFunctions)
{
  for (int g : {2, 3})
    for (auto rule : {QuadratureRule::nodal, QuadratureRule::gauss})
    {
      const auto q = make_facet_quadrature(rule, g, 1);
      EXPECT_NEAR(std::accumulate(q.weights.begin(), q.weights.end(), 0.0), 1.0, 1e-15);
      // ∫ N_a = measure / n for linear shape functions (any exact rule).
      for (int a = 0; a < q.num_nodes; ++a)
      {
        double s = 0.0;
        for (int p = 0; p < q.num_points(); ++p)
          s += q.weights[p] * q.shape[p * q.num_nodes + a];
        EXPECT_NEAR(s, 1.0 / g, 1e-15);
      }
    }
  EXPECT_THROW(make_facet_quadrature(QuadratureRule::gauss, 3, 2), std::invalid_argument);
}

TEST(FemInterface, UniformClosureGivesLawTractionAndBalancedForces)
{
  // A rigid normal approach δ of the plus side: every point has Δ = δ, σ = σ_BB(δ), and the
  // nodal forces on each side sum to σ × measure along ∓n (Barton-Bandis closed form).
  const double Kni = 2e10, Vm = 1e-3, delta = 4e-4;
  const double sigma = Kni * delta / (1.0 - delta / Vm);
  for (int g : {2, 3})
  {
    PairFixture f(g);
    auto a = f.make({std::make_shared<constitutive::BartonBandis>(Kni, Vm)});
    const auto n = a.normals();
    std::vector<double> u(2 * g * g, 0.0), r(u.size(), 0.0);
    for (int node = g; node < 2 * g; ++node)
      for (int c = 0; c < g; ++c)
        u[node * g + c] = -delta * n[c];
    ASSERT_TRUE(a.assemble_residual(u, r));
    for (double s : a.normal_stress())
      EXPECT_NEAR(s, sigma, 1e-12 * sigma);
    for (double d : a.closure())
      EXPECT_NEAR(d, delta, 1e-15);
    const double A = a.measures()[0];
    for (int c = 0; c < g; ++c)
    {
      double plus = 0.0, minus = 0.0;
      for (int node = 0; node < g; ++node)
      {
        minus += r[node * g + c];
        plus += r[(g + node) * g + c];
      }
      // Residual = internal force: plus side pushed along +n by the contact ⇒ R_plus = -σ A n.
      EXPECT_NEAR(plus, -sigma * A * n[c], 1e-10 * sigma * A);
      EXPECT_NEAR(minus, sigma * A * n[c], 1e-10 * sigma * A);
    }
  }
}

TEST(FemInterface, PairJacobianMatchesFiniteDifferences)
{
  const double Kni = 1e10, Vm = 1e-3;
  auto bb = std::make_shared<constitutive::BartonBandis>(Kni, Vm);
  auto exp_law = std::make_shared<constitutive::ExponentialLaw>(1e-3, 5e6);
  for (int g : {2, 3})
    for (auto rule : {QuadratureRule::nodal, QuadratureRule::gauss})
    {
      PairFixture f(g);
      {
        auto a = f.make({bb, ShearModel::constant, 3e9, 0.0, 1e7}, rule);
        expect_jacobian_matches_fd(a, closing_displacement(a, 3e-4, 1), 1e-6);
      }
      {
        auto a = f.make({exp_law, ShearModel::proportional, 0.0, 0.3, 0.0}, rule);
        expect_jacobian_matches_fd(a, closing_displacement(a, 2e-4, 2), 1e-5);
      }
    }
}

TEST(FemInterface, AdmissibleStepKeepsClosureBelowMaximum)
{
  const double Vm = 1e-3;
  PairFixture f(2);
  auto a = f.make({std::make_shared<constitutive::BartonBandis>(1e10, Vm)});
  const auto n = a.normals();
  std::vector<double> u(8, 0.0), du(8, 0.0);
  for (int node = 2; node < 4; ++node)
    for (int c = 0; c < 2; ++c)
      du[node * 2 + c] = -10.0 * Vm * n[c]; // would close 10 V_m
  const double alpha = a.admissible_step_length(u, du, 0.95);
  EXPECT_NEAR(alpha, 0.095, 1e-12);
  for (auto& x : du)
    x *= alpha;
  EXPECT_NEAR(a.maximum_closure_ratio(du), 0.95, 1e-12);
}

TEST(FemInterface, MissingBehaviourIsAClearError)
{
  PairFixture f(2);
  try
  {
    InterfaceAssembler(2, 1, QuadratureRule::nodal, f.minus, f.plus, f.vertices, f.interior, f.tags,
                       {{3, {std::make_shared<constitutive::BartonBandis>(1e10, 1e-3)}}});
    FAIL() << "expected std::invalid_argument";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("joint tag 7"), std::string::npos) << e.what();
  }
  EXPECT_THROW(validate({nullptr}, "j"), std::invalid_argument);
  EXPECT_THROW(validate({std::make_shared<constitutive::BartonBandis>(1e10, 1e-3),
                         ShearModel::constant, -1.0},
                        "j"),
               std::invalid_argument);
}

TEST(FemInterface, LocalArraysShorterThanThePairsAddressAreRefusedWithNames)
{
  // One 2D pair on nodes 0..3: every local array needs (3 + 1)·2 = 8 entries.
  PairFixture f(2);
  auto a = f.make({std::make_shared<constitutive::BartonBandis>(1e10, 1e-3)});
  EXPECT_EQ(a.minimum_local_size(), 8u);
  std::vector<double> u(8, 0.0), short_u(7, 0.0), residual(8, 0.0), short_residual(6, 0.0),
      matrix(a.pair_size() * a.pair_size());
  auto expect_named = [](auto&& call, const std::string& array)
  {
    try
    {
      call();
      FAIL() << "expected std::invalid_argument for " << array;
    }
    catch (const std::invalid_argument& e)
    {
      const std::string what = e.what();
      EXPECT_NE(what.find("'" + array + "'"), std::string::npos) << what;
      EXPECT_NE(what.find("8"), std::string::npos) << what;
    }
  };
  expect_named([&] { a.assemble_residual(short_u, residual); }, "u");
  expect_named([&] { a.assemble_residual(u, short_residual); }, "residual");
  expect_named([&] { a.pair_matrix(0, short_u, matrix); }, "u");
  expect_named([&] { a.maximum_closure_ratio(short_u); }, "u");
  expect_named([&] { a.admissible_step_length(u, short_u, 0.9); }, "du");
  EXPECT_THROW(a.pair_matrix(1, u, matrix), std::out_of_range);
  EXPECT_TRUE(a.assemble_residual(u, residual)); // the right sizes still work
}
