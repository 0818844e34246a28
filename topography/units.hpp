// SPDX-License-Identifier: MIT
#pragma once
/// @file units.hpp
/// Length units: the one table of them (topography files here; the Python layer reads the same
/// table through the bindings for scene files, calibration curves and law parameter files).
/// Inside the library everything is in metres.

#include <span>
#include <string>
#include <string_view>

namespace rockjoint::topography
{

/// A length unit and its size in metres.
struct LengthUnit
{
  std::string_view name; ///< e.g. "um"
  double metres; ///< its size [m]
};

/// Every length unit rockjoint reads: m, cm, mm, um (also µm, micron), nm, km.
std::span<const LengthUnit> length_units();

/// Metres per `unit` (a name of length_units()).
/// Throws std::invalid_argument naming the unit and the valid ones otherwise.
double metres_per_unit(const std::string& unit);

} // namespace rockjoint::topography
