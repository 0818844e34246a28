// SPDX-License-Identifier: MIT
#include "joint_strength.hpp"

#include <rockjoint/constitutive/validation.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rockjoint::joint
{

namespace
{
constexpr double degree = std::numbers::pi / 180.0;

/// Barton's mobilised friction angle [rad] at σ_n, and σ_n dangle/dσ_n.
struct MobilisedAngle
{
  double angle;
  double stress_times_rate;
};

MobilisedAngle barton_angle(const JointStrength& s, double normal_stress)
{
  const double cap = s.maximum_friction_angle;
  if (!(normal_stress > 0.0))
    return {cap, 0.0}; // σ_n <= 0: the low-stress cap (log10(JCS/σ_n) → ∞)
  if (normal_stress >= s.jcs)
    return {s.friction_angle, 0.0}; // past the correlation's range: roughness sheared off
  // JRC log10(JCS/σ_n) is in degrees; d/dσ_n of it is -JRC / (σ_n ln 10) degrees.
  const double angle = s.friction_angle + s.jrc * std::log10(s.jcs / normal_stress) * degree;
  if (angle >= cap)
    return {cap, 0.0};
  return {angle, -s.jrc * degree / std::numbers::ln10};
}
} // namespace

void validate(const JointStrength& s, const std::string& owner)
{
  namespace v = constitutive::validation;
  if (s.model == StrengthModel::none)
    return;
  if (s.model != StrengthModel::coulomb && s.model != StrengthModel::barton)
    v::fail(owner, "strength model", static_cast<double>(s.model), "",
            "0 (none), 1 (coulomb) or 2 (barton)");
  const bool barton = s.model == StrengthModel::barton;
  if (!(s.friction_angle >= 0.0 && s.friction_angle < std::numbers::pi / 2.0))
    v::fail(owner, barton ? "residual_friction_angle" : "friction_angle", s.friction_angle,
            "rad", "in [0, pi/2), i.e. [0, 90) degrees");
  v::non_negative(owner, "cohesion", s.cohesion, "Pa");
  v::non_negative(owner, "tensile_strength", s.tensile_strength, "Pa");
  double largest_angle = s.friction_angle;
  if (barton)
  {
    v::in_range(owner, "jrc", s.jrc, "", 0.0, 20.0, true);
    v::positive(owner, "jcs", s.jcs, "Pa");
    if (!(s.maximum_friction_angle >= s.friction_angle
          && s.maximum_friction_angle < std::numbers::pi / 2.0))
      v::fail(owner, "maximum_friction_angle", s.maximum_friction_angle, "rad",
              "in [residual_friction_angle, pi/2)");
    largest_angle = s.maximum_friction_angle;
  }
  if (!(s.dilation_angle >= 0.0 && s.dilation_angle <= largest_angle))
    v::fail(owner, "dilation_angle", s.dilation_angle, "rad",
            "in [0, " + std::to_string(largest_angle) + "] (0 <= psi <= the friction angle)");
  if (!(std::isfinite(s.reduction_factor) && s.reduction_factor > 0.0))
    v::fail(owner, "reduction_factor", s.reduction_factor, "", "finite and > 0 (1: no reduction)");
  if (!(s.dilation_limit > 0.0)) // NaN fails too; +inf (no limit) passes
    v::fail(owner, "dilation_limit", s.dilation_limit, "m", "> 0 (inf: dilation never stops)");
  // Tension cut-off inside the cone: at σ_n = -T the strength c - T tan φ must stay >= 0.
  if (largest_angle > 0.0 && s.tensile_strength > s.cohesion / std::tan(largest_angle))
    v::fail(owner, "tensile_strength", s.tensile_strength, "Pa",
            "<= cohesion / tan(friction angle) = "
                + std::to_string(s.cohesion / std::tan(largest_angle))
                + " Pa (the apex of the Coulomb cone)");
}

double reduced_tensile_strength(const JointStrength& s)
{
  return s.tensile_strength / s.reduction_factor;
}

ShearStrength shear_strength(const JointStrength& s, double normal_stress, bool bonded)
{
  if (s.model == StrengthModel::none)
    return {};
  const double cohesion = bonded ? s.cohesion : 0.0;
  double angle = s.friction_angle, stress_times_rate = 0.0;
  if (s.model == StrengthModel::barton)
  {
    const MobilisedAngle a = barton_angle(s, normal_stress);
    angle = a.angle;
    stress_times_rate = a.stress_times_rate;
  }
  const double tan_angle = std::tan(angle);
  // Reduced by F at every σ_n (header): c / F + σ_n tan a(σ_n) / F.
  const double factor = s.reduction_factor;
  const double strength = (cohesion + normal_stress * tan_angle) / factor;
  if (!(strength > 0.0))
    return {0.0, 0.0};
  // d/dσ_n [σ_n tan a(σ_n)] = tan a + σ_n sec²a da/dσ_n.
  return {strength, (tan_angle + (1.0 + tan_angle * tan_angle) * stress_times_rate) / factor};
}

DilationIncrement dilation_increment(const JointStrength& s, double accumulated_slip,
                                     double slip_increment)
{
  if (s.model == StrengthModel::none || s.dilation_angle == 0.0)
    return {};
  // ψ_F within the reduced friction: tan ψ_F = min(tan ψ, tan φ_max / F) (header).
  const double largest = s.model == StrengthModel::barton ? s.maximum_friction_angle : s.friction_angle;
  const double tan_psi = std::min(std::tan(s.dilation_angle), std::tan(largest) / s.reduction_factor);
  const double limit = s.dilation_limit;
  const double before = std::min(accumulated_slip, limit);
  const double after = std::min(accumulated_slip + slip_increment, limit);
  return {tan_psi * (after - before), accumulated_slip + slip_increment < limit ? tan_psi : 0.0};
}

} // namespace rockjoint::joint
