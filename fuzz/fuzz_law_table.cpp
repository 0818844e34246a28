// libFuzzer target: read_law_table (.rjt). Any input must either give a valid table or throw
// std::runtime_error naming the file; any other exception, a crash or a sanitizer report is a bug.
#include "fuzz_input.hpp"

#include <rockjoint/constitutive/law_table_file.hpp>

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string& path = rockjoint::fuzz::write_input(data, size, ".rjt");
  try
  {
    const auto table = rockjoint::constitutive::read_law_table(path);
    // A table the reader accepts must pass the library's own check.
    rockjoint::constitutive::validate_law_table(table, "fuzz");
  }
  catch (const std::runtime_error&)
  {
  }
  return 0;
}
