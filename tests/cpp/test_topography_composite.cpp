// SPDX-License-Identifier: MIT
// Contact state and composite topography (theory §3): identical walls are flat (zero closure
// capacity), offsets register walls, planes are removed, masks propagate, the geometric
// overlap ratio counts lattice points.
#include <rockjoint/topography/closure_parameters.hpp>
#include <rockjoint/topography/composite.hpp>
#include <rockjoint/topography/overlap.hpp>
#include <rockjoint/topography/self_affine.hpp>
#include <rockjoint/topography/summits.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace rockjoint::topography;

namespace
{
Surface rough(Eigen::Index rows, Eigen::Index cols, std::uint64_t seed)
{
  return self_affine_surface({0.8, 1e-3, 0.0, 0.0}, {rows, cols, 0.5e-3, seed, true});
}
} // namespace

TEST(TopographyComposite, IdenticalWallsAreFlatWithZeroClosureCapacity)
{
  const Surface w = rough(64, 64, 3);
  const CompositeTopography c = composite_topography(w, w);
  EXPECT_EQ((c.aperture.heights() == 0.0).count(), 64 * 64) << "aperture must be identically 0";
  EXPECT_EQ((c.composite.heights() == 0.0).count(), 64 * 64);
  EXPECT_EQ(c.mean_aperture, 0.0);
  const SummitAnalysis a = analyse_summits(c.composite);
  EXPECT_EQ(a.statistics.summit_count, 0);
  EXPECT_EQ(ApertureDistribution(c.aperture).overlap_ratio(0.0), 1.0)
      << "closed from the start: every point in contact";
}

TEST(TopographyComposite, OffsetRegistersAShiftedCopy)
{
  // lower(i + oy, j + ox) = upper(i, j): in contact state (ox, oy) the walls mate exactly.
  const Surface big = rough(80, 90, 11);
  const int ox = 7, oy = -4;
  const Eigen::Index rows = 60, cols = 70;
  const HeightGrid upper = big.heights().block(10, 10, rows, cols);
  const HeightGrid lower = big.heights().block(10 + oy, 10 + ox, rows, cols);
  // lower(i, j) = big(10 + oy + i, 10 + ox + j) = upper(i + oy, j + ox): upper(i, j) faces
  // lower(i - oy, j - ox), so the mating state is (-ox, -oy).
  const Surface u(upper, 0.5e-3), l(lower, 0.5e-3);
  ContactState state;
  state.offset_x = -ox, state.offset_y = -oy;
  const CompositeTopography c = composite_topography(u, l, state);
  EXPECT_EQ(c.aperture.rows(), rows - std::abs(oy));
  EXPECT_EQ(c.aperture.cols(), cols - std::abs(ox));
  EXPECT_LT(c.aperture.heights().abs().maxCoeff(), 1e-18);
  // As scanned (no offset) they do not mate.
  const CompositeTopography c0 = composite_topography(u, l);
  EXPECT_GT(c0.mean_aperture, 1e-4);
  EXPECT_EQ(c0.aperture.rows(), rows);
}

TEST(TopographyComposite, ApertureStartsAtFirstContactAndCompositeIsItsMirror)
{
  const auto [u, l] = mated_pair({0.8, 1e-3, 0.0, 0.0}, {64, 64, 0.5e-3, 9, true}, 3e-3);
  const CompositeTopography c = composite_topography(u, l);
  const HeightGrid& e = c.aperture.heights();
  EXPECT_EQ(e.minCoeff(), 0.0);
  EXPECT_NEAR(c.mean_aperture, e.mean(), 1e-18);
  // s = mean(e) - e, so max s = mean(e) (at first contact) and mean s = 0.
  EXPECT_NEAR(c.composite.heights().maxCoeff(), c.mean_aperture, 1e-18);
  EXPECT_NEAR(c.composite.mean_height(), 0.0, 1e-18);
  // The common plane does not change the aperture: e + min(z_u - z_l) = z_u - z_l as given.
  const HeightGrid raw = u.heights() - l.heights();
  EXPECT_LT((e - (raw - raw.minCoeff())).abs().maxCoeff(), 1e-17);
  EXPECT_NEAR(c.interpenetration, -raw.minCoeff(), 1e-18);
  const SummitStatistics st = analyse_summits(c.composite).statistics;
  EXPECT_GT(st.summit_count, 10);
  const auto p = asperity_parameters(st, 20e9);
  EXPECT_EQ(p.summit_density, st.summit_density);
  EXPECT_EQ(p.composite_modulus, 20e9);
}

