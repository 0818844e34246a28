// SPDX-License-Identifier: MIT
#include "transmissivity_table.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rockjoint::flow
{

namespace
{
[[noreturn]] void fail(std::size_t i, const std::string& what, double closure, double t)
{
  std::ostringstream msg;
  msg.precision(17);
  msg << "TransmissivityTable: knot " << i << " (closure " << closure << " m, transmissivity "
      << t << " m³): " << what;
  throw std::invalid_argument(msg.str());
}
} // namespace

TransmissivityTable::TransmissivityTable(std::span<const double> closure,
                                         std::span<const double> transmissivity)
    : _closure(closure.begin(), closure.end()),
      _transmissivity(transmissivity.begin(), transmissivity.end())
{
  const std::size_t n = closure.size();
  if (n != transmissivity.size() || n < 2)
    throw std::invalid_argument("TransmissivityTable: " + std::to_string(n) + " closures and "
                                + std::to_string(transmissivity.size())
                                + " transmissivities; equal numbers, at least 2, are needed");
  for (std::size_t i = 0; i < n; ++i)
  {
    const double d = closure[i], t = transmissivity[i];
    if (!std::isfinite(d) || !std::isfinite(t) || t < 0.0)
      fail(i, "closure and transmissivity must be finite, transmissivity >= 0", d, t);
    if (i == 0 && !(t > 0.0))
      fail(i, "the first transmissivity must be > 0", d, t);
    if (i > 0 && !(d > closure[i - 1]))
      fail(i, "closures must be strictly increasing", d, t);
    if (i > 0 && t > transmissivity[i - 1])
      fail(i, "transmissivity must not increase with closure", d, t);
    _positive += t > 0.0;
  }
  if (_positive >= 2)
  {
    namespace hermite = constitutive::hermite;
    std::vector<double> x(closure.begin(), closure.begin() + std::ptrdiff_t(_positive));
    std::vector<double> y(_positive), slope(_positive);
    for (std::size_t i = 0; i < _positive; ++i)
      y[i] = -std::log(transmissivity[i]);
    hermite::data_slopes(x, y, slope);
    for (std::size_t i = 0; i + 1 < _positive; ++i)
      _segments.push_back(hermite::make_segment(x[i], x[i + 1], y[i], y[i + 1], slope[i], slope[i + 1]));
    _end_slope = slope.back();
  }
}

double TransmissivityTable::transmissivity(double closure) const
{
  if (std::isnan(closure))
    return closure;
  const double d0 = _closure.front(), t0 = _transmissivity.front();
  if (closure <= d0)
  {
    // rigid separation past the first knot: e_h grows by the opening (file comment)
    const double e = std::cbrt(12.0 * t0) + (d0 - closure);
    return e * e * e / 12.0;
  }
  const double d_last = _closure[_positive - 1], t_last = _transmissivity[_positive - 1];
  if (closure >= d_last)
  {
    if (_positive < _closure.size())
    {
      const double d_zero = _closure[_positive];
      return closure >= d_zero ? 0.0 : t_last * (d_zero - closure) / (d_zero - d_last);
    }
    return t_last * std::exp(-_end_slope * (closure - d_last));
  }
  // d0 < Δ < d_last: the segment that holds Δ
  const auto it = std::upper_bound(_closure.begin(), _closure.begin() + std::ptrdiff_t(_positive),
                                   closure);
  const auto i = std::size_t(it - _closure.begin()) - 1;
  double y = 0.0, dy = 0.0;
  constitutive::hermite::evaluate(_segments[i], closure, y, dy);
  return std::exp(-y);
}

void TransmissivityTable::transmissivity(std::span<const double> closure,
                                         std::span<double> out) const
{
  if (closure.size() != out.size())
    throw std::invalid_argument("TransmissivityTable::transmissivity: " + std::to_string(closure.size())
                                + " closures, " + std::to_string(out.size()) + " outputs");
  for (std::size_t i = 0; i < closure.size(); ++i)
    out[i] = transmissivity(closure[i]);
}

} // namespace rockjoint::flow
