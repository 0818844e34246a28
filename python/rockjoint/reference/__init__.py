# SPDX-License-Identifier: MIT
"""Closed-form reference solutions, each in its own module in the notation of its source."""
from .kirsch import KirschSolution  # noqa: F401
from .plane_failure import PlaneFailure  # noqa: F401
