// SPDX-License-Identifier: MIT
#pragma once
/// @file plastic_contact.hpp
/// Contact of elastic-perfectly-plastic walls: the pressure is capped at the rock's indentation
/// hardness H (docs/contact.md §elastic-plastic). Load paths and cycles, permanent closure.
///
/// At a rigid approach d the pressure minimises ½ pᵀK p - pᵀ(d - e) over 0 <= p <= H (e the
/// current aperture, K the half-space kernel of half_space.hpp): the gap g = e - d + K p is >= 0
/// where p = 0, 0 where 0 < p < H, and <= 0 where p = H (there the walls overlap: plastic flow).
/// It is solved by conjugate gradients on the free points with projection onto the box (the
/// bound-constrained form of Polonsky & Keer 1999). The nominal stress σ = mean(p) rises with d,
/// and d is found for each prescribed σ by the project's root finder (Illinois through the
/// bracket). After each load the overlap at the capped points is flattened off for good (the
/// aperture grows by it): later loads and every unloading see the deformed walls, so unloading is
/// elastic, reloading retraces it up to the previous maximum, and a permanent closure remains.
/// The closure datum is the original walls': Δ = mean(e0) - mean(g) = d - mean(K p) - mean(w),
/// w the flattening, as ElasticContact's (H = +inf gives its answer: an independent check of both).
#include "contact_set.hpp"
#include "elastic_contact.hpp"
#include "half_space.hpp"

#include <rockjoint/topography/surface.hpp>

#include <vector>

namespace rockjoint::contact
{

/// One load of the elastic-plastic contact.
struct PlasticContactState
{
  double mean_pressure = 0.0;      ///< σ [Pa]
  double approach = 0.0;           ///< d [m] from the original walls' first contact
  double closure = 0.0;            ///< Δ [m] (see the file comment)
  /// fraction of the scanned points in the contact set (contact_set.hpp)
  double contact_area_ratio = 0.0;
  double plastic_area_ratio = 0.0; ///< fraction at the cap H
  double mean_flattening = 0.0;    ///< mean(w) so far [m]
  int evaluations = 0;             ///< fixed-d solves of this load
  int iterations = 0;              ///< conjugate-gradient iterations of this load
  bool converged = false; ///< the load met the solver's tolerance
};

/// Contact of elastic-perfectly-plastic walls, the pressure capped at the indentation hardness
/// H [Pa], along a load path of nominal stresses [Pa] (file comment: the method); the walls
/// keep their flattening, so unloading leaves a permanent closure.
class PlasticContact
{
public:
  /// @param aperture e [m] (NaN masked); @param hardness H [Pa] > 0 (+inf: elastic walls).
  /// @param composite_modulus E* [Pa], > 0; @param kernel periodic or non-periodic half-space;
  /// @param options stopping rule of the solver.
  /// Throws std::invalid_argument naming a bad E*, H or grid.
  PlasticContact(const topography::Surface& aperture, double composite_modulus, Kernel kernel,
                 double hardness, ContactOptions options = {});

  /// Contact at nominal stress σ > 0 [Pa] after the loads before it (the path matters).
  PlasticContactState solve(double mean_pressure);

  /// Closure [m] with the load removed from the walls as they are now: d0 - mean(w), d0 = min(e).
  double unloaded_closure() const;

  /// p [Pa] of the last solve (row-major, NaN where masked).
  std::vector<double> pressure() const;

  /// Gap g [m] under the last load on the flattened walls (row-major, NaN where masked): exactly
  /// 0 on the contact set (contact_set.hpp), the mechanical aperture a flow model needs. Empty
  /// before the first solve.
  std::vector<double> gap() const;

private:
  /// σ(d): the box-constrained minimisation at fixed approach d, warm-started from _pressure.
  double mean_pressure_at(double approach);

  HalfSpace _half_space;
  ContactOptions _options;
  double _hardness;
  std::size_t _rows, _cols, _valid_count = 0;
  std::vector<double> _aperture;           ///< e0 + w (shifted: min e0 = 0 over valid points)
  std::vector<unsigned char> _valid;
  std::vector<double> _pressure, _u, _g, _t, _r;
  ContactSet _contact;                     ///< of the last solve
  double _flattening_sum = 0.0;
  double _approach = 0.0;                  ///< d of the last solve
  int _iterations = 0;
};

} // namespace rockjoint::contact
