# SPDX-License-Identifier: MIT
"""Solvers of the nonlinear problems: rockjoint's Newton with a closure-limited step (newton), the
PETSc SNES problem (snes_problem), the linear solvers (linear_solver), pseudo-transient continuation
for softening sets (pseudo_transient) and the user's PETSc options (petsc_options)."""
