// SPDX-License-Identifier: MIT
// Speed against error of the Tang & Jiao interaction cell: closed form (interaction_cell.hpp)
// versus the paper's iterative algorithm (interaction_cell_numeric.hpp) at several area roots
// s and quadrature orders n. For each (s, n): µs per solve (p̄, P, δ_loc) and µs per pressure
// evaluation p(r), both medians of repeated runs, root-finder iterations, and the relative
// errors of p̄, P and max_r |p_num - p| / p(0) against the closed form. Prints CSV (one
// header line); bench/bench_interaction_cell.py formats it and writes bench/results/.
//
// Usage: bench_interaction_cell [order ...]   (default 8 16 32 64)
#include <rockjoint/constitutive/interaction_cell.hpp>
#include <rockjoint/constitutive/interaction_cell_numeric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace rockjoint::constitutive::interaction_cell;
using clock_type = std::chrono::steady_clock;

namespace
{
/// Median over `runs` of the time per call [µs] of f, each run repeating it `reps` times.
template <class F>
double median_us(F&& f, int reps, int runs = 7)
{
  std::vector<double> t;
  for (int r = 0; r < runs; ++r)
  {
    const auto t0 = clock_type::now();
    for (int i = 0; i < reps; ++i)
      f();
    t.push_back(std::chrono::duration<double, std::micro>(clock_type::now() - t0).count() / reps);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

volatile double sink = 0.0; // keeps the optimiser from dropping timed work
} // namespace

int main(int argc, char** argv)
{
  std::vector<int> orders{8, 16, 32, 64};
  if (argc > 1)
  {
    orders.clear();
    for (int i = 1; i < argc; ++i)
      orders.push_back(std::atoi(argv[i]));
  }
  // Theory §7 rock: E* = 26.7 GPa, R = β = 2.5 mm, σ_s = 0.05 mm, a from Eq. (1).
  const double modulus = 50e9 / (2 * (1 - 0.0625)), radius = 2.5e-3;
  const double a = effective_contact_radius(radius, 0.05e-3);
  const std::vector<double> roots{1e-3, 1e-2, 0.1, 0.3, 0.5, 0.7, 0.9};
  std::vector<double> r(16);
  for (std::size_t i = 0; i < r.size(); ++i)
    r[i] = a * i / r.size();

  std::printf("area_root,order,closed_solve_us,closed_pressure_us,numeric_solve_us,"
              "numeric_pressure_us,outer_iterations,inner_iterations,err_mean_pressure,"
              "err_load,err_pressure\n");
  for (double s : roots)
  {
    const Cell exact(modulus, radius, a, s);
    const double closed_solve = median_us(
        [&]
        {
          const Cell c(modulus, radius, a, s);
          sink = sink + c.mean_pressure() + c.load() + c.local_approach();
        },
        20000);
    const double closed_pressure = median_us(
        [&]
        {
          for (double x : r)
            sink = sink + exact.pressure(x);
        },
        2000) / r.size();
    for (int n : orders)
    {
      const NumericCell num(modulus, radius, a, s, n);
      const auto& sol = num.solution();
      double err_p = 0.0;
      for (int i = 0; i <= 200; ++i)
      {
        const double x = a * i / 200.0;
        err_p = std::max(err_p, std::abs(num.pressure(x) - exact.pressure(x)));
      }
      err_p /= exact.pressure(0.0);
      const int reps = n <= 16 ? 200 : (n <= 32 ? 50 : 10);
      const double numeric_solve = median_us(
          [&]
          {
            const NumericCell c(modulus, radius, a, s, n);
            sink = sink + c.solution().mean_pressure;
          },
          reps, 5);
      const double numeric_pressure = median_us(
          [&]
          {
            for (double x : r)
              sink = sink + num.pressure(x);
          },
          std::max(1, reps / 4), 5) / r.size();
      std::printf("%g,%d,%.4g,%.4g,%.4g,%.4g,%d,%d,%.3e,%.3e,%.3e\n", s, n, closed_solve,
                  closed_pressure, numeric_solve, numeric_pressure, sol.outer_iterations,
                  sol.inner_iterations,
                  std::abs(sol.mean_pressure - exact.mean_pressure()) / exact.mean_pressure(),
                  std::abs(sol.load - exact.load()) / exact.load(), err_p);
    }
  }
  return 0;
}
