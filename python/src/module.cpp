// SPDX-License-Identifier: MIT
// The _rockjoint extension: one binding file per C++ namespace (DOLFINx style).
#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace rockjoint::python
{
void declare_constitutive(py::module_& m);
void declare_topography(py::module_& m);
void declare_calibration(py::module_& m);
void declare_contact(py::module_& m);
void declare_flow(py::module_& m);
void declare_joint(py::module_& m);
void declare_continuum(py::module_& m);
} // namespace rockjoint::python

PYBIND11_MODULE(_rockjoint, m)
{
  m.doc() = "rockjoint C++ core: rough-rock-joint closure laws";
  m.attr("__version__") = ROCKJOINT_VERSION; // CMakeLists.txt's project(VERSION)
  py::module_ constitutive = m.def_submodule("constitutive", "Closure laws (SI units)");
  rockjoint::python::declare_constitutive(constitutive);
  py::module_ topography
      = m.def_submodule("topography", "Joint-wall topography -> closure-law parameters (SI units)");
  rockjoint::python::declare_topography(topography);
  py::module_ calibration = m.def_submodule(
      "calibration", "Fitting closure laws to measured closure curves (Levenberg-Marquardt)");
  rockjoint::python::declare_calibration(calibration);
  py::module_ contact = m.def_submodule(
      "contact", "Boundary-element contact reference of the composite topography (SI units)");
  rockjoint::python::declare_contact(contact);
  py::module_ flow = m.def_submodule(
      "flow", "Flow through the aperture field: transmissivity, hydraulic aperture (SI units)");
  rockjoint::python::declare_flow(flow);
  py::module_ joint = m.def_submodule(
      "joint", "Per-point joint behaviour: normal law, shear stiffness, strength, slip (SI units)");
  rockjoint::python::declare_joint(joint);
  py::module_ continuum = m.def_submodule(
      "continuum", "Equivalent continuum: rock elasticity + smeared joint sets (SI units)");
  rockjoint::python::declare_continuum(continuum);
}
