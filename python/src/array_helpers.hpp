#pragma once
// Helpers shared by the binding files: numpy in, numpy out, no copies where avoidable.

#include <cmath>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <span>
#include <string>

namespace rockjoint::python
{
namespace py = pybind11;

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// A read-only span over a contiguous double array.
inline std::span<const double> as_span(const DoubleArray& a)
{
  return {a.data(), static_cast<std::size_t>(a.size())};
}

/// A new array shaped like `like`.
inline DoubleArray empty_like(const DoubleArray& like)
{
  return DoubleArray(std::vector<py::ssize_t>(like.shape(), like.shape() + like.ndim()));
}

/// Raise ValueError naming `what` if any entry is NaN.
inline void require_no_nan(const DoubleArray& a, const std::string& what)
{
  auto s = as_span(a);
  for (std::size_t i = 0; i < s.size(); ++i)
    if (std::isnan(s[i]))
      throw py::value_error(what + " contains NaN (entry " + std::to_string(i) + ")");
}

} // namespace rockjoint::python
