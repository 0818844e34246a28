// SPDX-License-Identifier: MIT
#pragma once
/// @file interaction_cell_numeric.hpp
/// The paper's iterative algorithm for the interaction cell of Tang & Jiao (2018), Fig. 2:
/// the second, numerical implementation of interaction_cell.hpp. It generalises to
/// non-paraboloidal asperities; the pair is a speed-versus-error datum (bench/).
///
/// Contact problem (theory §5). Inside the contact r <= a the Boussinesq displacements of
/// Eq. (4) (f1: p on the disk a) and Eq. (5) (f2: p̄ on the disk b) satisfy
///
///     f1(r)/(πE*) = δ_loc - r²/(2R) + f2(r)/(πE*),
///
/// i.e. a frictionless punch of prescribed contact radius a, approach δ' = δ_loc + u2(0) and
/// effective profile f(r) = r²/(2R) + u2(0) - u2(r), u2 = f2/(πE*) = 4p̄bE(r/b)/(πE*)
/// (closed form of Eq. (5), complete elliptic integral E). The Sneddon / Abel reduction
/// G(x) = x ∫_0^{π/2} f'(x sin φ) dφ turns it into one-dimensional integrals:
///
///   - edge (fringe) coefficient  δ' - G(a): the pressure carries
///     (E*/π)(δ' - G(a))/√(a²-r²): > 0 → infinite fringe pressure, < 0 → tensile fringe;
///   - pressure  p(r) = (E*/π) ∫_0^{√(a²-r²)} G'(t)/t dw,  t = √(r²+w²)   (zero at r = a);
///   - load  P = 2E* ∫_0^a (G(a) - G(x)) dx.
///
/// All integrands are analytic on their closed intervals (a < b), so Gauss-Legendre rules of
/// `quadrature_order` nodes converge spectrally. The algorithm, as in the paper:
///   1. for a trial local approach δ_loc, a bracketed root find on p̄ (Illinois steps of the
///      shared root finder, root_finding.hpp) drives the edge coefficient to zero ("p̄ too
///      large → fringe pressure blows up, too small → negative");
///   2. an outer bracketed root find on δ_loc enforces self-consistency p̄ π b² = P (Eq. (3)).
/// The displacement fields of a unit p̄ are computed once per cell (influence coefficients),
/// so each root-finder step is cheap.
///
/// disk_displacement() evaluates Eq. (4) itself by adaptive quadrature: an independent check
/// that a pressure solves the contact condition.

#include <functional>

namespace rockjoint::constitutive::interaction_cell
{

/// Result of the paper's algorithm for one cell.
struct NumericSolution
{
  double mean_pressure = 0.0;  ///< p̄ [Pa]
  double local_approach = 0.0; ///< δ_loc [m]
  double load = 0.0;           ///< P [N]
  double hertz_load = 0.0;     ///< P_H [N] (p̄-independent part of P)
  double edge_coefficient = 0.0; ///< δ' - G(a) [m] at the solution (≈ 0)
  int outer_iterations = 0;    ///< root-finder iterations on δ_loc (self-consistency)
  int inner_iterations = 0;    ///< root-finder iterations on p̄ (finite fringe), summed
  bool converged = false; ///< both root finds met their tolerances
};

/// Numerical solution of one self-consistent cell.
class NumericCell
{
public:
  /// @param composite_modulus E* [Pa], > 0
  /// @param radius R [m], > 0
  /// @param contact_radius a [m], > 0
  /// @param area_root s = a/b [-], in (0, 1)
  /// @param quadrature_order Gauss-Legendre nodes per one-dimensional integral, in [4, 512]
  /// Solves at construction (throws std::invalid_argument for bad parameters only).
  NumericCell(double composite_modulus, double radius, double contact_radius, double area_root,
              int quadrature_order = 32);

  /// The solution found at construction.
  const NumericSolution& solution() const { return _solution; }
  /// b = a/s [m].
  double territory_radius() const { return _b; }

  /// Edge coefficient δ' - G(a) [m] for a trial (δ_loc [m], p̄ [Pa]).
  double edge_coefficient(double local_approach, double mean_pressure) const;
  /// Load P [N] of the finite-fringe pressure for exterior mean pressure p̄ [Pa].
  double load(double mean_pressure) const;
  /// Contact pressure p(r) [Pa] at the solution, 0 <= r <= a (0 outside).
  double pressure(double r) const;

private:
  /// G2(x)/p̄: the p̄ part of Sneddon's G for the profile -u2 [m/Pa].
  double interaction_g(double x) const;
  /// (1/t) dG2/dt per unit p̄ [1/(Pa m)].
  double interaction_g_rate_over_t(double t) const;

  double _modulus, _radius, _a, _s, _b;
  int _order;
  double _g_edge;  ///< G2(a)/p̄
  double _load_rate; ///< dP/dp̄ = 2E* ∫_0^a (G2(a) - G2(x)) dx / p̄ [m²]
  NumericSolution _solution;
};

/// Surface displacement u(r) = f1(r)/(πE*) [m] of Eq. (4): axisymmetric pressure p(ρ) [Pa]
/// on the disk ρ <= a [m], u(r) = (1/(πE*)) ∫_0^a p(ρ) ρ ∫_0^{2π} dθ/√(ρ²+r²-2rρ cos θ) dρ,
/// the θ-integral in closed form 4K(2√(ρr)/(ρ+r))/(ρ+r); adaptive quadrature (GSL QAGP)
/// with the log singularity at ρ = r as a break point. Returns NaN if the quadrature fails
/// to reach `relative_tolerance`.
double disk_displacement(const std::function<double(double)>& pressure, double contact_radius,
                         double composite_modulus, double r, double relative_tolerance = 1e-10);

} // namespace rockjoint::constitutive::interaction_cell
