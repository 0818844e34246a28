// SPDX-License-Identifier: MIT
#include "units.hpp"

#include <array>
#include <stdexcept>

namespace rockjoint::topography
{

namespace
{
constexpr std::array<LengthUnit, 8> units{{{"m", 1.0},
                                           {"cm", 1e-2},
                                           {"mm", 1e-3},
                                           {"um", 1e-6},
                                           {"µm", 1e-6},
                                           {"micron", 1e-6},
                                           {"nm", 1e-9},
                                           {"km", 1e3}}};
} // namespace

std::span<const LengthUnit> length_units() { return units; }

double metres_per_unit(const std::string& unit)
{
  std::string names;
  for (const LengthUnit& u : units)
  {
    if (u.name == unit)
      return u.metres;
    names += (names.empty() ? "" : ", ") + std::string(u.name);
  }
  throw std::invalid_argument("unknown length unit '" + unit + "'; use one of " + names);
}

} // namespace rockjoint::topography
