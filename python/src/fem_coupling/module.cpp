// SPDX-License-Identifier: MIT
// The _rockjoint_fem_coupling extension: bindings of rockjoint::fem_coupling (interface assembler). Separate
// from _rockjoint so that the closure laws and the per-point joint behaviour never need PETSc.
// Closure laws and JointBehaviour come in as the objects bound by rockjoint._rockjoint (import
// it first: pybind11 shares the registered types between the two modules).
#include "../array_helpers.hpp"

#include <rockjoint/fem_coupling/interface_assembler.hpp>
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
using namespace rockjoint::fem_coupling;

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

PYBIND11_MODULE(_rockjoint_fem_coupling, m)
{
  m.doc() = "rockjoint zero-thickness joint elements: interface assembly (SI units)";

  py::enum_<QuadratureRule>(m, "QuadratureRule", "Where the joint law is sampled on a facet")
      .value("nodal", QuadratureRule::nodal)
      .value("gauss", QuadratureRule::gauss);

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
                  const Array<std::int32_t>& tags, std::map<std::int32_t, rockjoint::joint::JointBehaviour> behaviours)
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
          py::arg("pair"), py::arg("u"),
          "dense consistent Jacobian of pair `pair` at u, (pair_size, pair_size) [N/m]")
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
           { a.update_state(span_of(u)); }, py::arg("u"),
           "refresh the trial point state at u [m] without assembling")
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
      .def(
          "set_pore_pressure",
          [](InterfaceAssembler& a, const Array<double>& p) { a.set_pore_pressure(span_of(p)); },
          py::arg("pressure"), "(num_points,) fluid pressure p [Pa] in the joint at each point")
      .def_property_readonly("pore_pressure", [](const InterfaceAssembler& a)
                             { return to_numpy(a.pore_pressure()); },
                             "(num_points,) fluid pressure p [Pa] at each point")
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
            py::array_t<double> slip({n, g - 1}), dilation(n), accumulated(n), peak(n);
            py::array_t<bool> broken(n);
            for (py::ssize_t i = 0; i < n; ++i)
            {
              broken.mutable_at(i) = s[i].bond_broken;
              for (py::ssize_t k = 0; k < g - 1; ++k)
                slip.mutable_at(i, k) = s[i].slip[k];
              dilation.mutable_at(i) = s[i].dilation;
              accumulated.mutable_at(i) = s[i].accumulated_slip;
              peak.mutable_at(i) = s[i].maximum_closure;
            }
            py::dict out;
            out["slip"] = slip;
            out["dilation"] = dilation;
            out["accumulated_slip"] = accumulated;
            out["bond_broken"] = broken;
            out["maximum_closure"] = peak;
            return out;
          },
          py::arg("converged") = false,
          "{slip (points, gdim-1), dilation, accumulated_slip, maximum_closure (largest elastic "
          "closure of the converged states, Δ_m)} [m], bond_broken (bool) of the trial (default) "
          "or converged point state")
      .def(
          "set_maximum_closure",
          [](InterfaceAssembler& a, const Array<double>& peak) { a.set_maximum_closure(span_of(peak)); },
          py::arg("maximum_closure"),
          "(num_points,) largest closure reached Δ_m [m] of every point, converged and trial")
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
