// The _rockjoint_fem extension: bindings of rockjoint::fem (interface assembler). Separate
// from _rockjoint so that the closure-law module never needs PETSc/DOLFINx. Closure laws
// come in as the shared_ptr<ClosureLaw> objects of rockjoint._rockjoint (import it first).
#include "../array_helpers.hpp"

#include <rockjoint/fem_coupling/interface_assembler.hpp>
#include <rockjoint/fem_coupling/joint_slip.hpp>
#include <rockjoint/fem_coupling/local_frame.hpp>
#include <rockjoint/fem_coupling/petsc_assembly.hpp>

#include <petscmat.h>
#include <petscsnes.h>
#include <cstdint>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <limits>
#include <optional>
#include <span>

namespace py = pybind11;
using namespace rockjoint::fem;

namespace
{
template <typename T>
using Array = py::array_t<T, py::array::c_style | py::array::forcecast>;

template <typename T>
std::span<const T> span_of(const Array<T>& a)
{
  return {a.data(), static_cast<std::size_t>(a.size())};
}

/// A numpy copy of a vector, reshaped to (n / cols, cols) when cols > 1.
template <typename T>
py::array_t<T> to_numpy(const std::vector<T>& v, py::ssize_t cols = 1)
{
  py::array_t<T> out(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), out.mutable_data());
  if (cols > 1)
    out.resize({static_cast<py::ssize_t>(v.size()) / cols, cols});
  return out;
}
} // namespace

