// SPDX-License-Identifier: MIT
#include "contact_set.hpp"

#include <cassert>
#include <cstddef>
#include <limits>

namespace rockjoint::contact
{

ContactSet contact_set(std::span<const double> pressure, std::span<const double> gap,
                       std::span<const unsigned char> valid)
{
  assert(pressure.size() == valid.size() && gap.size() == valid.size());
  ContactSet c;
  c.member.assign(valid.size(), 0);
  for (std::size_t k = 0; k < valid.size(); ++k)
    if (valid[k] && (pressure[k] > 0.0 || !(gap[k] > 0.0)))
    {
      c.member[k] = 1;
      ++c.count;
    }
  return c;
}

std::vector<double> gap_field(std::span<const double> gap, const ContactSet& contact,
                              std::span<const unsigned char> valid)
{
  std::vector<double> out(gap.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < gap.size(); ++k)
    if (valid[k])
      out[k] = contact.member[k] ? 0.0 : gap[k];
  return out;
}

int count_patches(std::span<const unsigned char> member, std::size_t rows, std::size_t cols,
                  bool periodic)
{
  std::vector<unsigned char> seen(member.size(), 0);
  std::vector<std::size_t> stack;
  int patches = 0;
  for (std::size_t start = 0; start < member.size(); ++start)
  {
    if (!member[start] || seen[start])
      continue;
    ++patches;
    stack.assign(1, start);
    seen[start] = 1;
    while (!stack.empty())
    {
      const std::size_t k = stack.back();
      stack.pop_back();
      const std::size_t i = k / cols, j = k % cols;
      auto visit = [&](std::ptrdiff_t ii, std::ptrdiff_t jj)
      {
        if (periodic)
        {
          ii = (ii + std::ptrdiff_t(rows)) % std::ptrdiff_t(rows);
          jj = (jj + std::ptrdiff_t(cols)) % std::ptrdiff_t(cols);
        }
        else if (ii < 0 || jj < 0 || ii >= std::ptrdiff_t(rows) || jj >= std::ptrdiff_t(cols))
          return;
        const std::size_t m = std::size_t(ii) * cols + std::size_t(jj);
        if (member[m] && !seen[m])
        {
          seen[m] = 1;
          stack.push_back(m);
        }
      };
      visit(std::ptrdiff_t(i) - 1, std::ptrdiff_t(j));
      visit(std::ptrdiff_t(i) + 1, std::ptrdiff_t(j));
      visit(std::ptrdiff_t(i), std::ptrdiff_t(j) - 1);
      visit(std::ptrdiff_t(i), std::ptrdiff_t(j) + 1);
    }
  }
  return patches;
}

} // namespace rockjoint::contact