TEST(TopographyComposite, PlaneRemovalModes)
{
  // Upper = lower + a tilt. Common plane: the relative tilt stays in the aperture; separate
  // planes: the walls become parallel and the aperture vanishes.
  const Surface l = rough(40, 50, 4);
  HeightGrid zu = l.heights();
  for (Eigen::Index i = 0; i < zu.rows(); ++i)
    for (Eigen::Index j = 0; j < zu.cols(); ++j)
      zu(i, j) += 2e-3 + 0.01 * j * 0.5e-3 - 0.02 * i * 0.5e-3;
  const Surface u(zu, 0.5e-3);
  const CompositeTopography common = composite_topography(u, l);
  const double tilt_range = 0.01 * 49 * 0.5e-3 + 0.02 * 39 * 0.5e-3;
  EXPECT_NEAR(common.aperture.heights().maxCoeff(), tilt_range, 1e-15);
  ContactState separate;
  separate.plane_removal = PlaneRemoval::separate;
  const CompositeTopography sep = composite_topography(u, l, separate);
  EXPECT_LT(sep.aperture.heights().abs().maxCoeff(), 1e-15);
  EXPECT_NEAR(sep.upper_plane.slope_x - sep.lower_plane.slope_x, 0.01, 1e-12);
  EXPECT_NEAR(sep.upper_plane.slope_y - sep.lower_plane.slope_y, -0.02, 1e-12);
}

TEST(TopographyComposite, MasksPropagateAndAreNeverFilled)
{
  const auto [u0, l0] = mated_pair({0.8, 1e-3, 0.0, 0.0}, {32, 32, 0.5e-3, 2, true}, 2e-3);
  HeightGrid zu = u0.heights(), zl = l0.heights();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  zu(5, 6) = nan;
  zl(20, 21) = nan;
  const CompositeTopography c = composite_topography(Surface(zu, 0.5e-3), Surface(zl, 0.5e-3));
  EXPECT_TRUE(std::isnan(c.aperture.heights()(5, 6)));
  EXPECT_TRUE(std::isnan(c.aperture.heights()(20, 21)));
  EXPECT_TRUE(std::isnan(c.composite.heights()(20, 21)));
  EXPECT_EQ(c.aperture.valid_count(), 32 * 32 - 2);
  // The overlap ratio counts valid points only.
  const ApertureDistribution d(c.aperture);
  EXPECT_EQ(d.sorted_apertures().size(), std::size_t(32 * 32 - 2));
  EXPECT_DOUBLE_EQ(d.overlap_ratio(1.0), 1.0);
  EXPECT_DOUBLE_EQ(d.overlap_ratio(-1e-9), 0.0);
  EXPECT_DOUBLE_EQ(d.overlap_ratio(0.0), 1.0 / (32 * 32 - 2)) << "one first-contact point";
  // Summits next to the holes are not eligible: 30² interior points minus 9 around each hole.
  EXPECT_EQ(analyse_summits(c.composite).statistics.eligible_points, 30 * 30 - 2 * 9);
}

TEST(TopographyComposite, MismatchedGridsAndEmptyOverlapAreErrors)
{
  const Surface a = rough(16, 16, 1);
  const Surface b(a.heights(), 0.25e-3);
  try
  {
    composite_topography(a, b);
    ADD_FAILURE();
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("mismatched grids"), std::string::npos);
  }
  ContactState far;
  far.offset_x = 15;
  EXPECT_THROW(composite_topography(a, a, far), std::invalid_argument);
}
