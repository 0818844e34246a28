// SPDX-License-Identifier: MIT
// The self-consistent interaction cell of Tang & Jiao (2018), theory §5: closed form
// (interaction_cell.hpp) against independent quadratures written here, and the paper's
// iterative algorithm (interaction_cell_numeric.hpp) against the closed form.
#include <rockjoint/constitutive/interaction_cell.hpp>
#include <rockjoint/constitutive/interaction_cell_numeric.hpp>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_sf_ellint.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

using namespace rockjoint::constitutive::interaction_cell;

namespace
{
constexpr double pi = std::numbers::pi;

// A granite-like cell (theory §7): E* 26.7 GPa, R = β = 2.5 mm, σ_s = 0.05 mm.
constexpr double modulus = 26.7e9, radius = 2.5e-3, height_std = 0.05e-3;

/// 1 - Q(s) in long double from its definition (2/π)[arcsin s - s√(1-s²)]: the
/// cancellation costs ~1/s² of the 64-bit mantissa, fine for s >= 1e-2.
double interaction_fraction_long_double(double s)
{
  const long double x = s;
  return static_cast<double>((2.0L / std::numbers::pi_v<long double>)
                             * (std::asin(x) - x * std::sqrt(1.0L - x * x)));
}

/// ∫_lo^hi f by GSL QAGS to 1e-12 relative (independent of the code under test).
double integrate(const std::function<double(double)>& f, double lo, double hi)
{
  gsl_set_error_handler_off();
  gsl_function g;
  g.function = [](double x, void* p)
  { return (*static_cast<std::function<double(double)>*>(p))(x); };
  g.params = const_cast<std::function<double(double)>*>(&f);
  gsl_integration_workspace* ws = gsl_integration_workspace_alloc(1000);
  double result = 0.0, error = 0.0;
  const int status = gsl_integration_qags(&g, lo, hi, 0.0, 1e-12, 1000, ws, &result, &error);
  gsl_integration_workspace_free(ws);
  EXPECT_EQ(status, GSL_SUCCESS) << "reference quadrature failed";
  return result;
}

const double area_roots[] = {1e-3, 1e-2, 0.05, 0.1, 0.3, 0.5, 0.7, 0.9};
} // namespace

TEST(InteractionCell, LoadFractionEndpointsAndSmallAreaSeries)
{
  EXPECT_EQ(load_fraction(0.0), 1.0);
  EXPECT_NEAR(load_fraction(1.0), 0.0, 1e-16);
  EXPECT_EQ(interaction_fraction(0.0), 0.0);
  EXPECT_NEAR(interaction_fraction(1.0), 1.0, 1e-16);
  EXPECT_TRUE(std::isnan(load_fraction(-0.1)));
  EXPECT_TRUE(std::isnan(load_fraction(1.1)));
  // 1-Q = (4/π)[s³/3 + s⁵/10 + 3s⁷/56 + 5s⁹/144 + ...] (series of 2s²/√(1-s²) integrated).
  for (double s : {1e-8, 1e-5, 1e-3, 1e-2})
  {
    const double series = 4.0 / pi * (s * s * s / 3.0 + std::pow(s, 5) / 10.0
                                       + 3.0 * std::pow(s, 7) / 56.0
                                       + 5.0 * std::pow(s, 9) / 144.0);
    EXPECT_NEAR(interaction_fraction(s), series, 1e-14 * series) << "s = " << s;
    EXPECT_NEAR(interaction_fraction(s) / (4 * s * s * s / (3 * pi)), 1.0, s * s)
        << "1-Q ≈ 4s³/(3π) at s = " << s;
  }
  for (double s : {1e-2, 0.1, 0.3, 0.49, 0.5, 0.51, 0.8, 0.99, 0.999999})
  {
    const double ref = interaction_fraction_long_double(s);
    EXPECT_NEAR(interaction_fraction(s), ref, 1e-13 * ref) << "s = " << s;
    EXPECT_NEAR(load_fraction(s) + interaction_fraction(s), 1.0, 4.5e-16) << "s = " << s;
  }
  // Q near 1 keeps relative accuracy (Q(1-x) ≈ (4/π)√(2x)): long-double reference with
  // 1-s² = (1-s)(1+s) formed exactly.
  for (double x : {1e-4, 1e-10})
  {
    const long double s = 1.0 - x, c = std::sqrt((1.0L - s) * (1.0L + s));
    const double ref = static_cast<double>(2.0L / std::numbers::pi_v<long double>
                                           * (std::acos(s) + s * c));
    EXPECT_NEAR(load_fraction(1.0 - x), ref, 1e-12 * ref) << "1 - s = " << x;
    const double gap = static_cast<double>(1.0L - s); // 1 - s as stored, exact
    EXPECT_NEAR(ref, 4 / pi * std::sqrt(2 * gap), 2 * gap * ref);
  }
  // dQ/ds against central differences of Q.
  for (double s : {0.05, 0.3, 0.7, 0.95})
  {
    const double h = 1e-6;
    const double fd = (load_fraction(s + h) - load_fraction(s - h)) / (2 * h);
    EXPECT_NEAR(load_fraction_derivative(s), fd, 1e-8 * std::abs(fd)) << s;
  }
}

