# SPDX-License-Identifier: MIT
"""Output of a solved model: XDMF files and mesh data for pictures (fields), boundary means and the
total stress a scene reads (monitors), and values at points independent of the partition (probe)."""
