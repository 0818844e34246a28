// SPDX-License-Identifier: MIT
// Interface assembler kernels (plain arrays, no PETSc objects): local frame, quadrature,
// residual balance, and the consistent pair Jacobian against central finite differences.
#include <algorithm>
#include <rockjoint/fem_coupling/facet_quadrature.hpp>
#include <rockjoint/fem_coupling/interface_assembler.hpp>
#include <rockjoint/fem_coupling/local_frame.hpp>

#include <rockjoint/constitutive/barton_bandis.hpp>
#include <rockjoint/constitutive/empirical_laws.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <set>

using namespace rockjoint;
using namespace rockjoint::fem_coupling;
using namespace rockjoint::joint;

namespace
{
/// One pair: minus nodes 0..n-1, plus nodes n..2n-1 at the same positions; node k has the
/// unrolled dofs k·gdim + c.
struct PairFixture
{
  int gdim;
  std::vector<std::int32_t> dofs, tags{7};
  std::vector<double> vertices, interior;

  explicit PairFixture(int g) : gdim(g)
  {
    for (int k = 0; k < 2 * g * g; ++k)
      dofs.push_back(k);
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
    return InterfaceAssembler(gdim, 1, rule, dofs, vertices, interior, tags, {{7, std::move(b)}});
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
    InterfaceAssembler(2, 1, QuadratureRule::nodal, f.dofs, f.vertices, f.interior, f.tags,
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

namespace
{
using Vec3 = std::array<double, 3>;

Vec3 cross3(const Vec3& a, const Vec3& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot3(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// A triangulated 3D joint surface x(s, t) on an n × n grid of (s, t) ∈ [0, 1]²: per triangle
/// one pair with its own 6 unrolled dofs (minus nodes 0-2, plus nodes 3-5), the minus-cell
/// interior point 0.3 below the facet along -unit normal of the surface (`down`).
struct SurfaceJoint
{
  std::vector<std::int32_t> dofs, tags;
  std::vector<double> vertices, interior;
  int num_pairs = 0;

  template <typename Surface, typename Down>
  SurfaceJoint(int n, Surface x, Down down)
  {
    auto add = [&](const Vec3& a, const Vec3& b, const Vec3& c)
    {
      for (const Vec3* v : {&a, &b, &c})
        vertices.insert(vertices.end(), v->begin(), v->end());
      Vec3 centroid{};
      for (int k = 0; k < 3; ++k)
        centroid[k] = (a[k] + b[k] + c[k]) / 3.0;
      const Vec3 d = down(centroid);
      for (int k = 0; k < 3; ++k)
        interior.push_back(centroid[k] + 0.3 * d[k]);
      for (int k = 0; k < 18; ++k)
        dofs.push_back(18 * num_pairs + k);
      tags.push_back(7);
      ++num_pairs;
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
      {
        const double s0 = double(i) / n, s1 = double(i + 1) / n, t0 = double(j) / n,
                     t1 = double(j + 1) / n;
        // alternate the vertex order: the normal must come from the cell side, not the order
        add(x(s0, t0), x(s1, t0), x(s1, t1));
        add(x(s0, t0), x(s0, t1), x(s1, t1));
      }
  }

  InterfaceAssembler make(JointBehaviour b) const
  {
    return InterfaceAssembler(3, 1, QuadratureRule::nodal, dofs, vertices, interior, tags,
                              {{7, std::move(b)}});
  }
};

void expect_orthonormal_right_handed(const LocalFrame& f, int gdim)
{
  for (int i = 0; i < gdim; ++i)
    for (int j = 0; j < gdim; ++j)
      EXPECT_NEAR(dot3(f.axes[i], f.axes[j]), i == j ? 1.0 : 0.0, 1e-14);
  if (gdim == 3)
  {
    const double det = dot3(f.axes[0], cross3(f.axes[1], f.axes[2]));
    EXPECT_NEAR(det, 1.0, 1e-14);
  }
}

/// The pre-reference rule's choice (coordinate axis least aligned with n) for a normal: used
/// only to show that a test geometry sits on its tie.
int least_aligned_axis(const Vec3& n)
{
  int k = 0;
  for (int c = 1; c < 3; ++c)
    if (std::abs(n[c]) < std::abs(n[k]))
      k = c;
  return k;
}

std::shared_ptr<constitutive::BartonBandis> bb_law() { return std::make_shared<constitutive::BartonBandis>(2e10, 1e-3); }
} // namespace

TEST(FemInterface, ExplicitDofMapsAddressTheGivenEntries)
{
  // The same pair twice: contiguous dofs 0..11 (2D, 2 + 2 nodes) and a scattered map π into
  // a longer array. Residual and Jacobian must move with the map, nothing else.
  PairFixture f(2);
  const std::vector<std::int32_t> pi{13, 2, 7, 0, 11, 4, 9, 15};
  auto a = f.make({bb_law(), ShearModel::constant, 3e9});
  auto b = InterfaceAssembler(2, 1, QuadratureRule::nodal, pi, f.vertices, f.interior, f.tags,
                              {{7, {bb_law(), ShearModel::constant, 3e9}}});
  EXPECT_EQ(b.minimum_local_size(), 16u);
  std::vector<std::int32_t> got(8);
  b.pair_dofs(0, got);
  EXPECT_EQ(got, pi);
  const auto u = closing_displacement(a, 3e-4, 3);
  std::vector<double> ub(16, 0.0), ra(8, 0.0), rb(16, 0.0);
  for (int k = 0; k < 8; ++k)
    ub[pi[k]] = u[k];
  ASSERT_TRUE(a.assemble_residual(u, ra));
  ASSERT_TRUE(b.assemble_residual(ub, rb));
  std::vector<double> expected(16, 0.0);
  for (int k = 0; k < 8; ++k)
    expected[pi[k]] = ra[k];
  for (int k = 0; k < 16; ++k)
    EXPECT_EQ(rb[k], expected[k]) << "entry " << k;
  std::vector<double> Ka(64), Kb(64);
  a.pair_matrix(0, u, Ka);
  b.pair_matrix(0, ub, Kb);
  EXPECT_EQ(Ka, Kb);
  // A shared dof (unsplit node) and a short array are refused.
  auto shared = pi;
  shared[4] = shared[0];
  EXPECT_THROW(InterfaceAssembler(2, 1, QuadratureRule::nodal, shared, f.vertices, f.interior,
                                  f.tags, {{7, {bb_law()}}}),
               std::invalid_argument);
  std::vector<double> short_u(15, 0.0);
  EXPECT_THROW(b.assemble_residual(short_u, rb), std::invalid_argument);
}

TEST(FemLocalFrame, TwoDimensionalTangentIsTheNormalRotatedClockwise)
{
  PairFixture f(2);
  const LocalFrame fr = facet_frame(2, f.vertices, f.interior);
  // Segment (0,0)-(2,1), minus cell below: n = (-1, 2)/√5, t1 = (n_y, -n_x) = (2, 1)/√5.
  EXPECT_NEAR(fr.axes[0][0], -1.0 / std::sqrt(5.0), 1e-15);
  EXPECT_NEAR(fr.axes[0][1], 2.0 / std::sqrt(5.0), 1e-15);
  EXPECT_NEAR(fr.axes[1][0], 2.0 / std::sqrt(5.0), 1e-15);
  EXPECT_NEAR(fr.axes[1][1], 1.0 / std::sqrt(5.0), 1e-15);
}

TEST(FemLocalFrame, ReferenceDirectionIsTheStrikeOfTheMeanPlane)
{
  auto moment = [](Vec3 n, double area)
  {
    std::array<double, 9> M{};
    const double l = std::sqrt(dot3(n, n));
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        M[3 * i + j] = area * n[i] * n[j] / (l * l);
    return M;
  };
  auto expect_vec = [](Vec3 got, Vec3 want)
  {
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(got[c], want[c], 1e-14) << "component " << c;
  };
  const double th = 0.6;
  // Dipping towards +x (normal up-east): strike +y (dip to its right seen from above); the
  // moment does not see the normal's sign.
  expect_vec(joint_reference_direction(moment({std::sin(th), 0.0, std::cos(th)}, 2.0)), {0, 1, 0});
  expect_vec(joint_reference_direction(moment({-std::sin(th), 0.0, -std::cos(th)}, 2.0)), {0, 1, 0});
  // Dipping towards +y: strike -x.
  expect_vec(joint_reference_direction(moment({0.0, std::sin(th), std::cos(th)}, 1.0)), {-1, 0, 0});
  // Horizontal: x axis. Vertical with normal ±x: m = +x, strike e_z × x = +y.
  expect_vec(joint_reference_direction(moment({0.0, 0.0, -1.0}, 1.0)), {1, 0, 0});
  expect_vec(joint_reference_direction(moment({-1.0, 0.0, 0.0}, 1.0)), {0, 1, 0});
  // Two facets of a shallow V (normals ±10° about z in the x-z plane): mean axis z, x axis.
  auto M = moment({std::sin(0.17), 0.0, std::cos(0.17)}, 1.0);
  const auto M2 = moment({-std::sin(0.17), 0.0, std::cos(0.17)}, 1.0);
  for (int k = 0; k < 9; ++k)
    M[k] += M2[k];
  expect_vec(joint_reference_direction(M), {1, 0, 0});
  EXPECT_THROW(joint_reference_direction(std::array<double, 9>{}), std::invalid_argument);
  auto bad = moment({0, 0, 1}, 1.0);
  bad[4] = std::nan("");
  EXPECT_THROW(joint_reference_direction(bad), std::invalid_argument);
}

TEST(FemInterface, PlanarJointOnTheAxisTieHasOneTangentOnEveryPair)
{
  // Plane through the origin with normal ∝ (1, 1, 2): |n_x| = |n_y| ties for the old
  // least-aligned-axis rule, which then picks x or y by round-off. The joint's strike is
  // e_z × m = (-1, 1, 0)/√2 (m = (1, 1, 2)/√6), in the plane: t1 must equal it on every pair.
  const Vec3 m{1.0 / std::sqrt(6.0), 1.0 / std::sqrt(6.0), 2.0 / std::sqrt(6.0)};
  const Vec3 e1{-1.0 / std::sqrt(2.0), 1.0 / std::sqrt(2.0), 0.0}, e2 = cross3(m, e1);
  auto x = [&](double s, double t)
  {
    // slightly irregular in-plane grid, so that the facets' round-off differs
    const double ss = 1.7 * s + 0.05 * std::sin(7.0 * t), tt = 1.3 * t + 0.04 * std::cos(5.0 * s);
    return Vec3{ss * e1[0] + tt * e2[0], ss * e1[1] + tt * e2[1], ss * e1[2] + tt * e2[2]};
  };
  const SurfaceJoint joint(6, x, [&](const Vec3&) { return Vec3{-m[0], -m[1], -m[2]}; });
  const double ks = 4e9;
  auto a = joint.make({bb_law(), ShearModel::constant, ks});
  std::set<int> old_choice;
  const Vec3 t1_expected = e1, t2_expected = cross3(m, e1);
  for (std::int32_t p = 0; p < a.num_pairs(); ++p)
  {
    const LocalFrame& f = a.frame(p);
    expect_orthonormal_right_handed(f, 3);
    old_choice.insert(least_aligned_axis(f.axes[0]));
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(f.axes[0][c], m[c], 1e-13) << "pair " << p;
      EXPECT_NEAR(f.axes[1][c], t1_expected[c], 1e-13) << "pair " << p;
      EXPECT_NEAR(f.axes[2][c], t2_expected[c], 1e-13) << "pair " << p;
    }
  }
  EXPECT_GT(old_choice.size(), 1u) << "the geometry no longer exercises the axis tie";

  // Uniform jump δ (closing 2e-4 along n plus a shear): the same shear traction on every
  // point, k_s (δ·t1, δ·t2).
  const Vec3 slide{3e-5, -1e-5, 4e-5};
  Vec3 delta{};
  for (int c = 0; c < 3; ++c)
    delta[c] = -2e-4 * m[c] + slide[c];
  std::vector<double> u(18 * a.num_pairs(), 0.0), r(u.size(), 0.0);
  for (std::int32_t p = 0; p < a.num_pairs(); ++p)
    for (int node = 3; node < 6; ++node)
      for (int c = 0; c < 3; ++c)
        u[18 * p + 3 * node + c] = delta[c];
  ASSERT_TRUE(a.assemble_residual(u, r));
  const double tau1 = ks * dot3(delta, t1_expected), tau2 = ks * dot3(delta, t2_expected);
  ASSERT_GT(std::abs(tau1), 1e4);
  ASSERT_GT(std::abs(tau2), 1e4);
  const auto& tau = a.shear_traction();
  for (std::size_t k = 0; k < tau.size() / 2; ++k)
  {
    EXPECT_NEAR(tau[2 * k], tau1, 1e-9 * std::abs(tau1)) << "point " << k;
    EXPECT_NEAR(tau[2 * k + 1], tau2, 1e-9 * std::abs(tau2)) << "point " << k;
  }
}

TEST(FemInterface, CurvedJointHasContinuousTangents)
{
  // Doubly curved surface z = 0.2 s² + 0.1 s t + 0.15 t² (x = s, y = t), minus side below:
  // neighbouring facets turn their normals by O(h), and t1 must follow continuously (no
  // flips): |t1_p - t1_q| <= 2 |n_p - n_q| for every pair of facets, t1 ⟂ n, t1·r > 0.
  auto x = [](double s, double t) { return Vec3{s, t, 0.2 * s * s + 0.1 * s * t + 0.15 * t * t}; };
  const SurfaceJoint joint(5, x, [](const Vec3&) { return Vec3{0.0, 0.0, -1.0}; });
  auto a = joint.make({bb_law(), ShearModel::constant, 1e9});
  std::array<double, 9> M{};
  for (const auto& [tag, moment] : a.normal_moments())
    M = moment;
  const Vec3 r = joint_reference_direction(M);
  for (std::int32_t p = 0; p < a.num_pairs(); ++p)
  {
    const LocalFrame& fp = a.frame(p);
    expect_orthonormal_right_handed(fp, 3);
    EXPECT_GT(dot3(fp.axes[1], r), 0.9) << "pair " << p;
    for (std::int32_t q = 0; q < p; ++q)
    {
      const LocalFrame& fq = a.frame(q);
      Vec3 dt{}, dn{};
      for (int c = 0; c < 3; ++c)
      {
        dt[c] = fp.axes[1][c] - fq.axes[1][c];
        dn[c] = fp.axes[0][c] - fq.axes[0][c];
      }
      EXPECT_LE(std::sqrt(dot3(dt, dt)), 2.0 * std::sqrt(dot3(dn, dn)) + 1e-14)
          << "pairs " << p << ", " << q;
    }
  }
}

TEST(FemInterface, InitialJumpActsAsAPreClosure)
{
  // j0_n = -Δ0 at u = 0: every point sees Δ0, so R_plus,a = -σ(Δ0) (∫N_a dA) n with
  // ∫N_a dA = A/3 (P1 triangle), R_minus,a = +σ(Δ0) (A/3) n (Barton-Bandis closed form), and
  // the Jacobian is the one at Δ0: the plus-plus block of node a is
  // (A/3) (k(Δ0) n nᵀ + k_s (I - n nᵀ)), k(Δ0) = K_ni / (1 - Δ0/V_m)².
  const double Kni = 2e10, Vm = 1e-3, d0 = 3e-4, ks = 5e9, s1 = 1e-5, s2 = -2e-5;
  const double sigma = Kni * d0 / (1.0 - d0 / Vm), k0 = Kni / std::pow(1.0 - d0 / Vm, 2);
  PairFixture f(3);
  auto a = f.make({std::make_shared<constitutive::BartonBandis>(Kni, Vm), ShearModel::constant, ks});
  const int np = a.num_pairs() * a.num_points_per_pair();
  std::vector<double> j0;
  for (int k = 0; k < np; ++k)
    j0.insert(j0.end(), {-d0, s1, s2});
  a.set_initial_jump(j0);
  EXPECT_EQ(a.initial_jump(), j0);
  std::vector<double> u(18, 0.0), r(18, 0.0), K(18 * 18);
  ASSERT_TRUE(a.assemble_residual(u, r));
  const LocalFrame& fr = a.frame(0);
  const auto& n = fr.axes[0];
  const double A3 = fr.measure / 3.0;
  for (int node = 0; node < 3; ++node)
    for (int c = 0; c < 3; ++c)
    {
      // T = Qᵀ t_local, t_local = (-σ, k_s s1, k_s s2)
      const double T = -sigma * n[c] + ks * (s1 * fr.axes[1][c] + s2 * fr.axes[2][c]);
      EXPECT_NEAR(r[3 * (3 + node) + c], A3 * T, 1e-10 * sigma * A3);
      EXPECT_NEAR(r[3 * node + c], -A3 * T, 1e-10 * sigma * A3);
    }
  for (double d : a.closure())
    EXPECT_DOUBLE_EQ(d, d0);
  a.pair_matrix(0, u, K);
  for (int node = 0; node < 3; ++node)
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d)
      {
        const double want = A3 * (k0 * n[c] * n[d] + ks * ((c == d) - n[c] * n[d]));
        const int i = 3 * (3 + node) + c, j = 3 * (3 + node) + d;
        EXPECT_NEAR(K[i * 18 + j], want, 1e-10 * k0 * A3) << "node " << node << " (" << c << ", " << d << ")";
      }
  // The step limiter sees the pre-closure: Δ0 / V_m at u = 0.
  EXPECT_NEAR(a.maximum_closure_ratio(u), d0 / Vm, 1e-15);

  auto wrong = j0;
  wrong.pop_back();
  EXPECT_THROW(a.set_initial_jump(wrong), std::invalid_argument);
  auto nan = j0;
  nan[4] = std::nan("");
  try
  {
    a.set_initial_jump(nan);
    FAIL() << "expected std::invalid_argument";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("point 1, component 1"), std::string::npos) << e.what();
  }
}

namespace
{
/// Linear law σ = k Δ that counts its evaluations (calls from any thread of this test only).
class CountingLaw : public constitutive::ClosureLaw
{
public:
  explicit CountingLaw(double k) : _k(k) {}
  std::string name() const override { return "counting"; }
  std::vector<constitutive::Parameter> parameters() const override { return {{"k", _k, "Pa/m"}}; }
  mutable std::size_t calls = 0;

protected:
  constitutive::ClosureResponse evaluate_contact(double closure) const override
  {
    ++calls;
    constitutive::ClosureResponse r;
    r.normal_stress = _k * closure;
    r.normal_stiffness = _k;
    r.status = constitutive::Status::contact;
    return r;
  }

private:
  double _k;
};
} // namespace

TEST(FemInterface, JacobianAtTheResidualsDisplacementReusesTheLawEvaluations)
{
  for (int g : {2, 3})
  {
    PairFixture f(g);
    auto law = std::make_shared<CountingLaw>(1e10);
    auto a = f.make({law, ShearModel::constant, 1e9});
    const std::size_t points = a.num_pairs() * a.num_points_per_pair();
    const auto u = closing_displacement(a, 2e-4, 4);
    std::vector<double> r(u.size(), 0.0), K(a.pair_size() * a.pair_size());
    ASSERT_TRUE(a.assemble_residual(u, r));
    ASSERT_EQ(law->calls, points) << "one law evaluation per point in the residual";
    EXPECT_EQ(a.num_law_evaluations(), points);
    a.pair_matrix(0, u, K);
    EXPECT_EQ(law->calls, points) << "the Jacobian at the same u re-evaluated the law";
    const auto K_cached = K;

    auto u2 = u;
    for (auto& x : u2)
      x *= 1.001;
    a.pair_matrix(0, u2, K);
    EXPECT_EQ(law->calls, 2 * points) << "a different u must re-evaluate every point";
    // After a commit (or revert) the cached responses belong to an outdated converged state.
    a.commit_state();
    a.pair_matrix(0, u, K);
    EXPECT_EQ(law->calls, 3 * points);
    EXPECT_EQ(K, K_cached); // the elastic law: same matrix whether cached or re-evaluated
    EXPECT_EQ(a.num_law_evaluations(), 3 * points);
  }
}

TEST(FemInterface, PointStatesStartAtZeroAndFollowCommitAndRevert)
{
  // The elastic joint_response keeps the state: converged and trial stay zero through
  // residuals, commits and reverts (the slip law changes this; its tests pin the evolution).
  PairFixture f(3);
  auto a = f.make({bb_law(), ShearModel::constant, 1e9});
  const auto u = closing_displacement(a, 2e-4, 5);
  std::vector<double> r(u.size(), 0.0);
  ASSERT_EQ(a.trial_state().size(), std::size_t(a.num_pairs() * a.num_points_per_pair()));
  ASSERT_EQ(a.converged_state().size(), a.trial_state().size());
  a.assemble_residual(u, r);
  a.commit_state();
  a.revert_state();
  for (const auto& s : a.trial_state())
  {
    EXPECT_EQ(s.slip[0], 0.0);
    EXPECT_EQ(s.slip[1], 0.0);
    EXPECT_EQ(s.dilation, 0.0);
    EXPECT_EQ(s.accumulated_slip, 0.0);
  }
}
