// SPDX-License-Identifier: MIT
#pragma once
// Test helpers for the per-point joint behaviour: a linear closure law (closed-form return
// mappings) and a Coulomb joint on it.
#include <rockjoint/constitutive/closure_law.hpp>
#include <rockjoint/joint/joint_behaviour.hpp>

#include <memory>
#include <numbers>
#include <string>
#include <vector>

namespace rockjoint::test
{
constexpr double deg = std::numbers::pi / 180.0;

/// σ = k_n Δ: a linear closure law, so that the return mapping has closed forms.
class LinearLaw : public constitutive::ClosureLaw
{
public:
  explicit LinearLaw(double stiffness) : _k(stiffness) {}
  std::string name() const override { return "linear_test_law"; }
  std::vector<constitutive::Parameter> parameters() const override
  {
    return {{"stiffness", _k, "Pa/m"}};
  }

protected:
  constitutive::ClosureResponse evaluate_contact(double d) const override
  {
    return {_k * d, _k, 0.0, 0.0, constitutive::Status::contact};
  }

private:
  double _k;
};

constexpr double kn = 1e10, ks = 4e9; // [Pa/m]

inline joint::JointBehaviour coulomb(double phi, double c, double psi = 0.0,
                              std::shared_ptr<const constitutive::ClosureLaw> law = nullptr)
{
  joint::JointBehaviour b;
  b.law = law ? law : std::make_shared<LinearLaw>(kn);
  b.shear_stiffness = ks;
  b.strength.model = joint::StrengthModel::coulomb;
  b.strength.friction_angle = phi;
  b.strength.cohesion = c;
  b.strength.dilation_angle = psi;
  return b;
}
} // namespace rockjoint::test
