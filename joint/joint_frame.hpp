// SPDX-License-Identifier: MIT
#pragma once
/// @file joint_frame.hpp
/// The local frame of a joint plane, (n, t1[, t2]): the one rule the discrete joint element
/// (fem_coupling::set_tangents, per facet) and the equivalent continuum (per smeared set) share,
/// so that a smeared set's shear axes are those its discrete joints would have.

#include <array>

namespace rockjoint::joint
{

/// Rows n, t1, t2 of a joint frame; columns x, y, z. Unused entries (2D) are zero.
using JointFrame = std::array<std::array<double, 3>, 3>;

/// Frame of the joint plane with unit normal `normal`:
/// - 2D: t1 = n rotated by -90°, (n_y, -n_x) (a horizontal joint with n = +y has t1 = +x);
///   one rule for every facet, so t1 is continuous along a joint whose normals are.
/// - 3D: t1 = the projection of `reference` on the plane, normalised; t2 = n × t1, so
///   (n, t1, t2) is right-handed. A plane whose normal lies within 1e-3 rad of `reference`
///   uses the coordinate axis least aligned with n instead (t1 would be ill-defined).
/// The shear response of joint_response() is isotropic in the plane, so t1 changes no result;
/// it fixes the direction the reported shear components refer to.
/// Throws std::invalid_argument for a reference that is not finite or is zero (3D).
JointFrame joint_frame(int gdim, const std::array<double, 3>& normal,
                       const std::array<double, 3>& reference = {1.0, 0.0, 0.0});

} // namespace rockjoint::joint
