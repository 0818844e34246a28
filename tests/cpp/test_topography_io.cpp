// SPDX-License-Identifier: MIT
// Height-grid and XYZ files: round trips with units and NaN masks, and malformed files whose
// errors must name the file and the line.
#include <rockjoint/topography/surface_io.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "expect_error.hpp"

using namespace rockjoint::topography;

namespace
{
std::string temp_file(const std::string& name, const std::string& content)
{
  const auto path = std::filesystem::temp_directory_path() / ("rockjoint_test_" + name);
  std::ofstream(path) << content;
  return path.string();
}

using rockjoint::testing::expect_error;

Surface sample_surface()
{
  HeightGrid z(3, 4);
  z << 1e-5, 2e-5, 3e-5, 4e-5, //
      -1e-5, std::numeric_limits<double>::quiet_NaN(), 0.0, 2.5e-5, //
      7e-6, 8e-6, 9e-6, 1.25e-4;
  return Surface(z, 0.5e-3, 0.25e-3);
}

void expect_same(const Surface& a, const Surface& b)
{
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.cols(), b.cols());
  EXPECT_NEAR(a.spacing_x(), b.spacing_x(), 1e-12 * a.spacing_x());
  EXPECT_NEAR(a.spacing_y(), b.spacing_y(), 1e-12 * a.spacing_y());
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j)
    {
      const double x = a.heights()(i, j), y = b.heights()(i, j);
      if (std::isnan(x))
        EXPECT_TRUE(std::isnan(y)) << "mask lost at " << i << "," << j;
      else
        EXPECT_NEAR(x, y, 1e-9 * std::abs(x) + 1e-20) << i << "," << j;
    }
}
} // namespace

TEST(TopographyIO, HeightGridRoundTripKeepsSpacingUnitsAndMask)
{
  const Surface s = sample_surface();
  const std::string path = temp_file("roundtrip.txt", "");
  write_height_grid(path, s, "mm", "um");
  const SurfaceFile f = read_height_grid(path);
  EXPECT_EQ(f.lateral_unit, "mm");
  EXPECT_EQ(f.height_unit, "um");
  expect_same(s, f.surface);
}

TEST(TopographyIO, HeightGridUnitsAreConverted)
{
  const std::string path = temp_file("units.txt", "# spacing: 20\n# lateral_unit: um\n"
                                                  "# height_unit: mm\n1 2 3\n4 nan 6\n");
  const Surface s = read_height_grid(path).surface;
  EXPECT_DOUBLE_EQ(s.spacing_x(), 20e-6);
  EXPECT_DOUBLE_EQ(s.heights()(1, 2), 6e-3);
  EXPECT_TRUE(std::isnan(s.heights()(1, 1)));
  EXPECT_EQ(s.valid_count(), 5);
}

TEST(TopographyIO, XyzRoundTripAnyOrderAndMissingPoints)
{
  const Surface s = sample_surface();
  const std::string path = temp_file("roundtrip.xyz", "");
  write_xyz(path, s, "mm", "mm");
  expect_same(s, read_xyz(path).surface);

  // Shuffled points, one lattice point absent: it becomes NaN, nothing is invented.
  const std::string p2 = temp_file("shuffled.xyz", "# lateral_unit: mm\n# height_unit: mm\n"
                                                   "1.0 0.5 3\n0 0 1\n0.5 0 2\n1.0 0 4\n"
                                                   "0 0.5 5\n");
  const Surface t = read_xyz(p2).surface;
  ASSERT_EQ(t.rows(), 2);
  ASSERT_EQ(t.cols(), 3);
  EXPECT_DOUBLE_EQ(t.heights()(0, 1), 2e-3);
  EXPECT_DOUBLE_EQ(t.heights()(1, 2), 3e-3);
  EXPECT_TRUE(std::isnan(t.heights()(1, 1)));
}

TEST(TopographyIO, RaggedRowNamesFileAndLine)
{
  const std::string path = temp_file("ragged.txt", "# spacing: 0.5\n# unit: mm\n1 2 3\n4 5\n");
  expect_error([&] { read_height_grid(path); }, {path + ":4:", "ragged row", "2 values"});
}

TEST(TopographyIO, NonNumberNamesFileLineAndToken)
{
  const std::string path = temp_file("nonnumber.txt", "# spacing: 0.5\n# unit: mm\n\n1 2 3\n"
                                                      "4 x5 6\n");
  expect_error([&] { read_height_grid(path); }, {path + ":5:", "'x5'", "not a number"});
}

