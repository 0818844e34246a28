// SPDX-License-Identifier: MIT
#pragma once
/// @file law_table_file.hpp
/// The data of a tabulated closure law and its file format (".rjt", text, version 1).
///
/// A table is tabulated once (possibly from an expensive law) and imported elsewhere, so the
/// file is self-describing: units, interpolation and extension rules, the source model's
/// name and every parameter, the requested tolerance and the error the builder checked,
/// the range, and the knots. Every number is written as a C99 hexadecimal float ("%a",
/// e.g. 0x1.4p+4) so a save/load round trip is bit-exact; a decimal copy in MPa and mm
/// follows each line after '#' for people (ignored on reading).
///
/// Layout (one record a line; '#' starts a comment; fields separated by blanks):
///
///     rockjoint-law-table 1
///     units closure=m stress=Pa stiffness=Pa/m
///     interpolation monotone_hermite_sqrt_first_segment
///     compression_extension linear_end_tangent
///     opening_extension residual_stiffness
///     source_model <name>
///     source_seating_stress <hex> Pa
///     source_parameter <name> <hex> <unit or ->        (zero or more)
///     tolerance <hex>
///     checked_error_stress <hex>
///     checked_error_stiffness <hex>
///     residual_stiffness <hex> Pa/m
///     table_maximum_closure <hex> m                    (range; must equal the last knot's)
///     table_maximum_stress <hex> Pa                    (range; must equal the last knot's)
///     knots <n>
///     knot <i> <Δ hex> <σ hex> <k hex>                 (n lines, i = 0..n-1; knot 0:
///                                                       Δ = σ = 0, k = k(0+))
///     end
///
/// Names and units are written as one field each: blanks, '#', '%' and non-printable bytes
/// as %XX escapes, the empty string as "-".
/// Header records may come in any order but all are required; knots follow `knots` and the
/// file ends with `end` (a truncated file is detected). Reading fails with a
/// std::runtime_error naming the file, the line and the field.

#include "closure_law.hpp"

#include <string>
#include <vector>

namespace rockjoint::constitutive
{

/// Everything that defines a tabulated law (monotone_hermite.hpp gives the interpolant).
struct LawTable
{
  std::string source_model;               ///< ClosureLaw::name() of the source
  std::vector<Parameter> source_parameters; ///< ClosureLaw::parameters() of the source (SI)
  double source_seating_stress = 0.0;     ///< ClosureLaw::seating_stress() of the source [Pa]
  double tolerance = 0.0;                 ///< requested max relative error of σ and k [-]
  double checked_error_stress = 0.0;      ///< largest relative σ error found by the builder
  double checked_error_stiffness = 0.0;   ///< largest relative k error found by the builder
  double residual_stiffness = 0.0;        ///< k_res [Pa/m] of the opening branch (>= 0)
  std::vector<double> closure;            ///< knots Δ_i [m], Δ_0 = 0, increasing
  std::vector<double> normal_stress;      ///< σ_i [Pa], σ_0 = 0, increasing
  /// k_i = dσ/dΔ [Pa/m] at the knots (the source's, limited to monotone); k_0 = k(0+)
  /// (0 for a Hertzian Δ^{3/2} onset).
  std::vector<double> stiffness;
};

/// Format identifiers of version 1.
namespace law_table_format
{
/// First word of a table file.
inline constexpr const char* magic = "rockjoint-law-table";
/// Format version this library writes and reads.
inline constexpr int version = 1;
/// Interpolant between the knots (monotone_hermite.hpp).
inline constexpr const char* interpolation = "monotone_hermite_sqrt_first_segment";
/// Beyond the last knot: linear with the end tangent.
inline constexpr const char* compression_extension = "linear_end_tangent";
/// For Δ <= 0: the residual stiffness.
inline constexpr const char* opening_extension = "residual_stiffness";
} // namespace law_table_format

/// Check the knots of `table`: at least 2, finite, Δ_0 = σ_0 = 0, Δ and σ strictly
/// increasing, stiffnesses >= 0 and every segment monotone (Fritsch-Carlson disc; the
/// quartic first segment by its own test), tolerance in (0, 1), residual stiffness finite
/// and >= 0. Throws std::invalid_argument naming `owner`,
/// the knot index and the field.
void validate_law_table(const LawTable& table, const std::string& owner);

/// Write `table` to `path` (format version 1). Throws std::runtime_error if the file
/// cannot be written.
void write_law_table(const std::string& path, const LawTable& table);

/// Read a table written by write_law_table. Throws std::runtime_error naming the file, the
/// line and the field for a missing, foreign, truncated, wrong-version or corrupt file.
LawTable read_law_table(const std::string& path);

} // namespace rockjoint::constitutive
