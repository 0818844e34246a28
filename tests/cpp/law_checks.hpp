// SPDX-License-Identifier: MIT
#pragma once
// Checks every closure law must pass: open branch exact, strictly increasing σ,
// k > 0 in contact, analytic k = central finite differences of σ, Δ(σ(Δ)) = Δ, batch =
// pointwise; and, for laws without a maximum closure, the same at extreme closures.
// Reference: the law's own σ only through finite differences and inversion.
#include <rockjoint/constitutive/closure_law.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace rockjoint::testing
{

/// Closures log-spaced over [top·1e-6, top].
inline std::vector<double> log_closures(double top, int n = 200)
{
  std::vector<double> d(n);
  for (int i = 0; i < n; ++i)
    d[i] = top * std::pow(10.0, -6.0 + 6.0 * i / (n - 1));
  return d;
}

/// Relative tolerance of the FD tangent check: central differences have O(h²) truncation
/// and O(eps/h) rounding error; h = 1e-4 Δ balances them for smooth laws.
/// `top` must lie below maximum_closure().
inline void check_law(const constitutive::ClosureLaw& law, double top,
                      double fd_tolerance = 1e-6, double inverse_tolerance = 1e-10)
{
  using constitutive::Status;
  // Open branch.
  for (double d : {0.0, -0.0, -1e-3, -1e300, -std::numeric_limits<double>::infinity()})
  {
    const auto r = law.evaluate(d);
    EXPECT_EQ(r.normal_stress, 0.0) << d;
    EXPECT_EQ(r.normal_stiffness, 0.0) << d;
    EXPECT_EQ(r.status, Status::open) << d;
  }
  EXPECT_EQ(law.evaluate(std::numeric_limits<double>::quiet_NaN()).status, Status::invalid_closure);

  const auto d = log_closures(top);
  double previous = 0.0;
  for (double x : d)
  {
    const auto r = law.evaluate(x);
    ASSERT_EQ(r.status, Status::contact) << "closure " << x;
    EXPECT_GT(r.normal_stress, previous) << "σ not strictly increasing at " << x;
    EXPECT_GT(r.normal_stiffness, 0.0) << x;
    previous = r.normal_stress;

    // Step small against Δ, against the distance to a finite maximum closure (a pole) and
    // against the law's own length scale σ/k (exponential-type growth).
    const double room = law.maximum_closure() - x;
    const double scale = std::min(x, r.normal_stress / r.normal_stiffness);
    const double h = 1e-4 * (std::isfinite(room) ? std::min(scale, room) : scale);
    const double fd = (law.normal_stress(x + h) - law.normal_stress(x - h)) / (2 * h);
    EXPECT_NEAR(r.normal_stiffness, fd, fd_tolerance * std::abs(fd))
        << "tangent vs central difference at closure " << x;

    if (r.normal_stress > 0.0)
    {
      const double back = law.closure_at_stress(r.normal_stress);
      EXPECT_NEAR(back, x, inverse_tolerance * x) << "Δ(σ(Δ)) at " << x;
    }
  }

  // Batch = pointwise.
  std::vector<double> s(d.size()), k(d.size()), a(d.size());
  std::vector<Status> st(d.size());
  law.evaluate(d, s, k, a, st);
  for (std::size_t i = 0; i < d.size(); ++i)
  {
    const auto r = law.evaluate(d[i]);
    EXPECT_EQ(s[i], r.normal_stress);
    EXPECT_EQ(k[i], r.normal_stiffness);
    EXPECT_EQ(a[i], r.contact_area_ratio);
    EXPECT_EQ(st[i], r.status);
  }
}

/// Extreme closures of a law with no maximum closure (1e-15 m to 1 m, twelve decades past
/// any roughness scale the callers use): every response in contact and finite, σ strictly
/// increasing, k > 0, Δ(σ(Δ)) = Δ to 1e-10 relative.
inline void check_extreme_closures(const constitutive::ClosureLaw& law)
{
  using constitutive::Status;
  double previous = 0.0;
  for (double d : {1e-15, 1e-13, 1e-11, 1e-9, 1e-7, 1e-5, 1e-3, 1e-1, 1.0})
  {
    const auto r = law.evaluate(d);
    ASSERT_EQ(r.status, Status::contact) << d;
    ASSERT_TRUE(std::isfinite(r.normal_stress) && std::isfinite(r.normal_stiffness)
                && std::isfinite(r.contact_area_ratio) && std::isfinite(r.contact_area_rate))
        << d;
    EXPECT_GT(r.normal_stress, previous) << d;
    EXPECT_GT(r.normal_stiffness, 0.0) << d;
    previous = r.normal_stress;
    EXPECT_NEAR(law.closure_at_stress(r.normal_stress), d, 1e-10 * d) << d;
  }
}

} // namespace rockjoint::testing
