// SPDX-License-Identifier: MIT
#pragma once
/// @file elasticity.hpp
/// Composite (contact) modulus of two elastic walls, theory §1.
///
/// 1/E* = (1-ν1²)/E1 + (1-ν2²)/E2. Two walls of one rock: E* = E / (2(1-ν²)).
/// Note: some papers call E/(1-ν²) "E'" (plane-strain modulus of ONE wall); every API of
/// this library that takes a modulus of contact takes E* as defined here and says so.

namespace rockjoint::constitutive
{

/// E* [Pa] of two walls with Young's moduli E1, E2 [Pa] and Poisson ratios ν1, ν2 [-].
/// Throws std::invalid_argument for E <= 0 or ν outside (-1, 0.5].
double composite_modulus(double young1, double poisson1, double young2, double poisson2);

/// E* [Pa] of two walls of the same rock (E [Pa], ν [-]).
double composite_modulus(double young, double poisson);

} // namespace rockjoint::constitutive
