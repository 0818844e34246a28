# SPDX-License-Identifier: MIT
"""The DOLFINx side of a jointed mesh: the gmsh model of rockjoint.meshes distributed over the ranks
with its joint pairs and named groups (distributed_mesh), and a mesh of DOLFINx's own reader split
along its joints (split_joints)."""
