// SPDX-License-Identifier: MIT
#include "surface_io.hpp"

#include "units.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace rockjoint::topography
{

namespace
{

[[noreturn]] void fail_at(const std::string& path, std::size_t line, const std::string& what)
{
  std::ostringstream msg;
  msg << path << ":" << line << ": " << what;
  throw std::invalid_argument(msg.str());
}

std::ifstream open_for_reading(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
    throw std::runtime_error("cannot open '" + path + "' for reading");
  return in;
}

std::ofstream open_for_writing(const std::string& path)
{
  std::ofstream out(path);
  if (!out)
    throw std::runtime_error("cannot open '" + path + "' for writing");
  return out;
}

std::string trim(const std::string& s)
{
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos)
    return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

/// Split on whitespace and commas.
std::vector<std::string> tokens(const std::string& line)
{
  std::vector<std::string> out;
  std::string cur;
  for (char c : line)
  {
    if (c == ' ' || c == '\t' || c == ',' || c == '\r' || c == ';')
    {
      if (!cur.empty())
        out.push_back(std::move(cur)), cur.clear();
    }
    else
      cur.push_back(c);
  }
  if (!cur.empty())
    out.push_back(std::move(cur));
  return out;
}

/// Parse one number; "nan", "NaN", "NA" give NaN; false for anything else that is not a
/// complete finite number.
bool parse_number(const std::string& token, double& value)
{
  if (token == "nan" || token == "NaN" || token == "NAN" || token == "NA" || token == "-nan")
  {
    value = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  const char* first = token.data();
  if (!token.empty() && token[0] == '+')
    ++first;
  const char* last = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(first, last, value);
  return ec == std::errc() && ptr == last && std::isfinite(value);
}

/// "# key: value" or "# key = value" header line -> (key, value); empty key otherwise.
std::pair<std::string, std::string> header_entry(const std::string& line)
{
  std::string body = trim(line.substr(1));
  auto pos = body.find_first_of(":=");
  if (pos == std::string::npos)
    return {};
  return {trim(body.substr(0, pos)), trim(body.substr(pos + 1))};
}

double header_number(const std::string& path, std::size_t line, const std::string& key,
                     const std::string& value)
{
  double v;
  if (!parse_number(value, v) || std::isnan(v))
    fail_at(path, line, "header '" + key + "': '" + value + "' is not a number");
  return v;
}

/// A row or column count: a whole number >= 1 (checked before the conversion to an integer,
/// which is undefined for values out of range).
long header_count(const std::string& path, std::size_t line, const std::string& key,
                  const std::string& value)
{
  const double v = header_number(path, line, key, value);
  if (!(v >= 1.0 && v <= 1e15 && v == std::floor(v)))
    fail_at(path, line, "header '" + key + "': '" + value + "' is not a whole number >= 1");
  return static_cast<long>(v);
}

std::string format_number(double v)
{
  if (std::isnan(v))
    return "nan";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

struct Header
{
  std::optional<double> spacing_x, spacing_y;
  std::optional<std::string> lateral_unit, height_unit;
  std::optional<long> rows, cols;
  std::size_t rows_line = 0, cols_line = 0;
};

/// Units and spacings: options override the file; missing ones are an error naming the file.
void resolve(const std::string& path, Header& h, const ReadOptions& options, bool need_spacing)
{
  if (options.spacing_x)
    h.spacing_x = options.spacing_x;
  if (options.spacing_y)
    h.spacing_y = options.spacing_y;
  if (options.lateral_unit)
    h.lateral_unit = options.lateral_unit;
  if (options.height_unit)
    h.height_unit = options.height_unit;
  if (need_spacing && (!h.spacing_x || !h.spacing_y))
    throw std::invalid_argument(path + ": no grid spacing: add a '# spacing: <value>' (or "
                                "spacing_x / spacing_y) header line or pass the spacing");
  if (!h.lateral_unit)
    throw std::invalid_argument(path + ": no lateral unit: add a '# lateral_unit: mm' header "
                                "line or pass the unit");
  if (!h.height_unit)
    throw std::invalid_argument(path + ": no height unit: add a '# height_unit: mm' header "
                                "line or pass the unit");
  try
  {
    metres_per_unit(*h.lateral_unit);
    metres_per_unit(*h.height_unit);
  }
  catch (const std::invalid_argument& e)
  {
    throw std::invalid_argument(path + ": " + e.what());
  }
}

/// Read a "# key: value" line into the header.
void read_header_line(const std::string& path, std::size_t n, const std::string& line,
                      Header& h)
{
  auto [key, value] = header_entry(line);
  if (key == "spacing")
    h.spacing_x = h.spacing_y = header_number(path, n, key, value);
  else if (key == "spacing_x")
    h.spacing_x = header_number(path, n, key, value);
  else if (key == "spacing_y")
    h.spacing_y = header_number(path, n, key, value);
  else if (key == "lateral_unit" || key == "unit")
    h.lateral_unit = value;
  else if (key == "height_unit")
    h.height_unit = value;
  else if (key == "rows")
    h.rows = header_count(path, n, key, value), h.rows_line = n;
  else if (key == "cols" || key == "columns")
    h.cols = header_count(path, n, key, value), h.cols_line = n;
  if (key == "unit" && !h.height_unit)
    h.height_unit = value;
}

/// The data lines of a text height file: blank lines skipped, '#' lines handed to the header
/// (once data has started, only if `header_after_data`), line numbers kept for errors.
class DataLines
{
public:
  DataLines(std::ifstream& in, const std::string& path, Header& header, bool header_after_data)
      : _in(in), _path(path), _header(header), _header_after_data(header_after_data)
  {
  }
  /// The next data line (trimmed) and its 1-based number; false at the end of the file.
  bool next(std::string& text, std::size_t& number)
  {
    std::string line;
    while (std::getline(_in, line))
    {
      ++_number;
      text = trim(line);
      if (text.empty())
        continue;
      if (text[0] == '#')
      {
        if (!_data_started || _header_after_data)
          read_header_line(_path, _number, text, _header);
        continue;
      }
      _data_started = true;
      number = _number;
      return true;
    }
    return false;
  }

private:
  std::ifstream& _in;
  const std::string& _path;
  Header& _header;
  bool _header_after_data;
  bool _data_started = false;
  std::size_t _number = 0;
};

} // namespace

SurfaceFile read_height_grid(const std::string& path, const ReadOptions& options)
{
  std::ifstream in = open_for_reading(path);
  Header h;
  std::vector<double> values;
  std::size_t cols = 0, rows = 0, n = 0, first_row_line = 0;
  std::string t;
  // Comments after the data started carry no header.
  DataLines data(in, path, h, false);
  while (data.next(t, n))
  {
    const auto tok = tokens(t);
    if (rows == 0)
      cols = tok.size(), first_row_line = n;
    else if (tok.size() != cols)
    {
      std::ostringstream msg;
      msg << "ragged row: " << tok.size() << " values, but row 1 (line " << first_row_line
          << ") has " << cols;
      fail_at(path, n, msg.str());
    }
    for (std::size_t k = 0; k < tok.size(); ++k)
    {
      double v;
      if (!parse_number(tok[k], v))
      {
        std::ostringstream msg;
        msg << "value " << k + 1 << " '" << tok[k] << "' is not a number (use nan for a "
            << "missing point)";
        fail_at(path, n, msg.str());
      }
      values.push_back(v);
    }
    ++rows;
  }
  if (rows == 0)
    throw std::invalid_argument(path + ": no data rows");
  if (h.rows && *h.rows != static_cast<long>(rows))
  {
    std::ostringstream msg;
    msg << "mismatched grid: header says rows = " << *h.rows << " but the file has " << rows
        << " data rows";
    fail_at(path, h.rows_line, msg.str());
  }
  if (h.cols && *h.cols != static_cast<long>(cols))
  {
    std::ostringstream msg;
    msg << "mismatched grid: header says cols = " << *h.cols << " but the rows have " << cols
        << " values";
    fail_at(path, h.cols_line, msg.str());
  }
  resolve(path, h, options, true);
  const double lat = metres_per_unit(*h.lateral_unit), ht = metres_per_unit(*h.height_unit);
  HeightGrid grid(rows, cols);
  for (std::size_t k = 0; k < values.size(); ++k)
    grid.data()[k] = values[k] * ht;
  try
  {
    return {Surface(std::move(grid), *h.spacing_x * lat, *h.spacing_y * lat), *h.lateral_unit,
            *h.height_unit};
  }
  catch (const std::invalid_argument& e)
  {
    throw std::invalid_argument(path + ": " + e.what());
  }
}

void write_height_grid(const std::string& path, const Surface& surface,
                       const std::string& lateral_unit, const std::string& height_unit)
{
  const double lat = metres_per_unit(lateral_unit), ht = metres_per_unit(height_unit);
  std::ofstream out = open_for_writing(path);
  out << "# rockjoint height grid (row i: y = i*spacing_y; column j: x = j*spacing_x)\n"
      << "# spacing_x: " << format_number(surface.spacing_x() / lat) << "\n"
      << "# spacing_y: " << format_number(surface.spacing_y() / lat) << "\n"
      << "# lateral_unit: " << lateral_unit << "\n"
      << "# height_unit: " << height_unit << "\n"
      << "# rows: " << surface.rows() << "\n"
      << "# cols: " << surface.cols() << "\n";
  for (Eigen::Index i = 0; i < surface.rows(); ++i)
  {
    for (Eigen::Index j = 0; j < surface.cols(); ++j)
      out << (j ? " " : "") << format_number(surface.heights()(i, j) / ht);
    out << "\n";
  }
  if (!out)
    throw std::runtime_error("error while writing '" + path + "'");
}

namespace
{
/// At most this many lattice points per point in an XYZ file (the rest are missing, NaN).
constexpr double max_lattice_fill = 100.0;

/// Lattice of a set of coordinates: origin and step.
struct Axis
{
  double origin, step;
};

/// The lattice lines are the coordinate values shared by many points (at least half the
/// median multiplicity), so one stray point cannot set the step; the step is the smallest
/// gap between lattice lines.
Axis lattice_axis(std::vector<double> c, const std::string& path, const char* name)
{
  std::sort(c.begin(), c.end());
  const double range = c.back() - c.front();
  const double merge = 1e-9 * std::max(range, std::abs(c.front()) + 1e-300);
  std::vector<std::pair<double, std::size_t>> lines; // (value, multiplicity)
  for (double v : c)
    if (!lines.empty() && v - lines.back().first <= merge)
      ++lines.back().second;
    else
      lines.emplace_back(v, 1);
  if (lines.size() < 2)
    throw std::invalid_argument(path + ": all points have the same " + name
                                + " coordinate; a lattice needs at least 2 distinct values");
  std::vector<std::size_t> mult;
  for (const auto& l : lines)
    mult.push_back(l.second);
  std::nth_element(mult.begin(), mult.begin() + mult.size() / 2, mult.end());
  double threshold = 0.5 * static_cast<double>(mult[mult.size() / 2]);
  if (std::count_if(lines.begin(), lines.end(), [&](const auto& l)
                    { return static_cast<double>(l.second) >= threshold; })
      < 2)
    threshold = 0.0; // too few points to tell lattice lines from strays: use them all
  double step = std::numeric_limits<double>::infinity(), previous = std::nan(""), origin = std::nan("");
  for (const auto& [v, m] : lines)
    if (static_cast<double>(m) >= threshold)
    {
      if (std::isnan(origin))
        origin = v;
      else
        step = std::min(step, v - previous);
      previous = v;
    }
  if (!std::isfinite(step))
    throw std::invalid_argument(path + ": cannot find a regular lattice in the " + name
                                + " coordinates");
  return {origin, step};
}
/// The lattice the points span must be mostly filled: a stray or mistyped coordinate (1e6
/// instead of 1.0) would otherwise ask for a grid of billions of points. Checked in floating
/// point before any index is formed, so no integer can overflow.
void check_lattice_size(const std::string& path, const std::vector<double>& xs,
                        const std::vector<double>& ys, const Axis& ax, const Axis& ay)
{
  const auto [x0, x1] = std::minmax_element(xs.begin(), xs.end());
  const auto [y0, y1] = std::minmax_element(ys.begin(), ys.end());
  const double cols = std::floor((*x1 - *x0) / ax.step + 0.5) + 1.0;
  const double rows = std::floor((*y1 - *y0) / ay.step + 0.5) + 1.0;
  const double points = static_cast<double>(xs.size());
  if (!(rows * cols <= max_lattice_fill * points))
  {
    std::ostringstream msg;
    msg.precision(6);
    msg << "the " << xs.size() << " points span a lattice of " << rows << " x " << cols
        << " points (steps " << ax.step << " in x, " << ay.step << " in y; x from " << *x0
        << " to " << *x1 << ", y from " << *y0 << " to " << *y1 << "), more than "
        << max_lattice_fill << " lattice points per point given: is a coordinate mistyped?";
    throw std::invalid_argument(path + ": " + msg.str());
  }
}
} // namespace

SurfaceFile read_xyz(const std::string& path, const ReadOptions& options)
{
  std::ifstream in = open_for_reading(path);
  Header h;
  std::vector<double> xs, ys, zs;
  std::vector<std::size_t> lines;
  std::size_t n = 0;
  std::string t;
  DataLines data(in, path, h, true);
  while (data.next(t, n))
  {
    const auto tok = tokens(t);
    if (tok.size() != 3)
    {
      std::ostringstream msg;
      msg << "expected 3 values 'x y z', found " << tok.size();
      fail_at(path, n, msg.str());
    }
    double v[3];
    for (int k = 0; k < 3; ++k)
      if (!parse_number(tok[k], v[k]) || (k < 2 && std::isnan(v[k])))
        fail_at(path, n,
                std::string("value ") + "xyz"[k] + " '" + tok[k] + "' is not a number");
    xs.push_back(v[0]), ys.push_back(v[1]), zs.push_back(v[2]), lines.push_back(n);
  }
  if (xs.empty())
    throw std::invalid_argument(path + ": no points");
  resolve(path, h, options, false);
  const Axis ax = lattice_axis(xs, path, "x"), ay = lattice_axis(ys, path, "y");
  check_lattice_size(path, xs, ys, ax, ay);
  const double tol = 1e-6;
  std::vector<long> ii(xs.size()), jj(xs.size());
  for (std::size_t k = 0; k < xs.size(); ++k)
  {
    const double fx = (xs[k] - ax.origin) / ax.step, fy = (ys[k] - ay.origin) / ay.step;
    jj[k] = std::lround(fx), ii[k] = std::lround(fy);
    if (std::abs(fx - jj[k]) > tol || std::abs(fy - ii[k]) > tol)
    {
      std::ostringstream msg;
      msg.precision(12);
      msg << "point (" << xs[k] << ", " << ys[k] << ") is not on the regular lattice x = "
          << ax.origin << " + j*" << ax.step << ", y = " << ay.origin << " + i*" << ay.step;
      fail_at(path, lines[k], msg.str());
    }
  }
  const long i_min = *std::min_element(ii.begin(), ii.end()), j_min = *std::min_element(jj.begin(), jj.end());
  const long rows = *std::max_element(ii.begin(), ii.end()) - i_min + 1;
  const long cols = *std::max_element(jj.begin(), jj.end()) - j_min + 1;
  HeightGrid grid = HeightGrid::Constant(rows, cols, std::numeric_limits<double>::quiet_NaN());
  std::map<std::pair<long, long>, std::size_t> seen;
  const double ht = metres_per_unit(*h.height_unit), lat = metres_per_unit(*h.lateral_unit);
  for (std::size_t k = 0; k < xs.size(); ++k)
  {
    auto [it, inserted] = seen.emplace(std::make_pair(ii[k], jj[k]), lines[k]);
    if (!inserted)
    {
      std::ostringstream msg;
      msg << "duplicate lattice point (" << xs[k] << ", " << ys[k] << "), first given on line "
          << it->second;
      fail_at(path, lines[k], msg.str());
    }
    grid(ii[k] - i_min, jj[k] - j_min) = zs[k] * ht;
  }
  return {Surface(std::move(grid), ax.step * lat, ay.step * lat), *h.lateral_unit,
          *h.height_unit};
}

void write_xyz(const std::string& path, const Surface& surface, const std::string& lateral_unit,
               const std::string& height_unit)
{
  const double lat = metres_per_unit(lateral_unit), ht = metres_per_unit(height_unit);
  std::ofstream out = open_for_writing(path);
  out << "# rockjoint XYZ point list on a regular lattice\n"
      << "# lateral_unit: " << lateral_unit << "\n"
      << "# height_unit: " << height_unit << "\n";
  for (Eigen::Index i = 0; i < surface.rows(); ++i)
    for (Eigen::Index j = 0; j < surface.cols(); ++j)
      out << format_number(j * surface.spacing_x() / lat) << " "
          << format_number(i * surface.spacing_y() / lat) << " "
          << format_number(surface.heights()(i, j) / ht) << "\n";
  if (!out)
    throw std::runtime_error("error while writing '" + path + "'");
}

} // namespace rockjoint::topography
