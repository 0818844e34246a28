#include "units.hpp"

#include <stdexcept>

namespace rockjoint::topography
{

double metres_per_unit(const std::string& unit)
{
  if (unit == "m")
    return 1.0;
  if (unit == "cm")
    return 1e-2;
  if (unit == "mm")
    return 1e-3;
  if (unit == "um" || unit == "µm" || unit == "micron")
    return 1e-6;
  if (unit == "nm")
    return 1e-9;
  throw std::invalid_argument("unknown length unit '" + unit
                              + "'; use one of m, cm, mm, um (µm), nm");
}

} // namespace rockjoint::topography
