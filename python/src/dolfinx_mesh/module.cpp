// SPDX-License-Identifier: MIT
// rockjoint._rockjoint_dolfinx (built with DOLFINx >= 0.10 only): a serial mesh created by
// dolfinx::mesh::create_mesh with its cells kept in the order given.
//
// Why: create_mesh reorders the cells with Gibbs-Poole-Stockmeyer, whose residual-component step
// clears an array the size of the mesh for every connected component of the cells' dual graph
// (DOLFINx 0.9-0.11, graph/ordering.cpp). A jointed mesh is split along its joints, so every block
// is a component: the continuum bench's discrete tunnel (23k triangles, 11k blocks) spent 0.66 s of
// its 0.7 s of mesh creation there, against 0.06 s for the same triangles glued
// (bench/results/tunnel_profile.md). The cells arrive block by block, blocks by centre of mass
// (meshes.builders), which already keeps neighbours close in memory; no reordering is needed.
//
// The mesh crosses into Python as DOLFINx's own nanobind type (dolfinx.cpp.mesh.Mesh_float64): this
// module is built with the nanobind and the DOLFINx headers DOLFINx's Python layer was built with.
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

#include <dolfinx/fem/CoordinateElement.h>
#include <dolfinx/graph/AdjacencyList.h>
#include <dolfinx/mesh/Mesh.h>
#include <dolfinx/mesh/utils.h>
#include <dolfinx_wrappers/caster_mpi.h>
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

namespace nb = nanobind;

namespace
{
/// The identity permutation: the cells stay in the order given.
std::vector<std::int32_t> keep_order(const dolfinx::graph::AdjacencyList<std::int32_t>& graph)
{
  std::vector<std::int32_t> order(graph.num_nodes());
  std::iota(order.begin(), order.end(), 0);
  return order;
}
} // namespace

NB_MODULE(_rockjoint_dolfinx, m)
{
  m.def(
      "create_mesh_in_order",
      [](dolfinx_wrappers::MPICommWrapper comm,
         nb::ndarray<const std::int64_t, nb::ndim<2>, nb::c_contig> cells,
         const dolfinx::fem::CoordinateElement<double>& element,
         nb::ndarray<const double, nb::ndim<2>, nb::c_contig> x)
      {
        int size = 0;
        MPI_Comm_size(comm.get(), &size);
        if (size != 1)
          throw std::invalid_argument("create_mesh_in_order: serial only (the cells are not partitioned)");
        std::span<const std::int64_t> c(cells.data(), cells.size());
        std::span<const double> xs(x.data(), x.size());
        return dolfinx::mesh::create_mesh(comm.get(), comm.get(), {c}, {element}, comm.get(), xs,
                                          {x.shape(0), x.shape(1)}, nullptr, 2, keep_order);
      },
      nb::arg("comm"), nb::arg("cells"), nb::arg("element"), nb::arg("x"),
      "A serial dolfinx::mesh::Mesh of `cells` (rows of node indices into `x`, in DOLFINx's node "
      "order) with the cells in the order given (no Gibbs-Poole-Stockmeyer reordering).");
}
