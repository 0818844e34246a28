// SPDX-License-Identifier: MIT
#pragma once
/// @file parameter_spec.hpp
/// What a law's parameter is, in the law's own code (MGIS-style metadata): its keyword, symbol,
/// SI unit, the unit parameter files and reports use, and its admissible range. A law's
/// constructor checks its arguments against these specs, and the Python layer reads the same
/// specs (`<Law>.parameter_specs()`) for the registry, parameter files, scenes and calibration:
/// the range of a parameter is written once.

#include "validation.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace rockjoint::constitutive
{

/// One parameter of a law's constructor: keyword, symbol, units and admissible range (the law's
/// `parameter_specs()` lists them; its constructor checks its arguments with `check`).
struct ParameterSpec
{
  std::string name;      ///< keyword of the SI constructor argument, e.g. "maximum_closure"
  std::string symbol;    ///< symbol in the theory, e.g. "V_m"
  std::string unit;      ///< SI unit, e.g. "m" ("-": dimensionless)
  std::string file_unit; ///< the unit of parameter files and reports, e.g. "mm"
  double lower = 0.0;    ///< lower bound of the admissible range
  bool lower_inclusive = false; ///< whether `lower` itself is admissible
  double upper = std::numeric_limits<double>::infinity(); ///< upper bound (∞: none)
  bool upper_inclusive = false; ///< whether `upper` itself is admissible

  /// Whether `value` lies in the admissible range (NaN never does; ∞ only up to an infinite
  /// inclusive bound, which no spec has).
  bool admits(double value) const
  {
    if (std::isnan(value) || std::isinf(value))
      return false;
    const bool above = lower_inclusive ? value >= lower : value > lower;
    const bool below = std::isinf(upper) || (upper_inclusive ? value <= upper : value < upper);
    return above && below;
  }

  /// The range in words, as error messages give it: "finite and > 0", "in [0, 1)".
  std::string range() const
  {
    std::ostringstream out;
    out.precision(17);
    if (std::isinf(upper))
      out << "finite and " << (lower_inclusive ? ">= " : "> ") << lower;
    else
      out << "in " << (lower_inclusive ? "[" : "(") << lower << ", " << upper
          << (upper_inclusive ? "]" : ")");
    return out.str();
  }

  /// `value` if admitted, else std::invalid_argument naming `owner`, the parameter, its value,
  /// unit and range (validation::fail).
  double check(const std::string& owner, double value) const
  {
    if (!admits(value))
      validation::fail(owner, name, value, unit, range());
    return value;
  }
};

} // namespace rockjoint::constitutive
