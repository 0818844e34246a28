#pragma once
// The library's contract for bad input, checked one way in every test: it throws
// std::invalid_argument and the message names the problem (parameter, file, line, ...).
#include <gtest/gtest.h>

#include <initializer_list>
#include <stdexcept>
#include <string>

namespace rockjoint::testing
{

/// Run f; expect std::invalid_argument whose message contains every fragment.
template <class F>
void expect_error(F&& f, std::initializer_list<std::string> fragments)
{
  std::string expected;
  for (const auto& s : fragments)
    expected += (expected.empty() ? "'" : ", '") + s + "'";
  try
  {
    f();
    ADD_FAILURE() << "no exception for " << expected;
  }
  catch (const std::invalid_argument& e)
  {
    for (const auto& s : fragments)
      EXPECT_NE(std::string(e.what()).find(s), std::string::npos)
          << "message '" << e.what() << "' lacks '" << s << "'";
  }
}

/// Run f; expect std::invalid_argument whose message contains `fragment`.
template <class F>
void expect_error(F&& f, const std::string& fragment)
{
  expect_error(std::forward<F>(f), {fragment});
}

} // namespace rockjoint::testing
