# SPDX-License-Identifier: MIT
"""The mechanics of a jointed rock mass: elastic and smeared blocks, the joint elements (interface,
coupling), the nonlinear problem (F, J) that the solvers drive, in-situ stress, loads, stages and the
model that holds them (JointedRockModel)."""
