# SPDX-License-Identifier: MIT
"""A toy closure law registered from outside the package (the test of docs/architecture.md,
"Adding a closure law"): the exponential law written with its initial stiffness,
Δ(σ) = V_m (1 - exp(-σ / (k0 V_m))), i.e. ExponentialLaw with σ_c = k0 V_m. One record, one
file; imported through ROCKJOINT_LAWS=toy_law_plugin (or by a test)."""
import numpy as np

from rockjoint import ExponentialLaw
from rockjoint.law_registry import REGISTRY, Quantity, law_from_parameters, register

KEY = "stiffness_exponential"


def make(initial_normal_stiffness: float, maximum_closure: float):
    """k0 [Pa/m], V_m [m]."""
    return ExponentialLaw(maximum_closure=maximum_closure,
                          characteristic_stress=initial_normal_stiffness * maximum_closure)


def guess(stress, closure, given, build, offset, closure_of):
    """V_m a little above the largest closure; k0 from the first secant."""
    return [stress[0] / max(closure[0], 1e-12), 1.2 * closure[-1]] + ([0.0] if offset else [])


RECORD = law_from_parameters(
    KEY, "exponential (k0, V_m)", "Δ = V_m (1 - exp(-σ/(k0 V_m))), the exponential law by its "
    "initial stiffness (a toy law of the registry test)", make,
    (Quantity("initial_normal_stiffness", "k0", "MPa/mm"), Quantity("maximum_closure", "V_m", "mm")),
    guess)
if KEY not in REGISTRY:
    register(RECORD)


def closure(stress, k0, vm):
    """The closed form [m]."""
    return vm * (1.0 - np.exp(-np.asarray(stress) / (k0 * vm)))
