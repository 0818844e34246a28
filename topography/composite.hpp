// SPDX-License-Identifier: MIT
#pragma once
/// @file composite.hpp
/// Contact state and composite topography of a joint (theory §3, after Xia et al. 2003).
///
/// Both walls are given in one frame (z up; the upper wall's heights are those of its lower,
/// joint-facing face). In the chosen contact state the lower wall is registered with a
/// relative offset, a least-squares plane is removed, and the aperture e = z_u - z_l is
/// shifted so that min e = 0 (first contact). The composite surface s = mean(e) - e carries
/// all the roughness the closure law sees: its summits are the aperture minima, and it is
/// the surface of the equivalent "rough wall against a flat" of GW.

#include "plane.hpp"
#include "surface.hpp"

namespace rockjoint::topography
{

/// How the mean plane is removed before the aperture is formed.
enum class PlaneRemoval : int
{
  common = 0,   ///< one plane fitted to both walls together, subtracted from both (default:
                ///< the relative tilt is part of the contact state, e is unchanged)
  separate = 1, ///< each wall its own plane (walls scanned separately: makes them parallel)
  none = 2,     ///< heights used as given
};

/// The relative position of the two walls.
struct ContactState
{
  /// Upper point (i, j) faces lower point (i + offset_y, j + offset_x): the lower wall is
  /// moved by (-offset_x·h_x, -offset_y·h_y). (0, 0) = as scanned ("perfectly mated" for a
  /// mated pair). Only the overlap of the two grids is kept.
  int offset_x = 0; ///< [grid steps]
  int offset_y = 0; ///< [grid steps]
  PlaneRemoval plane_removal = PlaneRemoval::common; ///< how the mean planes are removed
};

/// The registered walls and the fields derived from them, on the overlap lattice.
struct CompositeTopography
{
  Surface upper;           ///< upper wall after registration and plane removal [m]
  Surface lower;           ///< lower wall, registered, plane removed [m]
  Surface aperture;        ///< e = z_u - z_l - min(z_u - z_l) >= 0, NaN where either is missing [m]
  Surface composite;       ///< s = mean(e) - e [m]; max s = mean(e) at the first contact
  double mean_aperture;    ///< mean(e) [m] = the largest closure the walls admit
  double interpenetration; ///< -min(z_u - z_l) before the shift [m] (> 0: walls overlap as given)
  Plane upper_plane;       ///< plane removed from the upper wall
  Plane lower_plane;       ///< plane removed from the lower wall (in the overlap frame)
  ContactState state; ///< the relative position used
};

/// Register `upper` and `lower` in `state` and build the composite topography. Throws
/// std::invalid_argument for different spacings ("mismatched grids"), an empty overlap or
/// no point valid on both walls.
CompositeTopography composite_topography(const Surface& upper, const Surface& lower,
                                         const ContactState& state = {});

} // namespace rockjoint::topography
