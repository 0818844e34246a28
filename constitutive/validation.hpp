// SPDX-License-Identifier: MIT
#pragma once
/// @file validation.hpp
/// Parameter checks done once, at construction. Messages name the law, the parameter, its
/// value and unit, and the valid range.

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rockjoint::constitutive::validation
{

/// Throw std::invalid_argument naming `owner`, `parameter`, its value, unit and range.
[[noreturn]] inline void fail(const std::string& owner, const std::string& parameter,
                              double value, const std::string& unit, const std::string& range)
{
  std::ostringstream msg;
  msg.precision(17);
  msg << owner << ": parameter '" << parameter << "' = " << value;
  if (!unit.empty())
    msg << " " << unit;
  msg << " is invalid; it must be " << range;
  throw std::invalid_argument(msg.str());
}

/// value finite and > 0.
inline double positive(const std::string& owner, const std::string& parameter, double value,
                       const std::string& unit)
{
  if (!(std::isfinite(value) && value > 0.0))
    fail(owner, parameter, value, unit, "finite and > 0");
  return value;
}

/// value finite and >= 0.
inline double non_negative(const std::string& owner, const std::string& parameter,
                           double value, const std::string& unit)
{
  if (!(std::isfinite(value) && value >= 0.0))
    fail(owner, parameter, value, unit, "finite and >= 0");
  return value;
}

/// value finite.
inline double finite(const std::string& owner, const std::string& parameter, double value,
                     const std::string& unit)
{
  if (!std::isfinite(value))
    fail(owner, parameter, value, unit, "finite");
  return value;
}

/// lo < value < hi (open), or lo <= value <= hi with `closed` = true.
inline double in_range(const std::string& owner, const std::string& parameter, double value,
                       const std::string& unit, double lo, double hi, bool closed = false)
{
  const bool ok = closed ? (value >= lo && value <= hi) : (value > lo && value < hi);
  if (!ok || std::isnan(value))
  {
    std::ostringstream range;
    range.precision(17);
    range << "in " << (closed ? "[" : "(") << lo << ", " << hi << (closed ? "]" : ")");
    fail(owner, parameter, value, unit, range.str());
  }
  return value;
}

} // namespace rockjoint::constitutive::validation
