// SPDX-License-Identifier: MIT
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

/// (σ, k, A/A0, status) of `law` over a closure array, each shaped like it. Templated on the
/// law type so a TabulatedLaw keeps its inlined batch path (no virtual call per point).
template <class Law>
py::tuple evaluate_to_numpy(const Law& law, const DoubleArray& closure)
{
  require_no_nan(closure, "closure");
  DoubleArray s = empty_like(closure), k = empty_like(closure), a = empty_like(closure);
  py::array_t<int> st(std::vector<py::ssize_t>(closure.shape(), closure.shape() + closure.ndim()));
  const std::size_t n = closure.size();
  static_assert(sizeof(int) == sizeof(decltype(law.evaluate(0.0).status)));
  std::span status(reinterpret_cast<decltype(law.evaluate(0.0).status)*>(st.mutable_data()), n);
  {
    py::gil_scoped_release release;
    law.evaluate(as_span(closure), {s.mutable_data(), n}, {k.mutable_data(), n},
                 {a.mutable_data(), n}, status);
  }
  return py::make_tuple(s, k, a, st);
}

/// One output column of evaluate_to_numpy(); a 0-d input gives a Python float.
template <int Column, class Law>
py::object evaluate_column(const Law& law, const DoubleArray& closure)
{
  py::tuple t = evaluate_to_numpy(law, closure);
  py::array out = t[Column];
  if (closure.ndim() == 0)
    return out.attr("item")();
  return out;
}

} // namespace rockjoint::python
