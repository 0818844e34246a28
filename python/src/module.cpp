// The _rockjoint extension: one binding file per C++ namespace (DOLFINx style).
#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace rockjoint::python
{
void declare_constitutive(py::module_& m);
} // namespace rockjoint::python

PYBIND11_MODULE(_rockjoint, m)
{
  m.doc() = "rockjoint C++ core: rough-rock-joint closure laws";
  py::module_ constitutive = m.def_submodule("constitutive", "Closure laws (SI units)");
  rockjoint::python::declare_constitutive(constitutive);
}
