// SPDX-License-Identifier: MIT
// Bindings of rockjoint::continuum: the equivalent-continuum material (rock elasticity + smeared
// joint sets through the joint behaviour) and its many-point state container.
#include "array_helpers.hpp"

#include <rockjoint/continuum/continuum_points.hpp>
#include <rockjoint/continuum/equivalent_continuum.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

namespace py = pybind11;
using namespace rockjoint::continuum;

namespace rockjoint::python
{
namespace
{
/// Check an (n, k) array and return n.
std::size_t rows(const DoubleArray& a, std::size_t k, const std::string& what)
{
  if (a.ndim() != 2 || static_cast<std::size_t>(a.shape(1)) != k)
    throw py::value_error(what + " must have shape (n, " + std::to_string(k) + ")");
  return static_cast<std::size_t>(a.shape(0));
}
} // namespace

void declare_continuum(py::module_& m)
{
  py::class_<JointSet>(m, "JointSet", "A joint set smeared in the rock: unit normal, spacing, behaviour")
      .def(py::init(
               [](const std::vector<double>& normal, double spacing,
                  const rockjoint::joint::JointBehaviour& behaviour, const std::string& label)
               {
                 if (normal.size() < 2 || normal.size() > 3)
                   throw py::value_error("JointSet '" + label + "': normal must have 2 or 3 components, got "
                                         + std::to_string(normal.size()));
                 JointSet s;
                 s.normal = {normal[0], normal[1], normal.size() == 3 ? normal[2] : 0.0};
                 s.spacing = spacing;
                 s.behaviour = behaviour;
                 s.label = label;
                 return s;
               }),
           py::arg("normal"), py::arg("spacing"), py::arg("behaviour"), py::arg("label") = "set",
           "normal: unit normal [-]; spacing s [m] (> 0); behaviour: joint.JointBehaviour")
      .def_property_readonly("normal", [](const JointSet& s) { return std::vector<double>(s.normal.begin(), s.normal.end()); },
                             "Unit normal of the joints [-] (three components; z = 0 in 2D)")
      .def_readonly("spacing", &JointSet::spacing, "Spacing s [m] between the joints of the set")
      .def_readonly("behaviour", &JointSet::behaviour,
                    "The joints' behaviour (a joint.JointBehaviour: closure law, shear, strength)")
      .def_readonly("label", &JointSet::label, "The set's name, in messages and outputs");

  py::class_<EquivalentContinuum>(m, "EquivalentContinuum",
                                  "Rock elasticity + smeared joint sets (docs/equivalent-continuum.md); "
                                  "Voigt 2D (xx, yy, xy), 3D (xx, yy, zz, yz, xz, xy), engineering shear")
      .def(py::init<int, double, double, std::vector<JointSet>>(), py::arg("gdim"), py::arg("young"),
           py::arg("poisson"), py::arg("sets"))
      .def_property_readonly("gdim", &EquivalentContinuum::gdim, "Geometric dimension, 2 or 3")
      .def_property_readonly("strain_size", &EquivalentContinuum::strain_size,
                             "Voigt size nv of strain and stress: 3 in 2D, 6 in 3D")
      .def_property_readonly("num_sets", &EquivalentContinuum::num_sets, "Number of joint sets")
      .def_property_readonly("young", &EquivalentContinuum::young, "Young's modulus E of the rock [Pa]")
      .def_property_readonly("poisson", &EquivalentContinuum::poisson, "Poisson's ratio ν of the rock [-]")
      .def_property_readonly("sets", &EquivalentContinuum::sets, "The joint sets (a list of JointSet)")
      .def("rock_stiffness",
           [](const EquivalentContinuum& mat)
           {
             const auto d = mat.rock_stiffness();
             const py::ssize_t nv = mat.strain_size();
             DoubleArray out({nv, nv});
             std::copy(d.begin(), d.end(), out.mutable_data());
             return out;
           },
           "Isotropic elastic stiffness of the intact rock, (nv, nv) [Pa], Voigt with "
           "engineering shear");

  py::class_<ContinuumPoints>(m, "ContinuumPoints",
                              "The material at n points: converged and trial set states (MGIS style)")
      .def(py::init<EquivalentContinuum, std::size_t>(), py::arg("material"), py::arg("num_points"))
      .def_property_readonly("num_points", &ContinuumPoints::num_points, "Number of points n")
      .def_property_readonly("material", &ContinuumPoints::material,
                             "The EquivalentContinuum every point shares")
      .def(
          "evaluate",
          [](ContinuumPoints& p, const DoubleArray& strain)
          {
            const std::size_t nv = static_cast<std::size_t>(p.material().strain_size());
            const std::size_t n = rows(strain, nv, "strain");
            if (n != p.num_points())
              throw py::value_error("strain has " + std::to_string(n) + " rows for "
                                    + std::to_string(p.num_points()) + " points");
            DoubleArray stress({n, nv}), tangent({n, nv * nv});
            std::size_t failed = 0;
            {
              py::gil_scoped_release release;
              failed = p.evaluate(as_span(strain), {stress.mutable_data(), n * nv},
                                  {tangent.mutable_data(), n * nv * nv});
            }
            return py::make_tuple(stress, tangent, failed);
          },
          py::arg("strain"),
          "(stress (n, nv) [Pa], tangent (n, nv²) [Pa], number of failed points) at the total "
          "strains (n, nv); the trial state is recomputed from the converged one")
      .def("commit", &ContinuumPoints::commit,
           "Accept the trial states of the last evaluate as the converged ones (end of a step)")
      .def("revert", &ContinuumPoints::revert,
           "Discard the trial states: back to the converged ones (a step that failed)")
      .def(
          "initialise_from_stress",
          [](ContinuumPoints& p, const DoubleArray& stress)
          {
            const std::size_t nv = static_cast<std::size_t>(p.material().strain_size());
            const std::size_t n = rows(stress, nv, "stress");
            if (n != p.num_points())
              throw py::value_error("stress has " + std::to_string(n) + " rows for "
                                    + std::to_string(p.num_points()) + " points");
            DoubleArray strain({n, nv});
            p.initialise_from_stress(as_span(stress), {strain.mutable_data(), n * nv});
            return strain;
          },
          py::arg("stress"), "strain (n, nv) carrying the stresses (n, nv) [Pa]; sets the state")
      .def(
          "set_state",
          [](const ContinuumPoints& p, std::size_t set, bool converged)
          {
            const auto states = p.set_states(set, converged);
            const py::ssize_t n = static_cast<py::ssize_t>(states.size());
            DoubleArray jump({n, py::ssize_t(3)}), slip({n, py::ssize_t(2)});
            for (py::ssize_t i = 0; i < n; ++i)
            {
              for (int a = 0; a < 3; ++a)
                jump.mutable_at(i, a) = states[i].jump[a];
              for (int a = 0; a < 2; ++a)
                slip.mutable_at(i, a) = states[i].joint.slip[a];
            }
            py::dict out;
            out["jump"] = jump;
            out["slip"] = slip;
            return out;
          },
          py::arg("set"), py::arg("converged") = true,
          "{'jump': (n, 3) local jumps [m], 'slip': (n, 2) plastic slip [m]} of one set");
}

} // namespace rockjoint::python
