#pragma once
/// @file units.hpp
/// Length units of topography files. Inside the library everything is in metres.

#include <string>

namespace rockjoint::topography
{

/// Metres per `unit`: "m", "cm", "mm", "um" (also "µm", "micron"), "nm".
/// Throws std::invalid_argument naming the unit otherwise.
double metres_per_unit(const std::string& unit);

} // namespace rockjoint::topography
