// SPDX-License-Identifier: MIT
#include "law_table_file.hpp"
#include "monotone_hermite.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace rockjoint::constitutive
{

namespace
{
namespace fmt = law_table_format;

/// Hexadecimal float with a 0x prefix, locale-independent (to_chars), exact.
std::string hex(double x)
{
  if (std::isnan(x))
    return "nan";
  if (std::isinf(x))
    return x > 0 ? "inf" : "-inf";
  char buffer[64];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, std::abs(x),
                                 std::chars_format::hex);
  std::string digits(buffer, end);
  return (std::signbit(x) ? "-0x" : "0x") + digits;
}

/// Parse a token written by hex() (also "nan", "inf": rejected later with a clear message).
bool parse_hex(const std::string& token, double& value)
{
  std::string s = token;
  bool negative = false;
  if (!s.empty() && (s[0] == '-' || s[0] == '+'))
  {
    negative = s[0] == '-';
    s.erase(0, 1);
  }
  if (s == "nan" || s == "inf")
  {
    value = s == "nan" ? std::nan("") : HUGE_VAL;
    value = negative ? -value : value;
    return true;
  }
  if (s.size() < 3 || s[0] != '0' || (s[1] != 'x' && s[1] != 'X'))
    return false;
  const char* first = s.data() + 2;
  const char* last = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(first, last, value, std::chars_format::hex);
  if (ec != std::errc() || ptr != last)
    return false;
  value = negative ? -value : value;
  return true;
}

/// A string as one blank-free field: '%' escapes (%20 blank, %23 '#', %25 '%', ...) for
/// every byte that is not printable ASCII or is blank/'#'/'%'; "-" stands for "".
std::string encode(const std::string& text)
{
  if (text.empty())
    return "-";
  static const char* digits = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : text)
  {
    if (c > 32 && c < 127 && c != '#' && c != '%' && !(text == "-" && c == '-'))
      out += static_cast<char>(c);
    else
    {
      out += '%';
      out += digits[c >> 4];
      out += digits[c & 15];
    }
  }
  return out;
}

/// Inverse of encode(); false for a malformed escape.
bool decode(const std::string& field, std::string& text)
{
  text.clear();
  if (field == "-")
    return true;
  for (std::size_t i = 0; i < field.size(); ++i)
  {
    if (field[i] != '%')
    {
      text += field[i];
      continue;
    }
    if (i + 2 >= field.size())
      return false;
    // Unsigned: from_chars into a signed int would accept "%-1" as a byte.
    unsigned value = 0;
    auto [ptr, ec] = std::from_chars(field.data() + i + 1, field.data() + i + 3, value, 16);
    if (ec != std::errc() || ptr != field.data() + i + 3)
      return false;
    text += static_cast<char>(value);
    i += 2;
  }
  return true;
}

std::string decimal(double x, int digits = 9)
{
  std::ostringstream s;
  s.precision(digits);
  s << x;
  return s.str();
}

/// What is wrong with knot i of `table` given knots 0..i-1 (empty if nothing).
std::string knot_problem(const LawTable& table, std::size_t i)
{
  const double x = table.closure[i], s = table.normal_stress[i], k = table.stiffness[i];
  if (!std::isfinite(x) || !std::isfinite(s) || !std::isfinite(k))
    return "closure, normal_stress and stiffness must be finite (got " + decimal(x) + ", "
           + decimal(s) + ", " + decimal(k) + ")";
  if (k < 0.0)
    return "stiffness " + decimal(k) + " must be >= 0";
  if (i == 0)
    return x == 0.0 && s == 0.0 ? "" : "the first knot must be closure 0 with normal_stress 0";
  if (!(x > table.closure[i - 1]))
    return "closure is not greater than the previous knot's (knots must be strictly "
           "increasing)";
  if (!(s > table.normal_stress[i - 1]))
    return "normal_stress is not greater than the previous knot's (knots must be strictly "
           "increasing)";
  if (i == 1
      && !hermite::first_segment_is_monotone(
          hermite::make_first_segment(x, s, k, table.stiffness[0])))
    return "the first segment (knots 0 and 1) is not monotone";
  if (i > 1
      && !hermite::is_monotone(table.closure[i - 1], x, table.normal_stress[i - 1], s,
                               table.stiffness[i - 1], k))
    return "stiffnesses violate the monotonicity condition α² + β² <= 9 (Fritsch-Carlson)";
  return "";
}

