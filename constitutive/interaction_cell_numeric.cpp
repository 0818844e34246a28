// SPDX-License-Identifier: MIT
#include "interaction_cell_numeric.hpp"
#include "interaction_cell.hpp"
#include "root_finding.hpp"
#include "validation.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_sf_ellint.h>

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace rockjoint::constitutive::interaction_cell
{

namespace
{
constexpr double pi = std::numbers::pi;

/// Gauss-Legendre nodes and weights on [0, 1].
struct GaussLegendre
{
  std::vector<double> x, w;
  explicit GaussLegendre(int n) : x(n), w(n)
  {
    std::unique_ptr<gsl_integration_glfixed_table, decltype(&gsl_integration_glfixed_table_free)>
        table(gsl_integration_glfixed_table_alloc(n), &gsl_integration_glfixed_table_free);
    if (!table)
      throw std::runtime_error("interaction_cell: cannot allocate a Gauss-Legendre table");
    for (int i = 0; i < n; ++i)
      gsl_integration_glfixed_point(0.0, 1.0, i, &x[i], &w[i], table.get());
  }
};

/// Root of a continuous f on [lo, hi] with f(lo) < 0 < f(hi) by Illinois steps (modified
/// regula falsi: exact in one step for the affine residuals of this cell; the shared root
/// finder keeps it inside the bracket). Stops at |f| <= ftol or a step within 1e-15 relative;
/// adds the evaluations to `iterations`.
template <class F>
double illinois_root(F&& f, double lo, double hi, double flo, double fhi, double ftol,
                     int& iterations)
{
  root_finding::Options options;
  options.secant = true;
  options.residual_tolerance = ftol;
  options.maximum_iterations = 200;
  const root_finding::Root root = root_finding::find_root(
      [&](double x) { return root_finding::Residual{f(x)}; }, lo, hi,
      std::numeric_limits<double>::quiet_NaN(), options, flo, fhi);
  iterations += root.evaluations;
  return root.x;
}

const GaussLegendre& rule(int n)
{
  // One immutable table per order, built on first use; thread_local, so no locking.
  thread_local std::vector<std::unique_ptr<GaussLegendre>> cache(513);
  if (!cache[n])
    cache[n] = std::make_unique<GaussLegendre>(n);
  return *cache[n];
}
} // namespace

NumericCell::NumericCell(double composite_modulus, double radius, double contact_radius,
                         double area_root, int quadrature_order)
    : _modulus(validation::positive("interaction_cell::NumericCell", "composite_modulus",
                                    composite_modulus, "Pa")),
      _radius(validation::positive("interaction_cell::NumericCell", "radius", radius, "m")),
      _a(validation::positive("interaction_cell::NumericCell", "contact_radius",
                              contact_radius, "m")),
      _s(validation::in_range("interaction_cell::NumericCell", "area_root", area_root, "",
                              0.0, 1.0)),
      _b(contact_radius / area_root),
      _order(static_cast<int>(validation::in_range("interaction_cell::NumericCell",
                                                   "quadrature_order", quadrature_order, "",
                                                   4, 512, true)))
{
  gsl_set_error_handler_off();
  const GaussLegendre& gl = rule(_order);

  // Influence coefficients of a unit p̄ (the cell is linear in p̄ at fixed a).
  _g_edge = interaction_g(_a);
  double integral = 0.0;
  for (int i = 0; i < _order; ++i)
    integral += gl.w[i] * (_g_edge - interaction_g(_a * gl.x[i]));
  _load_rate = 2.0 * _modulus * _a * integral;

  NumericSolution& sol = _solution;
  // Hertz part 2E* ∫_0^a (a² - x²)/R dx by the same rule (exact for polynomials).
  double hertz = 0.0;
  for (int i = 0; i < _order; ++i)
    hertz += gl.w[i] * (_a * _a - _a * gl.x[i] * _a * gl.x[i]) / _radius;
  sol.hertz_load = 2.0 * _modulus * _a * hertz;

  const double hertz_approach = _a * _a / _radius;
  const double hertz_mean_pressure = 4.0 * _modulus * _a / (3.0 * pi * _radius);

  // Step 1: for a trial δ_loc, bracket p̄ between 0 (tensile fringe: edge < 0 when
  // δ_loc < a²/R) and a value with an infinite fringe pressure (edge > 0), then root-find.
  auto fringe_pressure = [&](double approach)
  {
    double lo = 0.0, hi = hertz_mean_pressure;
    double flo = edge_coefficient(approach, lo), fhi = edge_coefficient(approach, hi);
    for (int k = 0; fhi <= 0.0 && k < 200; ++k)
    {
      lo = hi;
      flo = fhi;
      hi *= 4.0;
      fhi = edge_coefficient(approach, hi);
    }
    if (flo >= 0.0)
      return lo;
    return illinois_root([&](double p) { return edge_coefficient(approach, p); }, lo, hi, flo,
                         fhi, 1e-15 * hertz_approach, sol.inner_iterations);
  };

  // Step 2: self-consistency p̄ π b² = P (Eq. (3)) by a bracketed root find on δ_loc:
  // at δ_loc = a²/R the fringe p̄ is 0 (residual -P_H < 0); lowering δ_loc raises p̄ until
  // p̄ π b² exceeds P = P_H + p̄ dP/dp̄ (dP/dp̄ = (1-Q) π b² < π b²).
  auto residual = [&](double approach)
  {
    const double p = fringe_pressure(approach);
    return p * pi * _b * _b - load(p);
  };
  double hi = hertz_approach, fhi = -sol.hertz_load;
  double step = 1e-6 * hertz_approach, lo = hi - step, flo = residual(lo);
  for (int k = 0; flo <= 0.0 && k < 200; ++k)
  {
    hi = lo;
    fhi = flo;
    step *= 4.0;
    lo = hertz_approach - step;
    flo = residual(lo);
  }
  // residual(lo) > 0 > residual(hi): swap orientation for the root finder (f(lo) < 0).
  const double approach = illinois_root([&](double d) { return -residual(d); }, lo, hi, -flo,
                                        -fhi, 1e-14 * sol.hertz_load, sol.outer_iterations);
  sol.local_approach = approach;
  sol.mean_pressure = fringe_pressure(approach);
  sol.load = load(sol.mean_pressure);
  sol.edge_coefficient = edge_coefficient(approach, sol.mean_pressure);
  sol.converged = std::isfinite(sol.mean_pressure)
                  && std::abs(sol.mean_pressure * pi * _b * _b - sol.load)
                         <= 1e-12 * sol.load;
}

double NumericCell::interaction_g(double x) const
{
  // G2(x) = x ∫_0^{π/2} h(x sin φ) dφ with the profile slope of -u2 per unit p̄,
  // h(r) = -du2/dr / p̄ = (4/(πE*)) k D(k), k = r/b, D = (K-E)/k² (stable at small k).
  const GaussLegendre& gl = rule(_order);
  double sum = 0.0;
  for (int i = 0; i < _order; ++i)
  {
    const double phi = 0.5 * pi * gl.x[i];
    const double k = x * std::sin(phi) / _b;
    sum += gl.w[i] * k * gsl_sf_ellint_Dcomp(k, GSL_PREC_DOUBLE);
  }
  return x * 0.5 * pi * sum * 4.0 / (pi * _modulus);
}

double NumericCell::interaction_g_rate_over_t(double t) const
{
  // G2'(t)/t = (4/(πE* b)) ∫_0^{π/2} sin φ E(k)/(1-k²) dφ, k = t sin φ / b
  // (d/dk [k D(k)] = E/(1-k²) - D, so the D terms cancel).
  const GaussLegendre& gl = rule(_order);
  double sum = 0.0;
  for (int i = 0; i < _order; ++i)
  {
    const double phi = 0.5 * pi * gl.x[i];
    const double sphi = std::sin(phi);
    const double k = t * sphi / _b;
    sum += gl.w[i] * sphi * gsl_sf_ellint_Ecomp(k, GSL_PREC_DOUBLE) / ((1.0 - k) * (1.0 + k));
  }
  return 0.5 * pi * sum * 4.0 / (pi * _modulus * _b);
}

double NumericCell::edge_coefficient(double local_approach, double mean_pressure) const
{
  // δ' = δ_loc + u2(0), u2(0) = 2p̄b/E* (Eq. (5) at the centre); G(a) = a²/R + p̄ G2(a).
  return local_approach + 2.0 * mean_pressure * _b / _modulus - _a * _a / _radius
         - mean_pressure * _g_edge;
}

double NumericCell::load(double mean_pressure) const
{
  return _solution.hertz_load + mean_pressure * _load_rate;
}

double NumericCell::pressure(double r) const
{
  r = std::abs(r);
  if (r >= _a)
    return 0.0;
  const double length = std::sqrt((_a - r) * (_a + r));
  const GaussLegendre& gl = rule(_order);
  double sum = 0.0;
  for (int i = 0; i < _order; ++i)
  {
    const double w = length * gl.x[i];
    sum += gl.w[i] * interaction_g_rate_over_t(std::sqrt(r * r + w * w));
  }
  // p = (E*/π) ∫_0^L G'(t)/t dw with G'(t)/t = 2/R + p̄ G2'(t)/t.
  return _modulus / pi * length * (2.0 / _radius + _solution.mean_pressure * sum);
}

double disk_displacement(const std::function<double(double)>& pressure, double contact_radius,
                         double composite_modulus, double r, double relative_tolerance)
{
  gsl_set_error_handler_off();
  struct Data
  {
    const std::function<double(double)>* p;
    double r;
  } data{&pressure, std::abs(r)};
  gsl_function integrand;
  integrand.params = &data;
  integrand.function = [](double rho, void* params) -> double
  {
    const auto* d = static_cast<const Data*>(params);
    const double p = (*d->p)(rho);
    if (d->r == 0.0)
      return 2.0 * pi * p;
    // ∫_0^{2π} dθ/√(ρ²+r²-2rρ cos θ) = 4K(k)/(ρ+r), k = 2√(ρr)/(ρ+r); K = R_F(0, 1-k², 1)
    // with 1-k² = ((ρ-r)/(ρ+r))² formed without cancellation.
    const double kc = (rho - d->r) / (rho + d->r);
    return p * rho * 4.0 * gsl_sf_ellint_RF(0.0, kc * kc, 1.0, GSL_PREC_DOUBLE)
           / (rho + d->r);
  };
  std::vector<double> points{0.0};
  if (data.r > 0.0 && data.r < contact_radius)
    points.push_back(data.r);
  points.push_back(contact_radius);
  const std::size_t limit = 2000;
  std::unique_ptr<gsl_integration_workspace, decltype(&gsl_integration_workspace_free)> ws(
      gsl_integration_workspace_alloc(limit), &gsl_integration_workspace_free);
  double result = 0.0, error = 0.0;
  const int status = gsl_integration_qagp(&integrand, points.data(), points.size(), 0.0,
                                          relative_tolerance, limit, ws.get(), &result, &error);
  if (status != GSL_SUCCESS)
    return std::numeric_limits<double>::quiet_NaN();
  return result / (pi * composite_modulus);
}

} // namespace rockjoint::constitutive::interaction_cell