TEST(InteractionCell, EffectiveRadiusMatchesExponentialGwMeanPressure)
{
  // Eq. (1): Hertz mean pressure 4E*a/(3πR) = E* √(σ_s/(πR)).
  const double a = effective_contact_radius(radius, height_std);
  EXPECT_NEAR(a, 0.75 * std::sqrt(pi * radius * height_std), 1e-18);
  const Cell cell(modulus, radius, a, 0.1);
  const double gw = modulus * std::sqrt(height_std / (pi * radius));
  EXPECT_NEAR(cell.hertz_mean_pressure(), gw, 1e-13 * gw);
}

TEST(InteractionCell, PressureIsZeroAtTheFringeAndIntegratesToTheLoad)
{
  const double a = effective_contact_radius(radius, height_std);
  for (double s : area_roots)
  {
    SCOPED_TRACE("s = " + std::to_string(s));
    const Cell cell(modulus, radius, a, s);
    const double b = a / s;
    EXPECT_NEAR(cell.territory_radius(), b, 1e-15 * b);
    EXPECT_EQ(cell.pressure(a), 0.0);
    EXPECT_EQ(cell.pressure(1.5 * a), 0.0);
    EXPECT_GT(cell.pressure(a * (1 - 1e-9)), 0.0);

    // Load written out here (theory §5), long double for the small-s cancellation.
    const double pbar = cell.mean_pressure();
    const long double B = b, A = a;
    const double load_ref = static_cast<double>(
        4.0L / 3.0L * modulus * A * A * A / radius
        + 2.0L * pbar * (B * B * std::asin(A / B) - A * std::sqrt(B * B - A * A)));
    EXPECT_NEAR(cell.load(), load_ref, 1e-12 * load_ref);
    // Self-consistency, Eq. (3): p̄ π b² = P.
    EXPECT_NEAR(pbar * pi * b * b, cell.load(), 1e-13 * cell.load());
    // p̄ = (4E*a/(3πR)) s²/Q.
    const double q = 1.0 - interaction_fraction_long_double(std::max(s, 1e-2));
    if (s >= 1e-2)
      EXPECT_NEAR(pbar, 4 * modulus * a / (3 * pi * radius) * s * s / q, 1e-12 * pbar);

    // ∫_0^a p 2πr dr = P by an independent adaptive quadrature (substitute r = a sin θ to
    // remove the √ edge).
    const double integral = integrate(
        [&](double th)
        {
          const double r = a * std::sin(th);
          return cell.pressure(r) * 2 * pi * r * a * std::cos(th);
        },
        0.0, pi / 2);
    EXPECT_NEAR(integral, cell.load(), 1e-10 * cell.load());
  }
}

TEST(InteractionCell, LocalApproachSolvesTheContactCondition)
{
  // f1(r)/(πE*) - f2(r)/(πE*) = δ_loc - r²/(2R) on r <= a: at r = 0 the Boussinesq integral of
  // Eq. (4) is (2/E*) ∫_0^a p dρ and Eq. (5) gives 2p̄b/E*, so ∫_0^a p dρ = E*δ_loc/2 + p̄b.
  const double a = effective_contact_radius(radius, height_std);
  for (double s : area_roots)
  {
    SCOPED_TRACE("s = " + std::to_string(s));
    const Cell cell(modulus, radius, a, s);
    const double b = a / s, pbar = cell.mean_pressure();
    const double lhs = integrate(
        [&](double th) { return cell.pressure(a * std::sin(th)) * a * std::cos(th); }, 0.0,
        pi / 2);
    const double rhs = modulus * cell.local_approach() / 2 + pbar * b;
    EXPECT_NEAR(lhs, rhs, 1e-10 * rhs);
    // u2(0) = 2p̄b/E*: Eq. (5) at the centre.
    EXPECT_NEAR(cell.territory_displacement(0.0), 2 * pbar * b / modulus,
                1e-14 * 2 * pbar * b / modulus);
    // δ_loc = a²/R - (2p̄/E*)√(b²-a²), and the I2 shift is its interaction part.
    const double shift = 2 * pbar / modulus * std::sqrt(b * b - a * a);
    EXPECT_NEAR(cell.closure_shift(), shift, 1e-12 * shift);
    EXPECT_NEAR(cell.local_approach(), a * a / radius - shift, 1e-12 * a * a / radius);
    // Off-centre: the full Boussinesq integral of Eq. (4) (adaptive, log singularity at
    // ρ = r) against δ_loc - r²/(2R) + u2(r).
    for (double x : {0.3, 0.7, 0.95})
    {
      const double r = x * a;
      const double u1 = disk_displacement([&](double rho) { return cell.pressure(rho); }, a,
                                          modulus, r, 1e-11);
      const double target = cell.local_approach() - r * r / (2 * radius)
                            + cell.territory_displacement(r);
      EXPECT_NEAR(u1, target, 1e-9 * std::abs(target)) << "r/a = " << x;
    }
  }
}

