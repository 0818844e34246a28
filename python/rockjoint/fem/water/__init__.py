# SPDX-License-Identifier: MIT
"""Water in a solved model: flow along the joint network with each point's transmissivity from its
closure (joint_flow, on the discrete network of network.py), the water's pressure acting back on
the joints (joint_pressure), the two-way coupled steady state (coupled) and transient flow with
storage (transient), and Darcy flow through blocks with smeared sets (darcy)."""