TEST(TopographyIO, HeaderThatDoesNotMatchTheDataIsAMismatchedGrid)
{
  const std::string path = temp_file("mismatch.txt", "# spacing: 0.5\n# unit: mm\n# rows: 3\n"
                                                     "1 2\n3 4\n");
  expect_error([&] { read_height_grid(path); }, {path + ":3:", "mismatched grid", "rows = 3"});
}

TEST(TopographyIO, MissingSpacingOrUnitIsNamed)
{
  const std::string p1 = temp_file("nospacing.txt", "# unit: mm\n1 2\n3 4\n");
  expect_error([&] { read_height_grid(p1); }, {p1, "spacing"});
  const std::string p2 = temp_file("nounit.txt", "# spacing: 1\n1 2\n3 4\n");
  expect_error([&] { read_height_grid(p2); }, {p2, "unit"});
  // ... unless the caller supplies them.
  ReadOptions opt;
  opt.lateral_unit = "mm", opt.height_unit = "um";
  EXPECT_DOUBLE_EQ(read_height_grid(p2, opt).surface.heights()(1, 1), 4e-6);
}

TEST(TopographyIO, XyzOffLatticeAndDuplicatePointsNameTheLine)
{
  // A 3 x 3 lattice (lines 2-10) and one stray point on line 11.
  const std::string p1 = temp_file("offlattice.xyz", "# unit: mm\n0 0 1\n1 0 2\n2 0 3\n"
                                                     "0 1 4\n1 1 5\n2 1 6\n0 2 7\n1 2 8\n"
                                                     "2 2 9\n0.5 1.3 5\n");
  expect_error([&] { read_xyz(p1); }, {p1 + ":11:", "not on the regular lattice"});
  const std::string p2 = temp_file("dup.xyz", "# unit: mm\n0 0 1\n1 0 2\n0 1 3\n0 0 4\n");
  expect_error([&] { read_xyz(p2); }, {p2 + ":5:", "duplicate", "line 2"});
  const std::string p3 = temp_file("twovalues.xyz", "# unit: mm\n0 0 1\n1 0\n");
  expect_error([&] { read_xyz(p3); }, {p3 + ":3:", "expected 3 values"});
}

TEST(TopographyIO, UnreadableFileIsNamed)
{
  EXPECT_THROW(read_height_grid("/nonexistent/rockjoint.txt"), std::runtime_error);
}

// Found by fuzz/fuzz_xyz (fuzz/regressions/xyz/oom-*): one mistyped coordinate made the reader
// allocate a 13 GB lattice (and, further out, overflow the lattice indices).
TEST(TopographyIO, XyzWithAStrayCoordinateIsRefusedNotAllocated)
{
  const std::string path = temp_file("stray.xyz", "# lateral_unit: mm\n# height_unit: mm\n"
                                                   "0 0 0.3\n0.5 0 0.4\n1 0 0.2\n"
                                                   "69349422 0 0.09\n0 0.5 -0.19\n");
  expect_error([&] { read_xyz(path); },
               {path, "span a lattice of 2 x 1.38699e+08 points", "mistyped"});
  // 10 apart, one point 1e9 out: a 2 x 1e8 lattice for 4 points
  const std::string far = temp_file("far.xyz", "# unit: mm\n0 0 1\n10 0 1\n0 10 1\n1e9 10 2\n");
  expect_error([&] { read_xyz(far); }, {far, "span a lattice", "mistyped"});
}

// A circular scan in its square keeps most of its lattice: a sparse but honest lattice reads.
TEST(TopographyIO, XyzWithManyMissingPointsStillReads)
{
  std::string text = "# unit: mm\n";
  for (int k = 0; k < 10; ++k)  // 10 points on the diagonal of a 10 x 10 lattice
    text += std::to_string(k) + " " + std::to_string(k) + " 1\n";
  const SurfaceFile f = read_xyz(temp_file("diagonal.xyz", text));
  EXPECT_EQ(f.surface.rows(), 10);
  EXPECT_EQ(f.surface.cols(), 10);
}

TEST(TopographyIO, HeightGridRowCountMustBeAWholeNumber)
{
  const std::string path = temp_file("rows.txt", "# spacing: 0.5\n# unit: mm\n# rows: 1e300\n1 2\n");
  expect_error([&] { read_height_grid(path); }, {path + ":3:", "rows", "whole number"});
  const std::string half = temp_file("half.txt", "# spacing: 0.5\n# unit: mm\n# cols: 2.5\n1 2\n");
  expect_error([&] { read_height_grid(half); }, {half + ":3:", "cols", "whole number"});
}
