// SPDX-License-Identifier: MIT
// Speed against error of TabulatedLaw. For each source law available and each
// tolerance: knots, build time, table memory, ns per (σ, k) evaluation of the table (batch
// of random closures in [0, Δ_max], median of several runs), ns per direct evaluation of the
// source law measured in the same run, the speed-up, and the relative error of σ and k
// measured on 10^4 random points against the source. Prints CSV (one header line); the
// driver bench/bench_tabulation.py formats it and writes bench/results/.
//
// Times are the CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID), median of several
// runs: on a shared machine wall time mostly measures the other processes.
//
// Usage: bench_tabulation [tolerance ...]   (default 1e-2 ... 1e-8)
#include <rockjoint/constitutive/barton_bandis.hpp>
#include <rockjoint/constitutive/elasticity.hpp>
#include <rockjoint/constitutive/empirical_laws.hpp>
#include <rockjoint/constitutive/tabulated_law.hpp>
#include <rockjoint/constitutive/greenwood_williamson.hpp>
#include <rockjoint/constitutive/tang_jiao.hpp>
#include <rockjoint/constitutive/tang_substrate.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <numbers>
#include <random>
#include <ctime>
#include <string>
#include <vector>

using namespace rockjoint::constitutive;

namespace
{
struct Model
{
  std::string label;
  std::shared_ptr<const ClosureLaw> law;
  double maximum_stress; // [Pa]
};

std::vector<Model> models()
{
  std::vector<Model> m{
      {"barton_bandis", std::make_shared<BartonBandis>(20e9, 0.3e-3), 30e6},
      {"logarithmic", std::make_shared<LogarithmicLaw>(0.05e-3, 0.1e6), 30e6},
      {"exponential", std::make_shared<ExponentialLaw>(0.2e-3, 5e6), 30e6},
  };
  // docs/theory.md §7: E 50 GPa, ν 0.25, η 0.3 mm⁻², β 2.5 mm, σ_s 0.05 mm, Gaussian, κ_s 8/(3π),
  // r0 1 mm.
  const AsperityParameters p{composite_modulus(50e9, 0.25), 0.3e6, 2.5e-3, 0.05e-3};
  SubstrateParameters sub;
  sub.deflection_coefficient = 8.0 / (3.0 * std::numbers::pi);
  sub.base_radius = 1e-3;
  auto gw = std::make_shared<GreenwoodWilliamson>(p);
  auto ts = std::make_shared<TangSubstrate>(p, HeightDistribution::gaussian, sub);
  auto tj = std::make_shared<TangJiao>(std::static_pointer_cast<const AsperityLaw>(ts));
  m.push_back({"greenwood_williamson", gw, 30e6});
  m.push_back({"tang_substrate", ts, 30e6});
  m.push_back({"tang_jiao", tj, 30e6});
  return m;
}

double median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// CPU time of this thread [s].
double thread_seconds()
{
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/// Median thread CPU time [s] of `runs` calls of f.
double time_runs(int runs, const std::function<void()>& f)
{
  std::vector<double> t;
  for (int r = 0; r < runs; ++r)
  {
    const double start = thread_seconds();
    f();
    t.push_back(thread_seconds() - start);
  }
  return median(t);
}

std::vector<double> uniform_closures(double top, std::size_t n, unsigned seed)
{
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> u(0.0, top);
  std::vector<double> d(n);
  for (auto& x : d)
    x = u(gen);
  return d;
}
} // namespace

int main(int argc, char** argv)
{
  std::vector<double> tolerances;
  for (int i = 1; i < argc; ++i)
    tolerances.push_back(std::atof(argv[i]));
  if (tolerances.empty())
    tolerances = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8};

