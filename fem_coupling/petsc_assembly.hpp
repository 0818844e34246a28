// SPDX-License-Identifier: MIT
#pragma once
/// @file petsc_assembly.hpp
/// Interface Jacobian into a PETSc matrix (the only PETSc-dependent piece).
///
/// Order with DOLFINx (docs/fem.md, pitfall 5): add the interface blocks with ADD_VALUES
/// *before* the bulk assembly with Dirichlet conditions, which ends with a flush and an
/// INSERT of the diagonal of constrained rows. Rows and columns of constrained dofs are left
/// out here (PETSc ignores negative indices), so the constrained rows stay identity rows.

#include "interface_assembler.hpp"

#include <petscmat.h>

#include <cstdint>
#include <span>

namespace rockjoint::fem_coupling
{

/// Add every pair's consistent Jacobian at `u` to `A` with MatSetValuesLocal/ADD_VALUES
/// (A must carry a local-to-global map of the unrolled local dof numbering, as matrices from
/// dolfinx.cpp.la.petsc.create_matrix do, and a pattern containing the pair couplings).
/// `constrained` is indexed by unrolled local dof (ghosts included); a non-zero entry drops
/// that row and column. `scale` multiplies the blocks (0 inserts explicit zeros: reserves the
/// couplings in a matrix that is later copied with SAME_NONZERO_PATTERN, since PETSc drops
/// preallocated entries never set at the final assembly). Does not assemble (flush) A.
/// Throws std::runtime_error on a PETSc error.
void assemble_interface_matrix(Mat A, const InterfaceAssembler& assembler,
                               std::span<const double> u,
                               std::span<const std::int8_t> constrained, double scale = 1.0);

} // namespace rockjoint::fem_coupling