TEST(InteractionCell, TerritoryDisplacementOutsideTheDisk)
{
  // Far from the disk b the load p̄πb² acts like a point force: u → p̄ b²/(E* r).
  const double a = effective_contact_radius(radius, height_std);
  const Cell cell(modulus, radius, a, 0.3);
  const double b = cell.territory_radius(), r = 1e3 * b;
  const double far = cell.mean_pressure() * b * b / (modulus * r);
  EXPECT_NEAR(cell.territory_displacement(r), far, 1e-6 * far);
  // Continuous at r = b: u(b) = 4p̄b/(πE*).
  const double edge = 4 * cell.mean_pressure() * b / (pi * modulus);
  EXPECT_NEAR(cell.territory_displacement(b), edge, 1e-14 * edge);
  EXPECT_NEAR(cell.territory_displacement(b * (1 + 1e-12)), edge, 1e-9 * edge);
}

TEST(InteractionCellNumeric, PapersAlgorithmMatchesClosedFormTo1e6)
{
  const double a = effective_contact_radius(radius, height_std);
  for (double s : area_roots)
  {
    SCOPED_TRACE("s = " + std::to_string(s));
    const Cell exact(modulus, radius, a, s);
    const NumericCell numeric(modulus, radius, a, s, 32);
    const NumericSolution& sol = numeric.solution();
    EXPECT_TRUE(sol.converged);
    EXPECT_GE(sol.outer_iterations, 1);
    EXPECT_GE(sol.inner_iterations, 1);
    EXPECT_NEAR(sol.mean_pressure, exact.mean_pressure(), 1e-6 * exact.mean_pressure());
    EXPECT_NEAR(sol.load, exact.load(), 1e-6 * exact.load());
    EXPECT_NEAR(sol.local_approach, exact.local_approach(), 1e-6 * a * a / radius);
    // The interaction load alone (the part the algorithm actually has to find).
    const double pint = sol.load - sol.hertz_load;
    EXPECT_NEAR(pint, exact.interaction_load(), 1e-6 * exact.interaction_load());
    for (double x : {0.0, 0.2, 0.5, 0.8, 0.95, 0.999})
    {
      const double p = exact.pressure(x * a);
      EXPECT_NEAR(numeric.pressure(x * a), p, 1e-6 * p) << "r/a = " << x;
    }
    EXPECT_EQ(numeric.pressure(a), 0.0);
    EXPECT_NEAR(sol.edge_coefficient, 0.0, 1e-12 * a * a / radius);
  }
}

TEST(InteractionCellNumeric, NearTheValidityLimitWithMoreNodes)
{
  // s = 0.99 (the default cap of the law): E(k)/(1-k²) nears its pole at k = 1, so the rule
  // needs more nodes; 64 reach the closed form to 1e-12.
  const double a = effective_contact_radius(radius, height_std);
  const Cell exact(modulus, radius, a, 0.99);
  const NumericCell numeric(modulus, radius, a, 0.99, 64);
  EXPECT_NEAR(numeric.solution().mean_pressure, exact.mean_pressure(),
              1e-12 * exact.mean_pressure());
  EXPECT_NEAR(numeric.pressure(0.5 * a), exact.pressure(0.5 * a), 1e-10 * exact.pressure(0.5 * a));
}

