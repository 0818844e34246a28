// SPDX-License-Identifier: MIT
#pragma once
/// @file asperity_parameters.hpp
/// Statistical description of the composite topography used by the asperity models
/// (GW, Tang substrate, Tang & Jiao), theory §2-§3.

#include "closure_law.hpp"
#include "parameter_spec.hpp"

#include <limits>
#include <string>

namespace rockjoint::constitutive
{

/// Roughness statistics of the composite topography of a joint, SI units: the project's one
/// parameter type for them (C++ laws, Python, parameter files and topography analysis).
struct AsperityParameters
{
  double composite_modulus; ///< E* [Pa], 1/E* = (1-ν1²)/E1 + (1-ν2²)/E2 (theory §1)
  double summit_density;    ///< η [1/m²], summits per unit nominal area
  double summit_radius;     ///< β [m], mean summit radius of curvature
  double summit_height_std; ///< σ_s [m], standard deviation of summit heights
  /// h [m], the sampling interval the statistics were measured at (η ~ h⁻², β ~ h^1.1:
  /// theory §3), NaN when not known. Metadata: no law uses it.
  double sampling_interval = std::numeric_limits<double>::quiet_NaN();

  /// E*, η, β, σ_s and h: units and ranges (checked by validate; h only when known).
  static const std::vector<ParameterSpec>& parameter_specs();
};

/// Throw std::invalid_argument naming `owner`, the field, its value and the valid range unless
/// E*, η, β, σ_s are finite and > 0 and h is NaN (unknown) or finite and > 0.
void validate(const AsperityParameters& parameters, const std::string& owner);

/// A closure law built on a population of Hertzian summits (GW and its descendants). It
/// provides a contact-area ratio and exposes the statistics the interaction cell of Tang &
/// Jiao needs (Eq. (1): R = β and σ_s; Eq. (2): A/A0).
class AsperityLaw : public ClosureLaw
{
public:
  bool provides_contact_area() const override { return true; }
  /// The summit statistics this law was built from.
  virtual AsperityParameters asperity_parameters() const = 0;
};

} // namespace rockjoint::constitutive
