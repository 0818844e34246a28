// SPDX-License-Identifier: MIT
// Benchmark of the closure laws: per model, the cost of one σ+k evaluation (median
// over repeats of a batch of 10^5 closures, 10^4 for laws above 10 µs a point) and, for the models that integrate over the
// summit heights, the error of the production integrator against an independent
// long-double reference (tanh-sinh quadrature, exact cubic root; tests/cpp/gw_reference.hpp)
// at three quadrature tolerances.
//
// Usage: bench_closure_laws [report.md]   (prints the table; writes it to the report too)
#include <rockjoint/constitutive/barton_bandis.hpp>
#include <rockjoint/constitutive/elasticity.hpp>
#include <rockjoint/constitutive/empirical_laws.hpp>
#include <rockjoint/constitutive/greenwood_williamson.hpp>
#include <rockjoint/constitutive/tang_jiao.hpp>
#include <rockjoint/constitutive/tang_substrate.hpp>

#include "../tests/cpp/gw_reference.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace rockjoint::constitutive;
namespace ref = rockjoint::testing;

namespace
{
// Theory §7 example joint (granite-like): E 50 GPa, ν 0.25, η 0.3 mm⁻², β 2.5 mm, σ_s 0.05 mm.
const AsperityParameters joint{composite_modulus(50e9, 0.25), 0.3e6, 2.5e-3, 0.05e-3};
const double base_radius = 1e-3; // r0 [m]
const double kappa = substrate::centre_deflection;
const double d0 = 3.5 * joint.summit_height_std; // reference separation [m]
const double max_stress = 30e6;                  // closure range: up to 30 MPa

/// Median ns per point of law.evaluate over `closure` (batch), `repeats` runs.
double ns_per_point(const ClosureLaw& law, const std::vector<double>& closure, int repeats = 7)
{
  std::vector<double> s(closure.size()), k(closure.size());
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r)
  {
    const auto t0 = std::chrono::steady_clock::now();
    law.evaluate(closure, s, k);
    const auto t1 = std::chrono::steady_clock::now();
    times.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count()
                    / closure.size());
  }
  std::nth_element(times.begin(), times.begin() + repeats / 2, times.end());
  return times[repeats / 2];
}

/// Uniform random closures on (0, top).
std::vector<double> random_closures(double top, std::size_t n)
{
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> d(n);
  for (auto& x : d)
    x = top * (1e-6 + (1.0 - 1e-6) * u(rng));
  return d;
}

/// Reference (σ_total, k, A/A0, dA/dΔ) of the Gaussian population at separation d, for the
/// substrate coefficient c = κ_s √β / r0 (c = 0: GW), by long-double tanh-sinh after
/// s = h + u², with g from an exact long-double cubic root.
struct Reference
{
  long double stress, stiffness, area, area_rate;
};
Reference reference_population(double d, double c)
{
  const long double ss = joint.summit_height_std, h = d / ss;
  const long double top = std::sqrt(std::max(h, 0.0L) + 16.0L - h); // φ falls by e^{-128}
  auto g_of = [&](long double u, long double& dg)
  {
    const long double w = u * u * ss;
    const long double t = c == 0.0 ? std::sqrt(w) : ref::cubic_root_newton(w, c);
    dg = 1.0L / (1.0L + 1.5L * c * t); // dg/dw
    return t * t;
  };
  auto integral = [&](auto&& f)
  { return ref::tanh_sinh([&](long double u) { return 2.0L * u * f(u) * ref::phi_ld(h + u * u); }, 0.0L, top); };
  const long double E = joint.composite_modulus, eta = joint.summit_density,
                    beta = joint.summit_radius;
  Reference r;
  r.stress = (4.0L / 3.0L) * E * eta * std::sqrt(beta) * integral([&](long double u) {
               long double dg; const long double g = g_of(u, dg); return g * std::sqrt(g); });
  r.stiffness = 2.0L * E * eta * std::sqrt(beta) * integral([&](long double u) {
                  long double dg; const long double g = g_of(u, dg); return std::sqrt(g) * dg; });
  r.area = std::numbers::pi_v<long double> * eta * beta * integral([&](long double u) {
             long double dg; return g_of(u, dg); });
  r.area_rate = std::numbers::pi_v<long double> * eta * beta * integral([&](long double u) {
                  long double dg; g_of(u, dg); return dg; });
  return r;
}

/// Tang & Jiao I1 from a base state (theory §5): F = f3/Q(s), dF/dΔ by the chain rule.
std::pair<long double, long double> reference_tang_jiao(const Reference& base, long double seat)
{
  const long double pi = std::numbers::pi_v<long double>;
  const long double s = std::sqrt(base.area);
  const long double Q = (2.0L / pi) * (std::acos(s) + s * std::sqrt(1.0L - s * s));
  const long double dQ = -(4.0L / pi) * s * s / std::sqrt(1.0L - s * s);
  const long double ds = base.area_rate / (2.0L * s);
  const long double f3 = base.stress - seat;
  return {f3 / Q, base.stiffness / Q - f3 * dQ * ds / (Q * Q)};
}

struct Row
{
  std::string model, setting;
  double ns;
  double stress_error = -1, stiffness_error = -1; // max relative; -1: no reference
  std::size_t batch = 0;
};

/// Max relative errors of σ and k against a reference functor over log-spaced closures.
template <typename RefFn>
std::pair<double, double> max_errors(const ClosureLaw& law, double top, RefFn&& reference)
{
  double es = 0, ek = 0;
  for (int i = 0; i < 40; ++i)
  {
    const double x = top * std::pow(10.0, -4.0 + 4.0 * i / 39.0);
    const auto r = law.evaluate(x);
    const auto [s, k] = reference(x);
    es = std::max(es, double(std::fabs((r.normal_stress - s) / s)));
    ek = std::max(ek, double(std::fabs((r.normal_stiffness - k) / k)));
  }
  return {es, ek};
}

