// SPDX-License-Identifier: MIT
// Uses the installed headers and library: σ of a Barton-Bandis joint at half its V_m equals K_ni V_m.
#include <rockjoint/constitutive/barton_bandis.hpp>

#include <cmath>
#include <cstdio>

int main()
{
  rockjoint::constitutive::BartonBandis law(20e9, 0.3e-3);
  const double sigma = law.normal_stress(0.15e-3);
  const double expected = 20e9 * 0.3e-3; // K_ni Δ/(1 - 1/2) with Δ = V_m/2
  std::printf("downstream: sigma = %.6g Pa (expected %.6g)\n", sigma, expected);
  return std::abs(sigma - expected) <= 1e-9 * expected ? 0 : 1;
}
