// SPDX-License-Identifier: MIT
// One summit is a Hertz contact (theory §1): an empirical list with a single summit must give
// hertz::load / A0, hertz::stiffness / A0 and hertz::contact_area / A0, for GW and for the
// Tang law with κ_s = 0; with a substrate, the load is Hertz's at the Hertz part g of the
// approach w = g + κ_s √β g^{3/2} / r0 (evaluated forwards from g: no root solving here).
#include <rockjoint/constitutive/greenwood_williamson.hpp>
#include <rockjoint/constitutive/hertz.hpp>
#include <rockjoint/constitutive/tang_substrate.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace rockjoint::constitutive;

namespace
{
constexpr double E = 26.7e9, R = 2.5e-3, A0 = 4e-6; // E* [Pa], radius [m], area [m²]
constexpr double ulp4 = 4.5e-16;                    // "exact to rounding": a few ulp
} // namespace

TEST(Hertz, SingleSummitGwIsHertzPerUnitArea)
{
  GreenwoodWilliamson law(E, EmpiricalSummits({0.0}, {R}, A0));
  EXPECT_EQ(law.reference_separation(), 0.0);
  EXPECT_EQ(law.seating_stress(), 0.0);
  for (double w : {1e-15, 1e-12, 1e-9, 3.3e-7, 1e-5, 1e-3, 1.0})
  {
    const auto r = law.evaluate(w);
    const double load = hertz::load(E, R, w) / A0;
    EXPECT_NEAR(r.normal_stress, load, ulp4 * load) << "closure " << w;
    const double k = hertz::stiffness(E, R, w) / A0;
    EXPECT_NEAR(r.normal_stiffness, k, ulp4 * k) << w;
    const double area = hertz::contact_area(R, w) / A0;
    EXPECT_NEAR(r.contact_area_ratio, area, ulp4 * area) << w;
    EXPECT_NEAR(r.contact_area_rate, std::numbers::pi * R / A0, ulp4 * std::numbers::pi * R / A0);
  }
}

TEST(Hertz, SingleSummitTangWithoutSubstrateIsHertz)
{
  TangSubstrate law(E, EmpiricalSummits({1e-4}, {R}, A0), {0.0, std::nullopt});
  EXPECT_EQ(law.reference_separation(), 1e-4); // first contact at the summit
  for (double w : {1e-12, 1e-6, 1e-3})
  {
    const double load = hertz::load(E, R, w) / A0;
    EXPECT_NEAR(law.normal_stress(w), load, ulp4 * load) << w;
  }
}

TEST(Hertz, SingleSummitOnSubstrateCarriesHertzLoadOfItsHertzPart)
{
  const double kappa = 8.0 / (3.0 * std::numbers::pi), r0 = 0.9e-3;
  TangSubstrate law(E, EmpiricalSummits({0.0}, {R}, A0), {kappa, r0});
  for (double g : {1e-14, 1e-10, 1e-7, 1e-5, 1e-3, 0.1})
  {
    const double w = g + kappa * std::sqrt(R) * g * std::sqrt(g) / r0; // theory §4
    const auto r = law.evaluate(w);
    const double load = hertz::load(E, R, g) / A0;
    EXPECT_NEAR(r.normal_stress, load, 1e-13 * load) << "g " << g;
    EXPECT_NEAR(r.contact_area_ratio, hertz::contact_area(R, g) / A0,
                1e-13 * hertz::contact_area(R, g) / A0);
    // k = dP/dg · dg/dw with dw/dg = 1 + 1.5 κ √R √g / r0.
    const double k
        = hertz::stiffness(E, R, g) / A0 / (1.0 + 1.5 * kappa * std::sqrt(R) * std::sqrt(g) / r0);
    EXPECT_NEAR(r.normal_stiffness, k, 1e-12 * k) << "g " << g;
  }
}

TEST(Hertz, SeatedSummitsSubtractTheirSeatingLoad)
{
  // Two summits, reference between them: the upper one is seated (w0 = 2 µm).
  const double z1 = 2e-6, z2 = -1e-6, R2 = 1e-3;
  GreenwoodWilliamson law(E, EmpiricalSummits({z2, z1}, {R2, R}, A0),
                          SeatingReference::at_separation(0.0));
  EXPECT_NEAR(law.seating_stress(), hertz::load(E, R, z1) / A0, 1e-15 * law.seating_stress());
  // Direct subtraction in the reference is accurate to ~ε w/Δ: fine from Δ = 1 nm.
  for (double d : {1e-9, 0.5e-6, 1e-6, 3e-6})
  {
    const double expected = (hertz::load(E, R, z1 + d) + hertz::load(E, R2, z2 + d)) / A0
                            - hertz::load(E, R, z1) / A0;
    EXPECT_NEAR(law.normal_stress(d), expected, 1e-10 * expected) << d;
  }
  // At Δ = 1e-15 m the law keeps full accuracy (no cancellation): σ = k(w1) Δ (1 + Δ/(4 w1)
  // + ...), second order 1.25e-10 relative.
  const double d = 1e-15, first_order = hertz::stiffness(E, R, z1) / A0 * d;
  EXPECT_NEAR(law.normal_stress(d), first_order, 1e-9 * first_order);
}
