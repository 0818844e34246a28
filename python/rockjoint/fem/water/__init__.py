# SPDX-License-Identifier: MIT
"""Water in a solved model: steady flow along the joint network with each point's transmissivity from
its closure (joint_flow), and Darcy flow through blocks with smeared sets (darcy)."""
