// SPDX-License-Identifier: MIT
#pragma once
/// @file contact_set.hpp
/// The contact set of a contact solution and the gap field it implies (docs/contact.md): one
/// definition for the elastic and the elastic-plastic solvers, read by everything downstream
/// (the contact-area ratio, the contact spots, the flow's closed cells, flow/reynolds_flow.hpp).
///
/// Why: the solvers meet g = 0 on the points that carry pressure only to their tolerance, so the
/// gap e - d + K p left there is 1e-16 to 1e-11 m, not 0 (issue 39: half the contact area of a
/// tight joint). Such a point is closed (the walls touch), and a flow model that read its
/// residual as an aperture would put a conductance 1e30 times below the open cells' into the
/// pressure system. The contact set is the solver's own active set: the points with p > 0, and
/// the points without pressure whose gap is <= 0 (overlapping within the tolerance: the next
/// iteration would put them in contact). The gap is exactly 0 there and g > 0 everywhere else.
#include <cstddef>
#include <span>
#include <vector>

namespace rockjoint::contact
{

/// The contact set of a contact solution and its gap field (file comment: why one definition).
struct ContactSet
{
  std::vector<unsigned char> member; ///< 1 on the contact set (0 where masked)
  std::size_t count = 0;             ///< its number of points
};

/// The contact set of pressure p [Pa] and gap g = e - d + K p [m] on the valid points.
ContactSet contact_set(std::span<const double> pressure, std::span<const double> gap,
                       std::span<const unsigned char> valid);

/// The gap field [m]: exactly 0 on the contact set, g elsewhere (> 0 there), NaN where masked.
std::vector<double> gap_field(std::span<const double> gap, const ContactSet& contact,
                              std::span<const unsigned char> valid);

/// Number of 4-connected spots of the contact set of a rows x cols grid (wrapping at the edges
/// if `periodic`).
int count_patches(std::span<const unsigned char> member, std::size_t rows, std::size_t cols,
                  bool periodic);

} // namespace rockjoint::contact