PYBIND11_MODULE(_rockjoint_fem, m)
{
  m.doc() = "rockjoint zero-thickness joint elements: interface assembly (SI units)";

  py::enum_<QuadratureRule>(m, "QuadratureRule", "Where the joint law is sampled on a facet")
      .value("nodal", QuadratureRule::nodal)
      .value("gauss", QuadratureRule::gauss);

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
                  double limit, double jrc, double jcs, double cap)
               {
                 JointStrength s{model, phi, c, t, psi, limit, jrc, jcs, cap};
                 validate(s, "JointStrength");
                 return s;
               }),
           py::arg("model") = StrengthModel::coulomb, py::kw_only(),
           py::arg("friction_angle") = 0.0, py::arg("cohesion") = 0.0,
           py::arg("tensile_strength") = 0.0, py::arg("dilation_angle") = 0.0,
           py::arg("dilation_limit") = std::numeric_limits<double>::infinity(),
           py::arg("jrc") = 0.0, py::arg("jcs") = 0.0,
           py::arg("maximum_friction_angle") = JointStrength{}.maximum_friction_angle,
           "model: StrengthModel; friction_angle φ (Barton: φ_r) [rad]; cohesion c [Pa]; "
           "tensile_strength T [Pa] (bonded joint, <= c / tan φ); dilation_angle ψ [rad] "
           "(<= φ); dilation_limit: slip after which dilation stops [m]; jrc [-], jcs [Pa] "
           "(Barton); maximum_friction_angle: cap of Barton's angle [rad]")
      .def_readonly("model", &JointStrength::model)
      .def_readonly("friction_angle", &JointStrength::friction_angle)
      .def_readonly("cohesion", &JointStrength::cohesion)
      .def_readonly("tensile_strength", &JointStrength::tensile_strength)
      .def_readonly("dilation_angle", &JointStrength::dilation_angle)
      .def_readonly("dilation_limit", &JointStrength::dilation_limit)
      .def_readonly("jrc", &JointStrength::jrc)
      .def_readonly("jcs", &JointStrength::jcs)
      .def_readonly("maximum_friction_angle", &JointStrength::maximum_friction_angle)
      .def("shear_strength",
           [](const JointStrength& s, double normal_stress)
           { return shear_strength(s, normal_stress, true).strength; },
           py::arg("normal_stress"), "τ_y [Pa] at σ_n [Pa] (compression +), bond intact");

  py::class_<JointPointState>(m, "JointPointState", "Path-dependent state of one joint point")
      .def(py::init(
               [](const std::vector<double>& slip, double dilation, double accumulated,
                  bool broken)
               {
                 if (slip.size() > 2)
                   throw py::value_error("JointPointState: slip has " + std::to_string(slip.size())
                                         + " components; at most 2 (t1, t2)");
                 JointPointState s;
                 std::copy(slip.begin(), slip.end(), s.slip.begin());
                 s.dilation = dilation;
                 s.accumulated_slip = accumulated;
                 s.bond_broken = broken;
                 return s;
               }),
           py::arg("slip") = std::vector<double>{}, py::arg("dilation") = 0.0,
           py::arg("accumulated_slip") = 0.0, py::arg("bond_broken") = false)
      .def_property_readonly("slip", [](const JointPointState& s)
                             { return std::vector<double>(s.slip.begin(), s.slip.end()); })
      .def_readonly("dilation", &JointPointState::dilation)
      .def_readonly("accumulated_slip", &JointPointState::accumulated_slip)
      .def_readonly("bond_broken", &JointPointState::bond_broken);

  py::class_<JointBehaviour>(m, "JointBehaviour",
                             "Closure law + shear stiffness + residual stiffness + strength of "
                             "a joint")
      .def(py::init(
               [](std::shared_ptr<const rockjoint::constitutive::ClosureLaw> law,
                  ShearModel model, double ks, double ratio, double kr,
                  std::optional<JointStrength> strength)
               {
                 JointBehaviour b{law, model, ks, ratio, kr, strength.value_or(JointStrength{})};
                 validate(b, law ? law->name() : std::string("?"));
                 return b;
               }),
           py::arg("law"), py::arg("shear_model") = ShearModel::constant,
           py::arg("shear_stiffness") = 0.0, py::arg("shear_stiffness_ratio") = 0.0,
           py::arg("residual_stiffness") = 0.0, py::arg("strength") = py::none())
      .def_readonly("shear_model", &JointBehaviour::shear_model)
      .def_readonly("shear_stiffness", &JointBehaviour::shear_stiffness)
      .def_readonly("shear_stiffness_ratio", &JointBehaviour::shear_stiffness_ratio)
      .def_readonly("residual_stiffness", &JointBehaviour::residual_stiffness)
      .def_readonly("strength", &JointBehaviour::strength)
      .def_property_readonly("law", [](const JointBehaviour& b)
                             { return std::const_pointer_cast<rockjoint::constitutive::ClosureLaw>(b.law); });

  m.def(
      "snes_set_function_domain_error",
      [](std::uintptr_t snes_handle)
      {
        // petsc4py 3.22 does not bind SNESSetFunctionDomainError; the SNES arrives as its handle
        // (petsc4py's SNES.handle), as matrices do.
        if (snes_handle == 0)
          throw py::value_error("snes_set_function_domain_error: the SNES handle is null");
        if (SNESSetFunctionDomainError(reinterpret_cast<SNES>(snes_handle)) != PETSC_SUCCESS)
          throw std::runtime_error("SNESSetFunctionDomainError failed");
      },
      py::arg("snes_handle"),
      "Tell a SNES that the function was evaluated outside its domain (SNESSetFunctionDomainError): "
      "the line search or solve then fails with SNES_DIVERGED_FUNCTION_DOMAIN.");
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
      [](const JointBehaviour& b, const Array<double>& jump, const JointPointState& converged)
      {
        const int gdim = static_cast<int>(jump.size());
        if (gdim != 2 && gdim != 3)
          throw py::value_error("joint_response: jump must have 2 or 3 components, got "
                                + std::to_string(gdim));
        std::array<double, 3> j{};
        std::copy_n(jump.data(), gdim, j.begin());
        JointPointState trial;
        const LocalResponse r = joint_response(b, gdim, j, converged, trial);
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
      "{traction [Pa], tangent ∂t/∂j [Pa/m], closure [m], normal_stress [Pa], status, "
      "shear_state, state (trial JointPointState)} at local jump (n, t1[, t2]) [m] from the "
      "converged state");

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

  m.def(
      "joint_reference_direction",
      [](const Array<double>& moment)
      {
        if (moment.size() != 9)
          throw py::value_error("joint_reference_direction: the normal moment must be 3 x 3");
        std::array<double, 9> M;
        std::copy_n(moment.data(), 9, M.begin());
        const auto r = joint_reference_direction(M);
        py::array_t<double> out(3);
        std::copy(r.begin(), r.end(), out.mutable_data());
        return out;
      },
      py::arg("normal_moment"),
      "Strike of the mean plane of a 3D joint from Σ A n nᵀ (3, 3); x axis if horizontal");

  py::class_<InterfaceAssembler>(m, "InterfaceAssembler", "Matched joint facet pairs")
      .def(py::init(
               [](int gdim, int degree, QuadratureRule rule, const Array<std::int32_t>& pair_dofs,
                  const Array<double>& vertices, const Array<double>& interior,
                  const Array<std::int32_t>& tags, std::map<std::int32_t, JointBehaviour> behaviours)
               {
                 return InterfaceAssembler(gdim, degree, rule, span_of(pair_dofs),
                                           span_of(vertices), span_of(interior), span_of(tags),
                                           std::move(behaviours));
               }),
           py::arg("gdim"), py::arg("degree"), py::arg("rule"), py::arg("pair_dofs"),
           py::arg("vertex_coordinates"), py::arg("minus_interior_points"), py::arg("joint_tags"),
           py::arg("behaviours"),
           "pair_dofs: (num_pairs, 2 * num_facet_nodes * gdim) unrolled local dofs, minus nodes "
           "then plus nodes (plus permuted to the minus order), node-major, component-minor")
      .def_property_readonly("gdim", &InterfaceAssembler::gdim)
      .def_property_readonly("num_pairs", &InterfaceAssembler::num_pairs)
      .def_property_readonly("num_points_per_pair", &InterfaceAssembler::num_points_per_pair)
      .def_property_readonly("pair_size", &InterfaceAssembler::pair_size)
      .def(
          "pair_dofs",
          [](const InterfaceAssembler& a)
          {
            const py::ssize_t n = a.pair_size();
            py::array_t<std::int32_t> out({static_cast<py::ssize_t>(a.num_pairs()), n});
            for (std::int32_t p = 0; p < a.num_pairs(); ++p)
              a.pair_dofs(p, {out.mutable_data(p, 0), static_cast<std::size_t>(n)});
            return out;
          },
          "(num_pairs, pair_size) unrolled local dofs of every pair")
      .def(
          "assemble_residual",
          [](InterfaceAssembler& a, const Array<double>& u, py::array_t<double> residual)
          {
            if (residual.size() != u.size() || !(residual.flags() & py::array::c_style))
              throw py::value_error("assemble_residual: residual must be a contiguous array "
                                    "of the size of u");
            py::gil_scoped_release release;
            return a.assemble_residual(span_of(u),
                                       {residual.mutable_data(), static_cast<std::size_t>(residual.size())});
          },
          py::arg("u"), py::arg("residual"),
          "Add the joint residual at local u into the local array `residual` (in place); "
          "False if a traction is not finite")
      .def(
          "assemble_matrix",
          [](const InterfaceAssembler& a, std::uintptr_t A_handle, const Array<double>& u,
             const Array<std::int8_t>& constrained, double scale)
          {
            // The matrix arrives as its PETSc handle (petsc4py's Mat.handle), not as a typed
            // object: DOLFINx 0.9's Python layer is nanobind and exports no pybind11 caster, so
            // the two binding systems meet through petsc4py handles and numpy arrays only.
            if (A_handle == 0)
              throw py::value_error("assemble_matrix: the PETSc Mat handle is null");
            Mat A = reinterpret_cast<Mat>(A_handle);
            py::gil_scoped_release release;
            assemble_interface_matrix(A, a, span_of(u), span_of(constrained), scale);
          },
          py::arg("A_handle"), py::arg("u"), py::arg("constrained"), py::arg("scale") = 1.0,
          "MatSetValuesLocal/ADD_VALUES of the joint Jacobian; rows/cols with constrained != 0 "
          "are skipped. Call before the bulk assemble_matrix(A, a, bcs).")
      .def(
          "pair_matrix",
          [](const InterfaceAssembler& a, std::int32_t p, const Array<double>& u)
          {
            if (p < 0 || p >= a.num_pairs())
              throw py::index_error("pair index out of range");
            const py::ssize_t n = a.pair_size();
            py::array_t<double> K({n, n});
            a.pair_matrix(p, span_of(u), {K.mutable_data(), static_cast<std::size_t>(n * n)});
            return K;
          },
          py::arg("pair"), py::arg("u"))
      .def("maximum_closure_ratio",
           [](const InterfaceAssembler& a, const Array<double>& u)
           { return a.maximum_closure_ratio(span_of(u)); },
           py::arg("u"), "max over points of closure / law maximum closure")
      .def("admissible_step_length",
           [](const InterfaceAssembler& a, const Array<double>& u, const Array<double>& du,
              double fraction)
           {
             if (du.size() != u.size())
               throw py::value_error("admissible_step_length: du must have the size of u");
             if (!(fraction > 0.0 && fraction < 1.0))
               throw py::value_error("admissible_step_length: fraction must be in (0, 1)");
             return a.admissible_step_length(span_of(u), span_of(du), fraction);
           },
           py::arg("u"), py::arg("du"), py::arg("fraction"),
           "largest α <= 1 keeping Δ <= Δ + fraction (Δ_max - Δ) at every point")
      .def("update_state", [](InterfaceAssembler& a, const Array<double>& u)
           { a.update_state(span_of(u)); }, py::arg("u"))
      .def(
          "normal_moments",
          [](const InterfaceAssembler& a)
          {
            py::dict out;
            for (const auto& [tag, M] : a.normal_moments())
            {
              py::array_t<double> m({3, 3});
              std::copy(M.begin(), M.end(), m.mutable_data());
              out[py::int_(tag)] = m;
            }
            return out;
          },
          "{joint tag: Σ A n nᵀ (3, 3)} over this rank's pairs [m² or m]")
      .def("set_reference_directions", &InterfaceAssembler::set_reference_directions,
           py::arg("directions"), "{joint tag: reference tangent direction (3,)}: rebuild t1, t2")
      .def_property_readonly(
          "frames",
          [](const InterfaceAssembler& a)
          {
            const py::ssize_t g = a.gdim();
            py::array_t<double> out({static_cast<py::ssize_t>(a.num_pairs()), g, g});
            for (std::int32_t p = 0; p < a.num_pairs(); ++p)
              for (py::ssize_t i = 0; i < g; ++i)
                for (py::ssize_t c = 0; c < g; ++c)
                  out.mutable_at(p, i, c) = a.frame(p).axes[i][c];
            return out;
          },
          "(num_pairs, gdim, gdim) frame rows n, t1[, t2] (global components)")
      .def(
          "set_initial_jump",
          [](InterfaceAssembler& a, const Array<double>& j0) { a.set_initial_jump(span_of(j0)); },
          py::arg("initial_jump"), "(num_points, gdim) initial local jump j0 [m]")
      .def_property_readonly("initial_jump", [](const InterfaceAssembler& a)
                             { return to_numpy(a.initial_jump(), a.gdim()); })
      .def("commit_state", &InterfaceAssembler::commit_state, "converged point state <- trial")
      .def("revert_state", &InterfaceAssembler::revert_state, "trial point state <- converged")
      .def("reset_state", &InterfaceAssembler::reset_state,
           "virgin point state (no slip, no dilation, bonds intact) at every point")
      .def_property_readonly("num_law_evaluations", &InterfaceAssembler::num_law_evaluations)
      .def(
          "point_state",
          [](const InterfaceAssembler& a, bool converged)
          {
            const auto& s = converged ? a.converged_state() : a.trial_state();
            const py::ssize_t n = static_cast<py::ssize_t>(s.size()), g = a.gdim();
            py::array_t<double> slip({n, g - 1}), dilation(n), accumulated(n);
            py::array_t<bool> broken(n);
            for (py::ssize_t i = 0; i < n; ++i)
            {
              broken.mutable_at(i) = s[i].bond_broken;
              for (py::ssize_t k = 0; k < g - 1; ++k)
                slip.mutable_at(i, k) = s[i].slip[k];
              dilation.mutable_at(i) = s[i].dilation;
              accumulated.mutable_at(i) = s[i].accumulated_slip;
            }
            py::dict out;
            out["slip"] = slip;
            out["dilation"] = dilation;
            out["accumulated_slip"] = accumulated;
            out["bond_broken"] = broken;
            return out;
          },
          py::arg("converged") = false,
          "{slip (points, gdim-1), dilation, accumulated_slip} [m], bond_broken (bool) of the "
          "trial (default) or converged point state")
      .def_property_readonly("closure", [](const InterfaceAssembler& a) { return to_numpy(a.closure()); })
      .def_property_readonly("normal_stress",
                             [](const InterfaceAssembler& a) { return to_numpy(a.normal_stress()); })
      .def_property_readonly("shear_traction",
                             [](const InterfaceAssembler& a)
                             {
                               auto t = to_numpy(a.shear_traction());
                               t.resize({static_cast<py::ssize_t>(a.closure().size()),
                                         static_cast<py::ssize_t>(a.gdim() - 1)});
                               return t;
                             })
      .def_property_readonly("status", [](const InterfaceAssembler& a) { return to_numpy(a.status()); })
      .def_property_readonly("shear_state", [](const InterfaceAssembler& a)
                             { return to_numpy(a.shear_state()); },
                             "ShearState per point at the last residual (stick 0, slip 1, open 2)")
      .def_property_readonly("point_coordinates", [](const InterfaceAssembler& a)
                             { return to_numpy(a.point_coordinates(), a.gdim()); })
      .def_property_readonly("normals", [](const InterfaceAssembler& a)
                             { return to_numpy(a.normals(), a.gdim()); })
      .def_property_readonly("point_tags", [](const InterfaceAssembler& a) { return to_numpy(a.point_tags()); })
      .def_property_readonly("measures", [](const InterfaceAssembler& a) { return to_numpy(a.measures()); });
}
