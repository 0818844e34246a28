// SPDX-License-Identifier: MIT
#pragma once
/// @file elastic_contact.hpp
/// Exact (to discretisation) frictionless elastic contact of a joint's composite topography:
/// the reference every closure law is measured against (docs/contact.md).
///
/// Aperture e(x) >= 0 on the grid (shifted so that min e = 0: first contact), rigid approach
/// d, gap g = e - d + u >= 0, pressure p >= 0, p g = 0, mean of p over the scanned points = σ,
/// u = K p (half_space.hpp). Solved at prescribed σ by the constrained conjugate gradients of
/// Polonsky & Keer (1999), warm-started from the previous load.
///
/// Datum of the reported closure: the change of the mean aperture from first contact,
/// Δ = mean(e) - mean(g) = d - mean(u) over the scanned points, net of the bulk deformation the
/// blocks of a model already carry (theory §0). Periodic kernel: mean(u) = 0, so the closure is
/// d itself. Non-periodic kernel: d also contains the patch's own deformation mean(u) = mean(K p)
/// under the actual pressure, which is subtracted (the raw d is reported as `approach`).
/// Masked (NaN) points carry no pressure and are not counted in A0: a hole in the scan is a
/// point that cannot touch.
#include "half_space.hpp"

#include <rockjoint/topography/surface.hpp>

#include <span>
#include <string>
#include <utility>
#include <vector>

namespace rockjoint::contact
{

/// Stopping rule of the contact solver.
struct ContactOptions
{
  /// Σ|p - p_prev| / Σ p between iterations at which a load is converged (Polonsky-Keer).
  double tolerance = 1e-8;
  int maximum_iterations = 2000; ///< iterations per load, > 0
  /// Time the phases of every load (ContactState::profile). Off, no clock is read: the timers
  /// are a branch per phase, nothing measurable against a transform of milliseconds.
  bool profile = false;
};

/// Where one load's wall time went, in seconds (ContactOptions::profile; zeros otherwise, but
/// the two counts, which are always kept). The phases are consecutive laps of one clock, so
/// they add up to `wall`.
struct ContactProfile
{
  double wall = 0.0;        ///< the whole ElasticContact::solve call
  double start = 0.0;       ///< warm or cold start, the first contact set (full-grid passes)
  double transforms = 0.0;  ///< u = K p and K t by FFT (HalfSpace::displacement), final u included
  double direct_sums = 0.0; ///< K t on a small contact set, summed directly
  /// per iteration: the interpenetration scan and the carried update of u (K c of the few points
  /// that clamping and entering changed included)
  double grid_passes = 0.0;
  double contact_set = 0.0; ///< per iteration: the CG algebra on the contact set's list
  double final_state = 0.0; ///< after convergence: gap, complementarity, contact set, spots, fields
  int transform_pairs = 0;  ///< HalfSpace::displacement calls (one forward + inverse pair each)
  int carried_updates = 0;  ///< iterations whose u = K p was carried without a transform
};

/// The contact at one nominal stress.
struct ContactState
{
  double mean_pressure = 0.0; ///< σ [Pa], the prescribed mean of p over the scanned points
  double approach = 0.0;      ///< d [m], rigid approach from first contact (raw)
  double closure = 0.0;       ///< Δ [m], d net of the bulk deformation (see file comment)
  /// A/A0: fraction of the scanned points in the contact set (contact_set.hpp). Biased upward
  /// by about one node row at the edges of every contact spot (a node is in or out; the
  /// true edge is inside the cell).
  double contact_area_ratio = 0.0;
  int contact_patches = 0;     ///< 4-connected spots of the contact set (periodic wrap for that kernel)
  int iterations = 0;          ///< conjugate-gradient iterations of this load
  bool converged = false;      ///< the tolerance was met within maximum_iterations
  double relative_change = 0.0;   ///< last Σ|Δp| / Σ p
  double complementarity = 0.0;   ///< max p·g [Pa·m] over the grid
  double minimum_gap = 0.0;       ///< min g [m] off contact (>= -solver tolerance)
  std::vector<double> pressure;   ///< p [Pa], row-major (NaN where masked)
  /// g [m] under load: the mechanical aperture, exactly 0 on the contact set (NaN where masked)
  std::vector<double> gap;
  ContactProfile profile; ///< where the time went (ContactOptions::profile)
};

/// The scanned points of an aperture field: `aperture` = e - min e over the valid (non-NaN)
/// points (first contact at d = 0; 0 where masked), `valid` = 1 there; returns their number.
/// Throws std::invalid_argument (naming `owner`) for fewer than 2 valid points.
std::size_t scanned_aperture(const topography::Surface& surface, const std::string& owner,
                             std::vector<double>& aperture, std::vector<unsigned char>& valid);

/// Frictionless elastic contact of a composite topography against a half-space of modulus E*
/// [Pa], solved at prescribed nominal stresses σ [Pa] (file comment: the method and the closure
/// datum); the exact reference of the closure laws.
class ElasticContact
{
public:
  /// @param aperture aperture field e [m] of the composite topography (NaN = masked)
  /// @param composite_modulus E* [Pa]
  /// @param kernel periodic or non-periodic half-space (half_space.hpp)
  /// @param options stopping rule of the solver
  /// Throws std::invalid_argument for a grid with fewer than 2 valid points or E* <= 0.
  ElasticContact(const topography::Surface& aperture, double composite_modulus, Kernel kernel,
                 ContactOptions options = {});