TEST(InteractionCellNumeric, PapersContractionOnTheMeanPressureConverges)
{
  // The paper's self-consistency iteration p̄ ← P(p̄)/(π b²), with P(p̄) the load of the
  // numerically solved finite-fringe contact, contracts with factor 1-Q(s) to the same p̄.
  const double a = effective_contact_radius(radius, height_std);
  for (double s : {0.1, 0.5, 0.9})
  {
    const Cell exact(modulus, radius, a, s);
    const NumericCell numeric(modulus, radius, a, s, 32);
    const double b = a / s;
    double p = 0.0;
    int it = 0;
    for (; it < 1000; ++it)
    {
      const double next = numeric.load(p) / (pi * b * b);
      if (std::abs(next - p) <= 1e-15 * next)
        break;
      p = next;
    }
    EXPECT_LT(it, 1000);
    EXPECT_NEAR(p, exact.mean_pressure(), 1e-12 * exact.mean_pressure()) << "s = " << s;
    // The contraction factor is dP/dp̄ / (πb²) = 1 - Q(s).
    // (A large p̄ step keeps the Hertz part P_H from swamping the difference.)
    const double step = 1e8 * exact.mean_pressure();
    const double factor = (numeric.load(step) - numeric.load(0.0)) / (step * pi * b * b);
    EXPECT_NEAR(factor, interaction_fraction_long_double(s), 1e-12);
  }
}

TEST(InteractionCellNumeric, EdgeTermSignsAsInThePaper)
{
  // p̄ too large → positive edge coefficient (infinite fringe pressure), too small → negative
  // (tensile fringe), at the self-consistent local approach.
  const double a = effective_contact_radius(radius, height_std);
  const NumericCell cell(modulus, radius, a, 0.4, 24);
  const auto& sol = cell.solution();
  EXPECT_GT(cell.edge_coefficient(sol.local_approach, 1.1 * sol.mean_pressure), 0.0);
  EXPECT_LT(cell.edge_coefficient(sol.local_approach, 0.9 * sol.mean_pressure), 0.0);
}

TEST(InteractionCellNumeric, PressureSatisfiesEq4ContactCondition)
{
  // The numerical pressure put through the Boussinesq integral of Eq. (4).
  const double a = effective_contact_radius(radius, height_std);
  for (double s : {0.1, 0.7})
  {
    const Cell exact(modulus, radius, a, s);
    const NumericCell numeric(modulus, radius, a, s, 24);
    for (double x : {0.0, 0.5, 0.9})
    {
      const double r = x * a;
      const double u1 = disk_displacement([&](double rho) { return numeric.pressure(rho); }, a,
                                          modulus, r, 1e-9);
      const double target = numeric.solution().local_approach - r * r / (2 * radius)
                            + exact.territory_displacement(r);
      EXPECT_NEAR(u1, target, 1e-7 * std::abs(target)) << "s " << s << " r/a " << x;
    }
  }
}

TEST(InteractionCellNumeric, ErrorFallsWithQuadratureOrder)
{
  const double a = effective_contact_radius(radius, height_std);
  const double s = 0.9; // the hardest case: k = r/b up to 0.9, near E/(1-k²)'s pole
  const Cell exact(modulus, radius, a, s);
  double previous = std::numeric_limits<double>::infinity();
  for (int n : {4, 8, 16})
  {
    const NumericCell numeric(modulus, radius, a, s, n);
    const double e = std::abs(numeric.solution().mean_pressure - exact.mean_pressure())
                     / exact.mean_pressure();
    EXPECT_LT(e, previous) << "order " << n;
    previous = e;
  }
}

TEST(InteractionCell, RejectsBadParametersWithNamedErrors)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : {nan, inf, -1.0, 0.0})
  {
    EXPECT_THROW(Cell(bad, 1e-3, 1e-4, 0.1), std::invalid_argument);
    EXPECT_THROW(Cell(1e9, bad, 1e-4, 0.1), std::invalid_argument);
    EXPECT_THROW(Cell(1e9, 1e-3, bad, 0.1), std::invalid_argument);
    EXPECT_THROW(NumericCell(bad, 1e-3, 1e-4, 0.1), std::invalid_argument);
  }
  for (double bad : {nan, 0.0, 1.0, 1.5, -0.1})
  {
    EXPECT_THROW(Cell(1e9, 1e-3, 1e-4, bad), std::invalid_argument);
    EXPECT_THROW(NumericCell(1e9, 1e-3, 1e-4, bad), std::invalid_argument);
  }
  EXPECT_THROW(NumericCell(1e9, 1e-3, 1e-4, 0.1, 2), std::invalid_argument);
  try
  {
    Cell(1e9, 1e-3, 1e-4, 1.5);
    FAIL() << "no exception";
  }
  catch (const std::invalid_argument& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("area_root"), std::string::npos) << what;
    EXPECT_NE(what.find("1.5"), std::string::npos) << what;
  }
}
