// SPDX-License-Identifier: MIT
#include "petsc_assembly.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace rockjoint::fem_coupling
{

void assemble_interface_matrix(Mat A, const InterfaceAssembler& assembler,
                               std::span<const double> u,
                               std::span<const std::int8_t> constrained, double scale)
{
  assembler.check_local_array("assemble_interface_matrix", "u", u.size());
  if (!constrained.empty())
    assembler.check_local_array("assemble_interface_matrix", "constrained", constrained.size());
  const int n = assembler.pair_size();
  std::vector<std::int32_t> dofs(n);
  std::vector<PetscInt> rows(n);
  std::vector<PetscScalar> values(static_cast<std::size_t>(n) * n);
  std::vector<double> matrix(static_cast<std::size_t>(n) * n);
  for (std::int32_t p = 0; p < assembler.num_pairs(); ++p)
  {
    assembler.pair_dofs(p, dofs);
    assembler.pair_matrix(p, u, matrix);
    for (int i = 0; i < n; ++i)
    {
      const auto d = static_cast<std::size_t>(dofs[i]);
      rows[i] = (d < constrained.size() && constrained[d] != 0) ? -1 : dofs[i];
    }
    for (std::size_t k = 0; k < matrix.size(); ++k)
      values[k] = scale * matrix[k];
    const PetscErrorCode ierr
        = MatSetValuesLocal(A, n, rows.data(), n, rows.data(), values.data(), ADD_VALUES);
    if (ierr != 0)
      throw std::runtime_error("assemble_interface_matrix: MatSetValuesLocal failed with PETSc "
                               "error " + std::to_string(ierr) + " at pair " + std::to_string(p)
                               + " (is the joint coupling in the sparsity pattern?)");
  }
}

} // namespace rockjoint::fem_coupling
