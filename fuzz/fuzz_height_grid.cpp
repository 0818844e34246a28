// SPDX-License-Identifier: MIT
// libFuzzer target: read_height_grid. Any input must give a surface or throw
// std::invalid_argument / std::runtime_error (documented in surface_io.hpp); any other
// exception, a crash or a sanitizer report is a bug.
#include "fuzz_input.hpp"

#include <rockjoint/topography/surface_io.hpp>

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string& path = rockjoint::fuzz::write_input(data, size, ".txt");
  try
  {
    (void)rockjoint::topography::read_height_grid(path);
  }
  catch (const std::invalid_argument&)
  {
  }
  catch (const std::runtime_error&)
  {
  }
  return 0;
}
