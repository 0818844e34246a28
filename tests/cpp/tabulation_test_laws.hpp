// SPDX-License-Identifier: MIT
#pragma once
// The laws every tabulation test runs over: each closure law of the library with the stress
// range a scene would tabulate, plus a Hertzian-onset test law (σ ~ Δ^{3/2}, k(0+) = 0).
#include <rockjoint/constitutive/barton_bandis.hpp>
#include <rockjoint/constitutive/closure_law.hpp>
#include <rockjoint/constitutive/empirical_laws.hpp>
#include <rockjoint/constitutive/elasticity.hpp>
#include <rockjoint/constitutive/greenwood_williamson.hpp>
#include <rockjoint/constitutive/tang_jiao.hpp>
#include <rockjoint/constitutive/tang_substrate.hpp>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

namespace rockjoint::testing
{

/// σ = c Δ^{3/2} (1 + Δ/L): the GW-type first-contact behaviour (one Hertzian summit,
/// then stiffening), with k = c Δ^{1/2} (3/2 + (5/2) Δ/L).
class HertzianOnsetLaw : public constitutive::ClosureLaw
{
public:
  HertzianOnsetLaw(double coefficient, double length) : _c(coefficient), _l(length) {}
  std::string name() const override { return "hertzian_onset_test_law"; }
  std::vector<constitutive::Parameter> parameters() const override
  {
    return {{"coefficient", _c, "Pa/m^1.5"}, {"length", _l, "m"}};
  }

protected:
  constitutive::ClosureResponse evaluate_contact(double d) const override
  {
    const double r = std::sqrt(d);
    return {_c * d * r * (1 + d / _l), _c * r * (1.5 + 2.5 * d / _l), 0.0, 0.0,
            constitutive::Status::contact};
  }

private:
  double _c, _l;
};

struct LawCase
{
  std::string label;
  std::shared_ptr<constitutive::ClosureLaw> law;
  double maximum_stress; ///< σ_max [Pa] of the table
  /// Finest tolerance the source's own accuracy supports (a law evaluated by quadrature
  /// cannot be matched more closely than its quadrature error; the Gaussian GW-type laws
  /// here, at quadrature tolerance 1e-10, reach 1e-8).
  double finest_tolerance = 1e-8;
};

inline std::vector<LawCase> library_laws()
{
  using namespace constitutive;
  std::vector<LawCase> cases{
      {"barton_bandis 20 MPa/mm, 0.3 mm", std::make_shared<BartonBandis>(20e9, 0.3e-3), 30e6},
      // K_ni V_m = 1 MPa: 30 MPa sits at Δ = 0.968 V_m, next to the pole.
      {"barton_bandis soft, near the pole", std::make_shared<BartonBandis>(5e9, 0.2e-3), 30e6},
      {"logarithmic", std::make_shared<LogarithmicLaw>(0.05e-3, 0.1e6), 30e6},
      {"exponential", std::make_shared<ExponentialLaw>(0.2e-3, 5e6), 30e6},
      {"hertzian onset", std::make_shared<HertzianOnsetLaw>(1e12, 0.05e-3), 30e6},
  };
  // Theory §7: E 50 GPa, ν 0.25, η 0.3 mm⁻², β 2.5 mm, σ_s 0.05 mm, κ_s 8/(3π), r0 1 mm.
  const AsperityParameters p{composite_modulus(50e9, 0.25), 0.3e6, 2.5e-3, 0.05e-3};
  SubstrateParameters sub;
  sub.deflection_coefficient = 8.0 / (3.0 * std::numbers::pi);
  sub.base_radius = 1e-3;
  auto ts = std::make_shared<TangSubstrate>(p, HeightDistribution::gaussian, sub);
  cases.push_back({"greenwood_williamson gaussian", std::make_shared<GreenwoodWilliamson>(p),
                   30e6});
  cases.push_back({"greenwood_williamson exponential (closed form)",
                   std::make_shared<GreenwoodWilliamson>(p, HeightDistribution::exponential),
                   30e6});
  cases.push_back({"tang_substrate gaussian", ts, 30e6});
  cases.push_back({"tang_jiao over tang_substrate",
                   std::make_shared<TangJiao>(std::static_pointer_cast<const AsperityLaw>(ts)),
                   30e6});
  return cases;
}

} // namespace rockjoint::testing
