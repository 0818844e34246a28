// SPDX-License-Identifier: MIT
#pragma once
// The library's contract for bad input, checked one way in every test: it throws
// std::invalid_argument (std::domain_error, std::runtime_error where the library documents
// them) and the message names the problem (parameter, file, line, limit, ...).
#include <gtest/gtest.h>

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>

namespace rockjoint::testing
{

/// Run f; expect an Error whose message contains every fragment.
template <class Error = std::invalid_argument, class F>
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
  catch (const Error& e)
  {
    for (const auto& s : fragments)
      EXPECT_NE(std::string(e.what()).find(s), std::string::npos)
          << "message '" << e.what() << "' lacks '" << s << "'";
  }
}

/// Run f; expect an Error whose message contains `fragment`.
template <class Error = std::invalid_argument, class F>
void expect_error(F&& f, const std::string& fragment)
{
  expect_error<Error>(std::forward<F>(f), {fragment});
}

} // namespace rockjoint::testing