std::string sci(double x)
{
  if (x < 0)
    return "n/a";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1e", x);
  return buf;
}
} // namespace

int main(int argc, char** argv)
{
  const std::size_t n = 100000;
  std::vector<Row> rows;
  auto add = [&](const std::string& model, const std::string& setting, const ClosureLaw& law,
                 double es = -1, double ek = -1)
  {
    const double top = std::min(law.closure_at_stress(max_stress),
                                0.95 * law.maximum_closure());
    // Batch of 1e5, or 1e4 (3 repeats) for laws slower than 10 µs a point, so the whole
    // benchmark runs in minutes; the per-point cost does not depend on the batch size.
    const double probe = ns_per_point(law, random_closures(top, 200), 1);
    const bool slow = probe > 1e4;
    rows.push_back({model, setting,
                    ns_per_point(law, random_closures(top, slow ? n / 10 : n), slow ? 3 : 7),
                    es, ek, slow ? n / 10 : n});
    std::fprintf(stderr, "  measured %s (%s)\n", model.c_str(), setting.c_str());
  };

  add("barton_bandis", "K_ni 10 MPa/mm, V_m 0.3 mm", BartonBandis(10e9, 0.3e-3));
  add("logarithmic", "B 0.05 mm, σ0 0.1 MPa", LogarithmicLaw(0.05e-3, 0.1e6));
  add("exponential", "V_m 0.2 mm, σ_c 5 MPa", ExponentialLaw(0.2e-3, 5e6));
  add("greenwood_williamson", "exponential heights (closed form)",
      GreenwoodWilliamson(joint, HeightDistribution::exponential));
  {
    // An empirical list of 2000 Gaussian summits over the area that gives the same η.
    std::mt19937_64 rng(7);
    std::normal_distribution<double> z(0.0, joint.summit_height_std);
    std::vector<double> h(2000), r(2000, joint.summit_radius);
    for (auto& x : h)
      x = z(rng);
    add("greenwood_williamson", "empirical list, 2000 summits",
        GreenwoodWilliamson(joint.composite_modulus,
                            EmpiricalSummits(h, r, 2000 / joint.summit_density)));
  }

  const double c = kappa * std::sqrt(joint.summit_radius) / base_radius;
  const auto seat = SeatingReference::at_separation(d0);
  const Reference gw0 = reference_population(d0, 0.0), tang0 = reference_population(d0, c);
  for (double tol : {1e-4, 1e-7, 1e-10})
  {
    const std::string setting = "Gaussian, quadrature tol " + sci(tol);
    GreenwoodWilliamson gw(joint, HeightDistribution::gaussian, seat, tol);
    const double top_gw = gw.closure_at_stress(max_stress);
    auto [es, ek] = max_errors(gw, top_gw, [&](double x) {
      const Reference r = reference_population(d0 - x, 0.0);
      return std::pair<double, double>(r.stress - gw0.stress, r.stiffness); });
    add("greenwood_williamson", setting, gw, es, ek);

    auto tang = std::make_shared<TangSubstrate>(
        joint, HeightDistribution::gaussian, SubstrateParameters{kappa, base_radius}, seat, tol);
    const double top_t = tang->closure_at_stress(max_stress);
    std::tie(es, ek) = max_errors(*tang, top_t, [&](double x) {
      const Reference r = reference_population(d0 - x, c);
      return std::pair<double, double>(r.stress - tang0.stress, r.stiffness); });
    add("tang_substrate", setting + ", κ_s 8/(3π), r0 1 mm", *tang, es, ek);

    TangJiao tj(std::static_pointer_cast<const AsperityLaw>(tang));
    const double top_tj = tj.closure_at_stress(max_stress);
    std::tie(es, ek) = max_errors(tj, top_tj, [&](double x) {
      const auto [F, k] = reference_tang_jiao(reference_population(d0 - x, c), tang0.stress);
      return std::pair<double, double>(F, k); });
    add("tang_jiao I1 over tang", setting, tj, es, ek);

    TangJiaoOptions i2;
    i2.variant = TangJiaoVariant::kinematic;
    TangJiao tj2(std::static_pointer_cast<const AsperityLaw>(tang), i2);
    add("tang_jiao I2 over tang", setting, tj2);
  }

  std::ostringstream table;
  table << "| model | setting | ns per σ+k (median) | batch | max rel. error σ | max rel. "
           "error k |\n|---|---|---:|---:|---:|---:|\n";
  for (const auto& r : rows)
  {
    char ns[32];
    std::snprintf(ns, sizeof ns, "%.0f", r.ns);
    table << "| " << r.model << " | " << r.setting << " | " << ns << " | " << r.batch << " | "
          << sci(r.stress_error) << " | " << sci(r.stiffness_error) << " |\n";
  }
  std::printf("%s", table.str().c_str());
  if (argc > 1)
  {
    std::ofstream out(argv[1]);
    out << "# Closure-law benchmark\n\nJoint of theory §7 (E 50 GPa, ν 0.25, η 0.3 mm⁻², β 2.5 mm, "
           "σ_s 0.05 mm, d0 = 3.5 σ_s), closures uniform on (0, Δ(30 MPa)). Errors: max over 40 "
           "log-spaced closures in [1e-4, 1] Δ(30 MPa) against a long-double tanh-sinh reference "
           "(tests/cpp/gw_reference.hpp), independent of the production integrator.\n\n"
        << table.str();
  }
  return 0;
}
