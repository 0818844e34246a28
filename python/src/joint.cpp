// SPDX-License-Identifier: MIT
// Bindings of rockjoint::joint: the per-point joint behaviour (normal law, shear stiffness,
// strength, slip and its state), a material point without PETSc, MPI or meshes.
#include "array_helpers.hpp"

#include <rockjoint/joint/joint_behaviour.hpp>
#include <rockjoint/joint/joint_point_state.hpp>
#include <rockjoint/joint/joint_slip.hpp>
#include <rockjoint/joint/joint_strength.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <string>

namespace py = pybind11;
using namespace rockjoint::joint;

namespace rockjoint::python
{
namespace
{
template <typename T>
using Array = py::array_t<T, py::array::c_style | py::array::forcecast>;
} // namespace

void declare_joint(py::module_& m)
{
  py::enum_<ShearModel>(m, "ShearModel", "Definition of the joint shear stiffness")
      .value("constant", ShearModel::constant)
      .value("proportional", ShearModel::proportional);

  py::enum_<StrengthModel>(m, "StrengthModel", "Peak shear strength of a joint")
      .value("none", StrengthModel::none)
      .value("coulomb", StrengthModel::coulomb)
      .value("barton", StrengthModel::barton);

  py::enum_<ShearState>(m, "ShearState", "Stick, slip or open, per joint point")
      .value("stick", ShearState::stick)
      .value("slip", ShearState::slip)
      .value("open", ShearState::open);

  py::class_<JointStrength>(m, "JointStrength",
                            "Shear strength of a joint (docs/joint-strength.md); SI units, "
                            "angles in radians")
      .def(py::init(
               [](StrengthModel model, double phi, double c, double t, double psi,
                  double limit, double jrc, double jcs, double cap, double factor)
               {
                 JointStrength s{model, phi, c, t, psi, limit, jrc, jcs, cap, factor};
                 validate(s, "JointStrength");
                 return s;
               }),
           py::arg("model") = StrengthModel::coulomb, py::kw_only(),
           py::arg("friction_angle") = 0.0, py::arg("cohesion") = 0.0,
           py::arg("tensile_strength") = 0.0, py::arg("dilation_angle") = 0.0,
           py::arg("dilation_limit") = std::numeric_limits<double>::infinity(),
           py::arg("jrc") = 0.0, py::arg("jcs") = 0.0,
           py::arg("maximum_friction_angle") = JointStrength{}.maximum_friction_angle,
           py::arg("reduction_factor") = 1.0,
           "model: StrengthModel; friction_angle φ (Barton: φ_r) [rad]; cohesion c [Pa]; "
           "tensile_strength T [Pa] (bonded joint, <= c / tan φ); dilation_angle ψ [rad] "
           "(<= φ); dilation_limit: slip after which dilation stops [m]; jrc [-], jcs [Pa] "
           "(Barton); maximum_friction_angle: cap of Barton's angle [rad]; reduction_factor F "
           "(> 0): c, tan of the mobilised angle and T divided by F (strength reduction)")
      .def_readonly("model", &JointStrength::model, "none, Coulomb or Barton")
      .def_readonly("friction_angle", &JointStrength::friction_angle, "φ (Coulomb) or the residual angle φ_r (Barton) [rad], [0, π/2)")
      .def_readonly("cohesion", &JointStrength::cohesion, "c [Pa], >= 0")
      .def_readonly("tensile_strength", &JointStrength::tensile_strength, "T [Pa], >= 0, at most the cone apex c / tan φ_max")
      .def_readonly("dilation_angle", &JointStrength::dilation_angle, "ψ [rad], 0 <= ψ <= φ (Barton: <= the angle cap)")
      .def_readonly("dilation_limit", &JointStrength::dilation_limit, "Accumulated slip after which dilation stops [m], > 0 (∞: never).")
      .def_readonly("jrc", &JointStrength::jrc, "joint roughness coefficient [-], [0, 20] (Barton)")
      .def_readonly("jcs", &JointStrength::jcs, "joint wall compressive strength [Pa], > 0 (Barton)")
      .def_readonly("maximum_friction_angle", &JointStrength::maximum_friction_angle, "Cap of Barton's mobilised friction angle [rad] (70°: Barton & Choubey 1977).")
      .def_readonly("reduction_factor", &JointStrength::reduction_factor,
                    "strength reduction factor F [-] (1: none): c, tan φ_m and T divided by it")
      .def("shear_strength",
           [](const JointStrength& s, double normal_stress)
           { return shear_strength(s, normal_stress, true).strength; },
           py::arg("normal_stress"), "τ_y [Pa] at σ_n [Pa] (compression +), bond intact");

  py::class_<JointPointState>(m, "JointPointState", "Path-dependent state of one joint point")
      .def(py::init(
               [](const std::vector<double>& slip, double dilation, double accumulated,
                  bool broken, double maximum_closure)
               {
                 if (slip.size() > 2)
                   throw py::value_error("JointPointState: slip has " + std::to_string(slip.size())
                                         + " components; at most 2 (t1, t2)");
                 JointPointState s;
                 std::copy(slip.begin(), slip.end(), s.slip.begin());
                 s.dilation = dilation;
                 s.accumulated_slip = accumulated;
                 s.bond_broken = broken;
                 s.maximum_closure = maximum_closure;
                 return s;
               }),
           py::arg("slip") = std::vector<double>{}, py::arg("dilation") = 0.0,
           py::arg("accumulated_slip") = 0.0, py::arg("bond_broken") = false,
           py::arg("maximum_closure") = 0.0)
      .def_property_readonly("slip", [](const JointPointState& s)
                             { return std::vector<double>(s.slip.begin(), s.slip.end()); },
                             "irreversible shear displacement along t1, t2 [m]")
      .def_readonly("dilation", &JointPointState::dilation, "normal opening produced by slip (dilatancy) [m]")
      .def_readonly("accumulated_slip", &JointPointState::accumulated_slip, "path length of the slip, ∫|d slip| [m]")
      .def_readonly("bond_broken", &JointPointState::bond_broken, "tensile strength exceeded once: bond (c, T) lost for good")
      .def_readonly("maximum_closure", &JointPointState::maximum_closure,
                    "largest elastic closure of the converged states, Δ_m [m] (every closure law)");

  py::class_<JointBehaviour>(m, "JointBehaviour",
                             "Closure law + shear stiffness + residual stiffness + strength of "
                             "a joint")
      .def(py::init(
               [](std::shared_ptr<const rockjoint::constitutive::ClosureLaw> law,
                  ShearModel model, double ks, double ratio, double kr,
                  std::optional<JointStrength> strength, double alpha)
               {
                 JointBehaviour b{law, model, ks, ratio, kr, strength.value_or(JointStrength{}),
                                  alpha};
                 validate(b, law ? law->name() : std::string("?"));
                 return b;
               }),
           py::arg("law"), py::arg("shear_model") = ShearModel::constant,
           py::arg("shear_stiffness") = 0.0, py::arg("shear_stiffness_ratio") = 0.0,
           py::arg("residual_stiffness") = 0.0, py::arg("strength") = py::none(),
           py::arg("effective_stress_coefficient") = 1.0)
      .def_readonly("shear_model", &JointBehaviour::shear_model, "how k_s is set")
      .def_readonly("shear_stiffness", &JointBehaviour::shear_stiffness, "k_s [Pa/m] (ShearModel::constant), >= 0")
      .def_readonly("shear_stiffness_ratio", &JointBehaviour::shear_stiffness_ratio, "α [-] (ShearModel::proportional), >= 0")
      .def_readonly("residual_stiffness", &JointBehaviour::residual_stiffness, "k_r [Pa/m], >= 0")
      .def_readonly("strength", &JointBehaviour::strength, "shear strength (default none: elastic joint)")
      .def_readonly("effective_stress_coefficient", &JointBehaviour::effective_stress_coefficient,
                    "α [-] of σ'_n = σ_n - α p (water in the joint)")
      .def_property_readonly("law", [](const JointBehaviour& b)
                             { return std::const_pointer_cast<rockjoint::constitutive::ClosureLaw>(b.law); },
                             "the normal-closure law σ(Δ) (a law with history unloads on its "
                             "branches, per point)");

  m.def(
      "closure_at_normal_stress",
      [](const JointBehaviour& b, const rockjoint::python::DoubleArray& stress) -> py::object
      {
        rockjoint::python::DoubleArray out = rockjoint::python::empty_like(stress);
        const double* in = stress.data();
        double* o = out.mutable_data();
        for (py::ssize_t i = 0; i < stress.size(); ++i)
        {
          try
          {
            o[i] = closure_at_normal_stress(b, in[i]);
          }
          catch (const std::exception& e)
          {
            throw py::value_error("closure_at_normal_stress: entry " + std::to_string(i) + ": "
                                  + e.what());
          }
        }
        if (stress.ndim() == 0)
          return out.attr("item")();
        return out;
      },
      py::arg("behaviour"), py::arg("normal_stress"),
      "Closure Δ >= 0 [m] with σ(Δ) + k_r Δ = σ_t for total normal stresses σ_t [Pa] "
      "(compression +), shaped like the input (a scalar gives a float). ValueError naming the "
      "entry for a NaN, infinite or negative σ_t or one beyond the law's range");

  m.def(
      "joint_response",
      [](const JointBehaviour& b, const Array<double>& jump, const JointPointState& converged,
         double pore_pressure)
      {
        const int gdim = static_cast<int>(jump.size());
        if (gdim != 2 && gdim != 3)
          throw py::value_error("joint_response: jump must have 2 or 3 components, got "
                                + std::to_string(gdim));
        std::array<double, 3> j{};
        std::copy_n(jump.data(), gdim, j.begin());
        JointPointState trial;
        const LocalResponse r = joint_response(b, gdim, j, converged, trial, pore_pressure);
        py::array_t<double> t(gdim), D({gdim, gdim});
        for (int i = 0; i < gdim; ++i)
        {
          t.mutable_at(i) = r.traction[i];
          for (int k = 0; k < gdim; ++k)
            D.mutable_at(i, k) = r.tangent[i][k];
        }
        py::dict out;
        out["traction"] = t;
        out["tangent"] = D;
        out["closure"] = r.closure;
        out["normal_stress"] = r.normal_stress;
        out["status"] = static_cast<int>(r.status);
        out["shear_state"] = r.shear_state;
        out["state"] = trial;
        return out;
      },
      py::arg("behaviour"), py::arg("local_jump"), py::arg("converged") = JointPointState{},
      py::arg("pore_pressure") = 0.0,
      "{traction [Pa], tangent ∂t/∂j [Pa/m], closure [m], normal_stress [Pa] (effective: the "
      "law's σ'), status, shear_state, state (trial JointPointState)} at local jump (n, t1[, t2]) "
      "[m] from the converged state, with the fluid pressure p [Pa] in the joint (0: dry)");

  m.def(
      "local_response",
      [](const JointBehaviour& b, const Array<double>& jump)
      {
        const int gdim = static_cast<int>(jump.size());
        if (gdim != 2 && gdim != 3)
          throw py::value_error("local_response: jump must have 2 or 3 components");
        std::array<double, 3> j{};
        std::copy_n(jump.data(), gdim, j.begin());
        const LocalResponse r = local_response(b, gdim, j);
        py::array_t<double> t(gdim), D({gdim, gdim});
        for (int i = 0; i < gdim; ++i)
        {
          t.mutable_at(i) = r.traction[i];
          for (int k = 0; k < gdim; ++k)
            D.mutable_at(i, k) = r.tangent[i][k];
        }
        return py::make_tuple(t, D, r.closure, r.normal_stress, static_cast<int>(r.status));
      },
      py::arg("behaviour"), py::arg("local_jump"),
      "(local traction [Pa], tangent ∂t/∂j [Pa/m], closure [m], normal stress [Pa], status)");

}
} // namespace rockjoint::python
