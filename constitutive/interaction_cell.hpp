// SPDX-License-Identifier: MIT
#pragma once
/// @file interaction_cell.hpp
/// Closed form of the self-consistent interaction cell of Tang & Jiao (2018), Eqs. (1)-(5),
/// in the reading of theory §5.
///
/// The cell: one representative paraboloidal asperity of radius R with a *fixed* contact
/// radius a (Eq. (1)), its territory of radius b with (a/b)² = A/A0 (Eq. (2)), the annulus
/// a < r < b unloaded, and the other asperities smeared into a uniform mean pressure p̄ over
/// r > b with p̄ π b² = P, the load of the cell (Eq. (3)). Eqs. (4) and (5) are π E* times the
/// Boussinesq displacements of p on the disk a (f1) and of p̄ on the disk b (f2). Splitting
/// "p̄ outside b" into "p̄ everywhere" (a uniform bulk translation, excluded by theory §0)
/// minus "p̄ on the disk b", the contact condition inside the contact is
///
///     f1(r) - f2(r) = π E* (δ_loc - r²/(2R)),   r <= a.
///
/// For a prescribed contact radius (Sneddon / Abel) the pressure carries an edge term
/// ∝ (δ_eff - G(a))/√(a²-r²); "p̄ too large → infinite fringe pressure, too small → negative"
/// (the paper's iteration) is driving it to zero. For this cell that has a closed form:
///
///   - finite-fringe condition  δ_loc = a²/R - (2 p̄/E*) √(b²-a²)
///   - pressure  p(r) = (2E*/(πR)) √(a²-r²) + (2p̄/π) arctan √((a²-r²)/(b²-a²)),  p(a) = 0
///   - load  P = (4/3) E* a³/R + 2 p̄ [b² arcsin(a/b) - a √(b²-a²)] = P_H + P_int
///   - self-consistency p̄ π b² = P with s = a/b:  p̄ = (4 E* a/(3πR)) s² / Q(s),
///     Q(s) = (2/π)[arccos s + s √(1-s²)]  (Q(0) = 1, Q(1) = 0, 1-Q ≈ 4s³/(3π)),
///     P_int / (π b²) = (1 - Q(s)) p̄.
///
/// Variant I2 of the Tang & Jiao law (tang_jiao.hpp) shifts the closure by the interaction
/// part of δ_loc, ε = (2F/E*) √(b²-a²) (closure_shift()).
///
/// Units: SI (Pa, m, N). Header of pure functions; the paper's iterative algorithm is the
/// second implementation in interaction_cell_numeric.hpp.

namespace rockjoint::constitutive::interaction_cell
{

/// Q(s) = (2/π)[arccos s + s √(1-s²)] for s in [0, 1]: the fraction of the cell's load
/// carried by the Hertz part, P_H = Q P (theory §5). Not defined outside [0, 1] (NaN).
double load_fraction(double area_root);

/// 1 - Q(s) = (2/π)[arcsin s - s √(1-s²)], accurate for small s (series
/// (4/π) Σ c_n s^{2n+3}/(2n+3), c_n = (2n)!/(4^n n!²), for s < 0.5): 1-Q ≈ 4s³/(3π).
/// The relative interaction correction; keeps F → f3 exact as s → 0.
double interaction_fraction(double area_root);

/// dQ/ds = -(4/π) s² / √(1-s²) [-].
double load_fraction_derivative(double area_root);

/// Eq. (1): effective contact radius a = (3/4) √(π R σ_s) [m] — the Hertz radius whose
/// mean pressure 4E*a/(3πR) equals the GW-exponential mean real pressure E* √(σ_s/(πR)).
/// @param radius R [m]; @param summit_height_std σ_s [m]
double effective_contact_radius(double radius, double summit_height_std);

/// One self-consistent cell, closed form. Construct with E* [Pa], R [m], a [m] and
/// s = a/b = √(A/A0) in (0, 1). Parameters are validated (std::invalid_argument).
class Cell
{
public:
  /// @param composite_modulus E* [Pa] (1/E* = Σ (1-ν²)/E), > 0
  /// @param radius R [m] of the representative asperity, > 0
  /// @param contact_radius a [m], > 0 (Eq. (1) for Tang & Jiao)
  /// @param area_root s = a/b = √(A/A0) [-], in (0, 1) (Eq. (2))
  Cell(double composite_modulus, double radius, double contact_radius, double area_root);

  /// E* [Pa].
  double composite_modulus() const { return _modulus; }
  /// R [m] of the representative asperity.
  double radius() const { return _radius; }
  /// a [m].
  double contact_radius() const { return _a; }
  /// b = a/s [m], Eq. (2).
  double territory_radius() const { return _b; }
  /// s = a/b [-].
  double area_root() const { return _s; }

  /// Hertz mean pressure p_m = 4E*a/(3πR) [Pa] (theory §1).
  double hertz_mean_pressure() const;
  /// Self-consistent p̄ = p_m s²/Q(s) [Pa] (Eq. (3) with the finite fringe).
  double mean_pressure() const;
  /// Finite-fringe local approach δ_loc = a²/R - (2p̄/E*) √(b²-a²) [m].
  double local_approach() const;
  /// Hertz part of the load P_H = (4/3) E* a³/R [N].
  double hertz_load() const;
  /// Interaction part P_int = 2p̄ [b² arcsin(a/b) - a √(b²-a²)] [N].
  double interaction_load() const;
  /// P = P_H + P_int [N]; equals p̄ π b² (self-consistency).
  double load() const { return hertz_load() + interaction_load(); }
  /// Contact pressure p(r) [Pa] for 0 <= r <= a (0 outside [0, a]).
  double pressure(double r) const;
  /// Displacement of the surface at r >= 0 due to p̄ on the disk b (Eq. (5) / (π E*)):
  /// u2(r) = 4 p̄ b E(r/b) / (π E*) for r <= b, 4 p̄ r [E(b/r) - (1-b²/r²) K(b/r)]/(π E*)
  /// beyond [m]; E, K complete elliptic integrals (modulus convention).
  double territory_displacement(double r) const;
  /// Variant I2 closure shift of the cell, ε = (2 p̄/E*) √(b²-a²) [m] (F = p̄).
  double closure_shift() const;

private:
  double _modulus, _radius, _a, _s, _b;
};

/// √(b²-a²) = a √(1-s²)/s [m] for contact radius a and s = a/b (without forming b).
double annulus_half_chord(double contact_radius, double area_root);

/// Variant I2 closure shift ε = (2F/E*) √(b²-a²) [m] of a law with nominal stress F [Pa]
/// (theory §5: the interaction lifts each contact's surroundings by the p̄ term of δ_loc).
/// s = 0 (no territory) gives 0.
double closure_shift(double nominal_stress, double composite_modulus, double contact_radius,
                     double area_root);

} // namespace rockjoint::constitutive::interaction_cell
