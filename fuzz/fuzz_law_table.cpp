// SPDX-License-Identifier: MIT
// libFuzzer target: .rjt files as a user's scene or script loads them, TabulatedLaw::load
// (read_law_table, then the law and its segment index built from the knots), and the loaded law
// evaluated inside, at the ends of and beyond its table. Any input must either give a law or throw
// std::runtime_error / std::invalid_argument naming the problem; any other exception, a crash or
// a sanitizer report is a bug.
#include "fuzz_input.hpp"

#include <rockjoint/constitutive/tabulated_law.hpp>

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  using rockjoint::constitutive::TabulatedLaw;
  const std::string& path = rockjoint::fuzz::write_input(data, size, ".rjt");
  try
  {
    const TabulatedLaw law = TabulatedLaw::load(path);
    const double top = law.table_maximum_closure();
    for (double x : {-top, 0.0, 1e-3 * top, 0.5 * top, top, 2.0 * top})
      (void)law.evaluate(x);
    (void)law.closure_at_stress(0.5 * law.table().normal_stress.back());
  }
  catch (const std::runtime_error&)
  {
  }
  catch (const std::invalid_argument&)
  {
  }
  catch (const std::domain_error&)
  {
  }
  return 0;
}
