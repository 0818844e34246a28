// SPDX-License-Identifier: MIT
#pragma once
/// @file joint_strength.hpp
/// Shear strength of a joint (docs/joint-strength.md): the yield function of the Coulomb slip
/// model, its tension cut-off and the dilatancy of its non-associated flow rule.
///
/// With σ_n the normal stress (compression +) and τ = |(τ1, τ2)| the shear stress magnitude:
///   Coulomb:  τ_y(σ_n) = c + σ_n tan φ,
///   Barton:   τ_y(σ_n) = c + σ_n tan(φ_r + JRC log10(JCS/σ_n))   (Barton & Choubey 1977),
///             the mobilised angle capped at `maximum_friction_angle` (70°, Barton & Choubey's
///             limit for low stress, also used for σ_n <= 0) and the roughness term at zero for
///             σ_n >= JCS (the correlation's range ends there);
/// yield function f = τ - τ_y(σ_n) <= 0; plastic potential g = τ - σ_n tan ψ (slip opens the
/// joint by tan ψ per unit slip while the accumulated slip is below `dilation_limit`).
/// Tension cut-off: a joint carries tension only while bonded (tensile_strength T > 0, never
/// exceeded); T = 0 (default): an open joint transmits no traction.
///
/// Strength reduction (factor of safety, docs/slopes.md): with `reduction_factor` F (default 1)
/// the strength is divided by F at every normal stress,
///   τ_y,F(σ_n) = c / F + σ_n tan φ_m(σ_n) / F,   T_F = T / F,   tan ψ_F = min(tan ψ, tan φ_max / F),
/// φ_m the mobilised angle above (Coulomb: φ; Barton: φ_r + JRC log10(JCS/σ_n), capped), φ_max its
/// largest value (φ; Barton: the cap). For Barton this is the reduction of a non-linear criterion
/// through its instantaneous friction, tan φ_m(σ_n) / F at each σ_n, as discontinuum codes do
/// (Itasca UDEC manual, "Factor-of-Safety Calculation": the strength reduction of non-linear
/// criteria, after Dawson et al. 2000 and Hammah et al. 2005); ψ_F keeps the dilation within the
/// reduced friction, as tan ψ_F = min(tan ψ, tan φ / F) does for Coulomb.

#include <limits>
#include <string>

namespace rockjoint::joint
{

/// Which peak strength bounds the shear stress.
enum class StrengthModel : int
{
  none = 0,    ///< elastic joint: no strength, no slip (the model before joint strength)
  coulomb = 1, ///< τ_y = c + σ_n tan φ
  barton = 2,  ///< τ_y = c + σ_n tan(φ_r + JRC log10(JCS/σ_n))
};

/// Parameters of the shear strength (angles in radians, stresses in Pa, lengths in m).
struct JointStrength
{
  StrengthModel model = StrengthModel::none; ///< none, Coulomb or Barton
  double friction_angle = 0.0;   ///< φ (Coulomb) or the residual angle φ_r (Barton) [rad], [0, π/2)
  double cohesion = 0.0;         ///< c [Pa], >= 0
  double tensile_strength = 0.0; ///< T [Pa], >= 0, at most the cone apex c / tan φ_max
  double dilation_angle = 0.0;   ///< ψ [rad], 0 <= ψ <= φ (Barton: <= the angle cap)
  /// Accumulated slip after which dilation stops [m], > 0 (∞: never).
  double dilation_limit = std::numeric_limits<double>::infinity();
  double jrc = 0.0;              ///< joint roughness coefficient [-], [0, 20] (Barton)
  double jcs = 0.0;              ///< joint wall compressive strength [Pa], > 0 (Barton)
  /// Cap of Barton's mobilised friction angle [rad] (70°: Barton & Choubey 1977).
  double maximum_friction_angle = 70.0 * 3.14159265358979323846 / 180.0;
  /// Strength reduction factor F [-], > 0 (1: the strength itself): c, tan φ_m and T divided by it.
  double reduction_factor = 1.0;
};

/// Throw std::invalid_argument naming `owner`, the parameter, its value and valid range.
void validate(const JointStrength& strength, const std::string& owner);

/// Shear strength τ_y [Pa] and its slope μ = dτ_y/dσ_n [-] at normal stress σ_n (compression
/// +). `bonded` = false drops cohesion (a bond broken in tension). τ_y is clamped at 0 (only
/// reachable in tension, where the validated T keeps a bonded joint inside the cone).
struct ShearStrength
{
  double strength = std::numeric_limits<double>::infinity(); ///< τ_y [Pa] (∞: no strength)
  double slope = 0.0; ///< dτ_y/dσ_n [-]
};
/// τ_y and dτ_y/dσ_n at normal stress σ_n [Pa] (compression +).
ShearStrength shear_strength(const JointStrength& strength, double normal_stress, bool bonded);

/// The tensile strength in force, T / F [Pa] (F the reduction factor).
double reduced_tensile_strength(const JointStrength& strength);

/// Dilation produced by increasing the accumulated slip from κ0 to κ0 + dλ [m], and its rate
/// d(dilation)/d(dλ) at that end (tan ψ before the dilation limit, 0 after it).
struct DilationIncrement
{
  double opening = 0.0; ///< dilation over the increment [m]
  double rate = 0.0; ///< d(dilation)/d(dλ) at its end [-]
};
/// Dilation from accumulated slip κ0 [m] over a slip increment dλ [m].
DilationIncrement dilation_increment(const JointStrength& strength, double accumulated_slip,
                                     double slip_increment);

} // namespace rockjoint::joint