/// Error naming the file and, if given, the line.
[[noreturn]] void fail(const std::string& path, std::size_t line, const std::string& what)
{
  std::ostringstream msg;
  msg << "law table file '" << path << "'";
  if (line > 0)
    msg << ", line " << line;
  msg << ": " << what;
  throw std::runtime_error(msg.str());
}

/// One meaningful line: its number and its blank-separated fields (comments removed).
struct Record
{
  std::size_t line;
  std::vector<std::string> fields;
};

std::vector<Record> read_records(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
    fail(path, 0, "cannot be opened for reading");
  std::vector<Record> records;
  std::string text;
  for (std::size_t line = 1; std::getline(in, text); ++line)
  {
    if (auto hash = text.find('#'); hash != std::string::npos)
      text.erase(hash);
    std::istringstream words(text);
    Record r{line, {}};
    for (std::string w; words >> w;)
      r.fields.push_back(w);
    if (!r.fields.empty())
      records.push_back(std::move(r));
  }
  return records;
}

} // namespace

void validate_law_table(const LawTable& table, const std::string& owner)
{
  const std::size_t n = table.closure.size();
  auto bad = [&](const std::string& what)
  { throw std::invalid_argument(owner + ": invalid table: " + what); };
  if (n < 2)
    bad("it needs at least 2 knots, it has " + std::to_string(n));
  if (table.normal_stress.size() != n || table.stiffness.size() != n)
    bad("closure, normal_stress and stiffness must have the same length");
  if (!(table.tolerance > 0.0 && table.tolerance < 1.0))
    bad("tolerance = " + decimal(table.tolerance) + " must be in (0, 1)");
  if (!(std::isfinite(table.residual_stiffness) && table.residual_stiffness >= 0.0))
    bad("residual_stiffness = " + decimal(table.residual_stiffness)
        + " Pa/m must be finite and >= 0");
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::string at = "knot " + std::to_string(i) + ": ";
    if (const std::string why = knot_problem(table, i); !why.empty())
      bad(at + why);
  }
}

void write_law_table(const std::string& path, const LawTable& table)
{
  validate_law_table(table, "write_law_table('" + path + "')");
  std::ofstream out(path);
  if (!out)
    fail(path, 0, "cannot be opened for writing");
  const double dmax = table.closure.back();
  out << fmt::magic << ' ' << fmt::version << '\n'
      << "# Tabulated rock-joint closure law written by rockjoint. Numbers are hexadecimal\n"
      << "# floats (exact); the decimal values after '#' are in MPa and mm, for reading only.\n"
      << "units closure=m stress=Pa stiffness=Pa/m\n"
      << "interpolation " << fmt::interpolation
      << "  # cubic Hermite in closure with the knot stiffnesses; first\n"
         "# segment [0, closure_1] a quartic in sqrt(closure) with k(0+) = knot 0 stiffness\n"
      << "compression_extension " << fmt::compression_extension
      << "  # closure > last knot: sigma = sigma_n + k_n (closure - closure_n)\n"
      << "opening_extension " << fmt::opening_extension
      << "  # closure <= 0: sigma = residual_stiffness * closure\n"
      << "source_model " << encode(table.source_model) << '\n'
      << "source_seating_stress " << hex(table.source_seating_stress) << " Pa  # "
      << decimal(table.source_seating_stress * 1e-6) << " MPa\n";
  for (const Parameter& p : table.source_parameters)
    out << "source_parameter " << encode(p.name) << ' ' << hex(p.value) << ' ' << encode(p.unit)
        << "  # " << decimal(p.value, 17) << '\n';
  out << "tolerance " << hex(table.tolerance) << "  # " << decimal(table.tolerance) << '\n'
      << "checked_error_stress " << hex(table.checked_error_stress) << "  # "
      << decimal(table.checked_error_stress, 3) << '\n'
      << "checked_error_stiffness " << hex(table.checked_error_stiffness) << "  # "
      << decimal(table.checked_error_stiffness, 3) << '\n'
      << "residual_stiffness " << hex(table.residual_stiffness) << " Pa/m  # "
      << decimal(table.residual_stiffness * 1e-9) << " MPa/mm\n"
      << "table_maximum_closure " << hex(dmax) << " m  # table range: closure 0 .. "
      << decimal(dmax * 1e3) << " mm\n"
      << "table_maximum_stress " << hex(table.normal_stress.back()) << " Pa  # stress 0 .. "
      << decimal(table.normal_stress.back() * 1e-6) << " MPa\n"
      << "knots " << table.closure.size() << '\n'
      << "# knot i  closure[m]  normal_stress[Pa]  stiffness[Pa/m]"
         "  # closure[mm] stress[MPa] stiffness[MPa/mm]\n";
  for (std::size_t i = 0; i < table.closure.size(); ++i)
  {
    const double x = table.closure[i], sg = table.normal_stress[i], k = table.stiffness[i];
    out << "knot " << i << ' ' << hex(x) << ' ' << hex(sg) << ' ' << hex(k) << "  # "
        << decimal(x * 1e3) << ' ' << decimal(sg * 1e-6) << ' ' << decimal(k * 1e-9) << '\n';
  }
  out << "end\n";
  if (!out.flush())
    fail(path, 0, "write failed");
}

