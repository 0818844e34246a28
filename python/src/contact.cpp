// SPDX-License-Identifier: MIT
// Bindings of rockjoint::contact: the boundary-element contact reference (SI units). The
// Python layer rockjoint/contact.py owns the curve object and the defaults.
#include "array_helpers.hpp"

#include <rockjoint/contact/exact_law.hpp>
#include <rockjoint/contact/plastic_contact.hpp>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <limits>

#include <memory>

namespace py = pybind11;

namespace rockjoint::python
{
using namespace rockjoint::contact;

namespace
{
py::array_t<double> field(const std::vector<double>& v, std::size_t rows, std::size_t cols)
{
  if (v.empty())
    return py::array_t<double>();
  py::array_t<double> out({rows, cols});
  std::copy(v.begin(), v.end(), out.mutable_data());
  return out;
}
} // namespace

void declare_contact(py::module_& m)
{
  py::enum_<Kernel>(m, "Kernel", "Half-space kernel of the contact reference")
      .value("periodic", Kernel::periodic)
      .value("non_periodic", Kernel::non_periodic);

  py::class_<ContactProfile>(m, "ContactProfile",
                             "Where one load's wall time went [s] (ContactOptions profile=True)")
      .def_readonly("wall", &ContactProfile::wall, "the whole solve call")
      .def_readonly("start", &ContactProfile::start, "warm or cold start, the first contact set")
      .def_readonly("transforms", &ContactProfile::transforms, "u = K p and K t by FFT")
      .def_readonly("direct_sums", &ContactProfile::direct_sums, "K t on a small contact set, summed directly")
      .def_readonly("grid_passes", &ContactProfile::grid_passes, "interpenetration scan, carried u update with K c")
      .def_readonly("contact_set", &ContactProfile::contact_set, "CG algebra on the contact set")
      .def_readonly("final_state", &ContactProfile::final_state, "gap, contact set, spots, fields")
      .def_readonly("transform_pairs", &ContactProfile::transform_pairs, "FFT pairs of the load (always counted)")
      .def_readonly("carried_updates", &ContactProfile::carried_updates, "iterations that carried u = K p without a transform (always counted)");

  py::class_<ContactState>(m, "ContactState", "The contact at one nominal stress (SI)")
      .def_readonly("mean_pressure", &ContactState::mean_pressure, "σ [Pa]")
      .def_readonly("approach", &ContactState::approach, "d [m], raw rigid approach")
      .def_readonly("closure", &ContactState::closure, "Δ [m], net of bulk deformation")
      .def_readonly("contact_area_ratio", &ContactState::contact_area_ratio, "A/A0 [-]")
      .def_readonly("contact_patches", &ContactState::contact_patches, "4-connected spots of the contact set (periodic wrap for that kernel)")
      .def_readonly("iterations", &ContactState::iterations, "conjugate-gradient iterations of this load")
      .def_readonly("converged", &ContactState::converged, "the tolerance was met within maximum_iterations")
      .def_readonly("relative_change", &ContactState::relative_change, "last Σ|Δp| / Σ p")
      .def_readonly("complementarity", &ContactState::complementarity, "max p g [Pa m]")
      .def_readonly("minimum_gap", &ContactState::minimum_gap, "min g off contact [m]")
      .def_readonly("profile", &ContactState::profile, "where the load's time went");

  py::class_<ElasticContact>(m, "ElasticContact",
                             "Frictionless elastic contact of an aperture field (Polonsky-Keer)")
      .def(py::init<const topography::Surface&, double, Kernel, ContactOptions>(),
           py::arg("aperture"), py::arg("composite_modulus"), py::arg("kernel"),
           py::arg("options"))
      .def(
          "solve",
          [](ElasticContact& c, double sigma, bool keep_fields, std::size_t rows, std::size_t cols)
          {
            ContactState st;
            {
              py::gil_scoped_release release;
              st = c.solve(sigma, keep_fields);
            }
            return py::make_tuple(st, field(st.pressure, rows, cols), field(st.gap, rows, cols));
          },
          py::arg("mean_pressure"), py::arg("keep_fields"), py::arg("rows"), py::arg("cols"))
      .def_property_readonly("bulk_compliance", &ElasticContact::bulk_compliance, "c = mean over the scanned points of the displacement under unit uniform pressure [m/Pa] (0 for the periodic kernel): the patch's bulk compliance under a uniform load (a check of the kernel against Boussinesq's closed form; the closure subtracts mean(K p) instead).")
      .def_property_readonly("valid_count", &ElasticContact::valid_count, "Number of scanned (non-NaN) points.")
      .def(
          "transform_pair_seconds",
          [](ElasticContact& c, int repeats)
          {
            py::gil_scoped_release release;
            return c.transform_pair_seconds(repeats);
          },
          py::arg("repeats"), "shortest of `repeats` u = K p calls on the last pressure [s]")
      .def_property_readonly("setup_seconds", &ElasticContact::setup_seconds, "wall time of the constructor [s], planning included")
      .def_property_readonly("planning_seconds", [](const ElasticContact& c) { return c.half_space().planning_seconds(); },
                             "wall time of FFTW's planning [s]");

  py::class_<PlasticContactState>(m, "PlasticContactState", "One load of the elastic-plastic contact (SI)")
      .def_readonly("mean_pressure", &PlasticContactState::mean_pressure, "σ [Pa]")
      .def_readonly("approach", &PlasticContactState::approach, "d [m]")
      .def_readonly("closure", &PlasticContactState::closure, "Δ [m]")
      .def_readonly("contact_area_ratio", &PlasticContactState::contact_area_ratio, "A/A0 [-]")
      .def_readonly("plastic_area_ratio", &PlasticContactState::plastic_area_ratio, "at H [-]")
      .def_readonly("mean_flattening", &PlasticContactState::mean_flattening, "mean(w) [m]")
      .def_readonly("evaluations", &PlasticContactState::evaluations, "fixed-d solves of this load")
      .def_readonly("iterations", &PlasticContactState::iterations, "conjugate-gradient iterations of this load")
      .def_readonly("converged", &PlasticContactState::converged, "the load met the solver's tolerance");

  py::class_<PlasticContact>(m, "PlasticContact",
                             "Contact of elastic-perfectly-plastic walls (pressure capped at H)")
      .def(py::init<const topography::Surface&, double, Kernel, double, ContactOptions>(),
           py::arg("aperture"), py::arg("composite_modulus"), py::arg("kernel"),
           py::arg("hardness"), py::arg("options"))
      .def(
          "solve",
          [](PlasticContact& c, double sigma)
          {
            py::gil_scoped_release release;
            return c.solve(sigma);
          },
          py::arg("mean_pressure"))
      .def("unloaded_closure", &PlasticContact::unloaded_closure,
           "closure [m] with the load removed from the walls as they are now (permanent)")
      .def(
          "pressure",
          [](const PlasticContact& c, std::size_t rows, std::size_t cols)
          { return field(c.pressure(), rows, cols); },
          py::arg("rows"), py::arg("cols"))
      .def(
          "gap",
          [](const PlasticContact& c, std::size_t rows, std::size_t cols)
          { return field(c.gap(), rows, cols); },
          py::arg("rows"), py::arg("cols"),
          "g [m] under the last load, exactly 0 on the contact set (NaN where masked)");

  py::class_<ContactOptions>(m, "ContactOptions")
      .def(py::init(
               [](double tol, int its, bool profile)
               {
                 ContactOptions o;
                 o.tolerance = tol;
                 o.maximum_iterations = its;
                 o.profile = profile;
                 return o;
               }),
           py::arg("tolerance") = ContactOptions{}.tolerance,
           py::arg("maximum_iterations") = ContactOptions{}.maximum_iterations,
           py::arg("profile") = ContactOptions{}.profile);

  m.def(
      "exact_elastic_law",
      [](const std::vector<ContactState>& curve, double modulus, double spacing, double rows,
         double cols, Kernel kernel, double tolerance, double residual_stiffness,
         double initial_stiffness)
      {
        return std::make_shared<constitutive::TabulatedLaw>(exact_elastic_law(
            curve, ContactSource{modulus, spacing, rows, cols, kernel, tolerance},
            residual_stiffness, initial_stiffness));
      },
      py::arg("curve"), py::arg("composite_modulus"), py::arg("spacing"), py::arg("rows"),
      py::arg("cols"), py::arg("kernel"), py::arg("tolerance"), py::arg("residual_stiffness"),
      py::arg("initial_stiffness") = 0.0);
}

} // namespace rockjoint::python