  /// Contact at mean pressure σ > 0 [Pa], warm-started from the previous solve (its pressure
  /// scaled to σ). `keep_fields`: fill pressure and gap.
  ContactState solve(double mean_pressure, bool keep_fields = true);

  /// One state per stress (in the given order; increasing stresses warm-start best).
  std::vector<ContactState> closure_curve(std::span<const double> mean_pressures,
                                          bool keep_fields = false);

  /// c = mean over the scanned points of the displacement under unit uniform pressure [m/Pa]
  /// (0 for the periodic kernel): the patch's bulk compliance under a uniform load (a check of
  /// the kernel against Boussinesq's closed form; the closure subtracts mean(K p) instead).
  double bulk_compliance() const { return _bulk_compliance; }
  /// Number of scanned (non-NaN) points.
  std::size_t valid_count() const { return _valid_count; }

  /// The solver's limit per iteration: the shortest of `repeats` (>= 1) calls of u = K p on the
  /// last pressure (one forward + inverse transform pair with the kernel product, the plans,
  /// buffers and copies every iteration uses) [s]. Changes no state of the solver.
  double transform_pair_seconds(int repeats);
  /// Wall time of the constructor [s]: FFTW's planning (half_space().planning_seconds()), the
  /// kernel's transform, the bulk and self compliances.
  double setup_seconds() const { return _setup_seconds; }
  /// The influence operator.
  const HalfSpace& half_space() const { return _half_space; }

private:
  HalfSpace _half_space;
  ContactOptions _options;
  std::size_t _rows, _cols, _valid_count = 0;
  std::vector<double> _aperture; // shifted: min 0 over valid points
  std::vector<unsigned char> _valid;
  std::vector<double> _pressure; // last converged pressure (warm start)
  double _last_stress = 0.0;
  double _bulk_compliance = 0.0;
  double _self_compliance = 0.0; ///< K_kk [m/Pa]: the step when the CG step is degenerate
  double _setup_seconds = 0.0;
  std::vector<double> _u, _t, _r, _previous; // work arrays
  std::vector<std::size_t> _contact;  // the contact set S of an iteration
  std::vector<std::size_t> _entering; // points re-entering contact in an iteration
  std::vector<unsigned char> _member; // 1 on S (the list's membership, for the full-grid scan)
  std::vector<double> _gap_contact, _t_contact, _r_contact; // g, t and K t on S
  std::vector<std::pair<std::size_t, double>> _clamped; // (index in S, p - τ t < 0) clamped to 0
  std::vector<std::size_t> _correction_nodes;           // c of the carried update of u
  std::vector<double> _correction_values;
};

} // namespace rockjoint::contact