LawTable read_law_table(const std::string& path)
{
  const std::vector<Record> records = read_records(path);
  if (records.empty())
    fail(path, 0, "is empty; expected a rockjoint law table");

  // Magic and version.
  const Record& first = records.front();
  if (first.fields[0] != fmt::magic)
    fail(path, first.line,
         "not a rockjoint law table: it starts with '" + first.fields[0] + "', expected '"
             + fmt::magic + " " + std::to_string(fmt::version) + "'");
  if (first.fields.size() != 2 || first.fields[1] != std::to_string(fmt::version))
    fail(path, first.line,
         "unsupported format version '" + (first.fields.size() > 1 ? first.fields[1] : "")
             + "'; this build reads version " + std::to_string(fmt::version));

  LawTable table;
  std::map<std::string, std::size_t> seen; // header field -> line
  auto number = [&](const Record& r, std::size_t field, const std::string& what)
  {
    double value;
    if (r.fields.size() <= field)
      fail(path, r.line, "field '" + what + "' is missing");
    if (!parse_hex(r.fields[field], value))
      fail(path, r.line,
           "field '" + what + "' = '" + r.fields[field] + "' is not a hexadecimal float");
    if (!std::isfinite(value))
      fail(path, r.line, "field '" + what + "' is " + r.fields[field] + "; it must be finite");
    return value;
  };
  auto word = [&](const Record& r, const std::string& expected)
  {
    const std::string got = r.fields.size() > 1 ? r.fields[1] : "";
    if (got != expected || r.fields.size() != 2)
      fail(path, r.line,
           "field '" + r.fields[0] + "' is '" + got + "'; this reader supports '" + expected
               + "'");
  };

  std::size_t k = 1;
  std::size_t knot_count = 0;
  double range_closure = 0.0, range_stress = 0.0; // checked against the last knot
  for (; k < records.size(); ++k)
  {
    const Record& r = records[k];
    const std::string& key = r.fields[0];
    if (key != "source_parameter" && !seen.emplace(key, r.line).second)
      fail(path, r.line, "field '" + key + "' appears twice");
    if (key == "units")
    {
      const std::vector<std::string> expected{"units", "closure=m", "stress=Pa",
                                              "stiffness=Pa/m"};
      if (r.fields != expected)
        fail(path, r.line, "field 'units' must be 'closure=m stress=Pa stiffness=Pa/m' (SI)");
    }
    else if (key == "interpolation")
      word(r, fmt::interpolation);
    else if (key == "compression_extension")
      word(r, fmt::compression_extension);
    else if (key == "opening_extension")
      word(r, fmt::opening_extension);
    else if (key == "source_model")
    {
      if (r.fields.size() != 2)
        fail(path, r.line, "field 'source_model' needs exactly one name");
      if (!decode(r.fields[1], table.source_model))
        fail(path, r.line, "field 'source_model' has a malformed %-escape");
    }
    else if (key == "source_seating_stress")
      table.source_seating_stress = number(r, 1, key);
    else if (key == "source_parameter")
    {
      if (r.fields.size() != 4)
        fail(path, r.line, "field 'source_parameter' needs a name, a value and a unit");
      Parameter p;
      if (!decode(r.fields[1], p.name) || !decode(r.fields[3], p.unit))
        fail(path, r.line, "field 'source_parameter' has a malformed %-escape");
      p.value = number(r, 2, "source_parameter " + r.fields[1]);
      table.source_parameters.push_back(p);
    }
    else if (key == "tolerance")
      table.tolerance = number(r, 1, key);
    else if (key == "checked_error_stress")
      table.checked_error_stress = number(r, 1, key);
    else if (key == "checked_error_stiffness")
      table.checked_error_stiffness = number(r, 1, key);
    else if (key == "residual_stiffness")
      table.residual_stiffness = number(r, 1, key);
    else if (key == "table_maximum_closure")
      range_closure = number(r, 1, key);
    else if (key == "table_maximum_stress")
      range_stress = number(r, 1, key);
    else if (key == "knots")
    {
      long long n = -1;
      if (r.fields.size() == 2)
      {
        const std::string& s = r.fields[1];
        auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), n);
        if (ec != std::errc() || ptr != s.data() + s.size())
          n = -1;
      }
      if (n < 2)
        fail(path, r.line, "field 'knots' must be a knot count >= 2");
      knot_count = static_cast<std::size_t>(n);
      ++k;
      break;
    }
    else
      fail(path, r.line, "unknown field '" + key + "'");
  }
  for (const char* required :
       {"units", "interpolation", "compression_extension", "opening_extension", "source_model",
        "source_seating_stress", "tolerance", "checked_error_stress",
        "checked_error_stiffness", "residual_stiffness", "table_maximum_closure",
        "table_maximum_stress", "knots"})
  {
    if (!seen.count(required))
      fail(path, 0, std::string("missing field '") + required + "'");
  }

  // Knots, each checked where it is read so the message names its line.
  for (std::size_t i = 0; i < knot_count; ++i, ++k)
  {
    if (k >= records.size())
      fail(path, records.back().line,
           "truncated: expected " + std::to_string(knot_count) + " knots, found "
               + std::to_string(i));
    const Record& r = records[k];
    const std::string name = "knot " + std::to_string(i);
    if (r.fields[0] != "knot" || r.fields.size() != 5 || r.fields[1] != std::to_string(i))
      fail(path, r.line,
           "expected '" + name + " <closure> <normal_stress> <stiffness>', found '"
               + r.fields[0] + (r.fields.size() > 1 ? " " + r.fields[1] : "") + " ...'");
    table.closure.push_back(number(r, 2, name + " closure"));
    table.normal_stress.push_back(number(r, 3, name + " normal_stress"));
    table.stiffness.push_back(number(r, 4, name + " stiffness"));
    if (const std::string why = knot_problem(table, i); !why.empty())
      fail(path, r.line, name + ": " + why);
  }
  if (k >= records.size())
    fail(path, records.back().line, "truncated: the closing 'end' line is missing");
  if (records[k].fields.size() != 1 || records[k].fields[0] != "end")
    fail(path, records[k].line,
         "expected 'end' after " + std::to_string(knot_count) + " knots, found '"
             + records[k].fields[0] + "'");
  if (k + 1 < records.size())
    fail(path, records[k + 1].line, "unexpected content after 'end'");
  // The stated range must be the last knot's (a self-consistency check of the file).
  if (range_closure != table.closure.back())
    fail(path, seen["table_maximum_closure"],
         "field 'table_maximum_closure' = " + decimal(range_closure, 17)
             + " m disagrees with the last knot's closure " + decimal(table.closure.back(), 17));
  if (range_stress != table.normal_stress.back())
    fail(path, seen["table_maximum_stress"],
         "field 'table_maximum_stress' = " + decimal(range_stress, 17)
             + " Pa disagrees with the last knot's stress "
             + decimal(table.normal_stress.back(), 17));

  try
  {
    validate_law_table(table, "law table file '" + path + "'");
  }
  catch (const std::invalid_argument& e)
  {
    throw std::runtime_error(e.what());
  }
  return table;
}

} // namespace rockjoint::constitutive