  std::printf("model,tolerance,knots,build_s,law_evaluations,memory_bytes,ns_table_batch,"
              "ns_table_point_via_base,ns_direct,speedup,checked_error_stress,"
              "checked_error_stiffness,measured_error_stress,measured_error_stiffness,"
              "maximum_closure_m,maximum_stress_pa\n");
  double checksum = 0.0;
  for (const Model& m : models())
  {
    const double dmax = m.law->closure_at_stress(m.maximum_stress);
    // Direct cost of the source law, measured once per model on n_direct points sized to
    // take ~0.3 s.
    std::size_t n_direct = 1000;
    {
      const auto d = uniform_closures(dmax, n_direct, 1);
      std::vector<double> s(n_direct), k(n_direct);
      const double t = time_runs(1, [&] { m.law->evaluate(d, s, k); });
      n_direct = std::clamp<std::size_t>(static_cast<std::size_t>(0.3 / std::max(t / n_direct, 1e-9)),
                                         1000, 1000000);
    }
    const auto dd = uniform_closures(dmax, n_direct, 2);
    std::vector<double> sd(n_direct), kd(n_direct);
    const double ns_direct
        = 1e9 * time_runs(3, [&] { m.law->evaluate(dd, sd, kd); }) / n_direct;
    checksum += sd[0];

    // Accuracy points: half uniform, half log-uniform over 12 decades.
    std::mt19937_64 gen(3);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    std::vector<double> acc(10000);
    for (std::size_t i = 0; i < acc.size(); ++i)
      acc[i] = i % 2 ? dmax * std::pow(10.0, -12.0 * u01(gen)) : dmax * std::max(u01(gen), 1e-16);
    std::vector<double> se(acc.size()), ke(acc.size());
    m.law->evaluate(acc, se, ke);

    for (double tol : tolerances)
    {
      TabulatedLaw::Options o;
      o.tolerance = tol;
      std::unique_ptr<TabulatedLaw> table;
      double build = 0.0;
      try
      {
        const double start = thread_seconds();
        table = std::make_unique<TabulatedLaw>(
            TabulatedLaw::up_to_stress(*m.law, m.maximum_stress, o));
        build = thread_seconds() - start;
      }
      catch (const std::exception& e)
      {
        std::fprintf(stderr, "%s at tolerance %g: %s\n", m.label.c_str(), tol, e.what());
        std::printf("%s,%g,FAILED,,,,,,,,,,,,,\n", m.label.c_str(), tol);
        std::fflush(stdout);
        continue;
      }
      const std::size_t n = 1000000;
      const auto d = uniform_closures(dmax, n, 4);
      std::vector<double> s(n), k(n);
      const double ns_batch = 1e9 * time_runs(7, [&] { table->evaluate(d, s, k); }) / n;
      checksum += s[n / 2];
      const ClosureLaw& base = *table;
      const double ns_base = 1e9 * time_runs(5, [&] {
                               double acc_s = 0.0;
                               for (std::size_t i = 0; i < n; ++i)
                               {
                                 const ClosureResponse r = base.evaluate(d[i]);
                                 acc_s += r.normal_stress + r.normal_stiffness;
                               }
                               checksum += acc_s;
                             })
                             / n;

      double err_s = 0.0, err_k = 0.0;
      for (std::size_t i = 0; i < acc.size(); ++i)
      {
        const ClosureResponse r = table->evaluate(acc[i]);
        err_s = std::max(err_s, std::abs(r.normal_stress / se[i] - 1.0));
        err_k = std::max(err_k, std::abs(r.normal_stiffness / ke[i] - 1.0));
      }
      std::printf("%s,%g,%zu,%.6g,%zu,%zu,%.4g,%.4g,%.6g,%.6g,%.3g,%.3g,%.3g,%.3g,%.17g,%.17g\n",
                  m.label.c_str(), tol, table->knot_count(), build, table->law_evaluations(),
                  table->memory_bytes(), ns_batch, ns_base, ns_direct, ns_direct / ns_batch,
                  table->table().checked_error_stress, table->table().checked_error_stiffness,
                  err_s, err_k, table->table_maximum_closure(), table->table_maximum_stress());
      std::fflush(stdout);
    }
  }
  std::fprintf(stderr, "checksum %g\n", checksum);
  return 0;
}
