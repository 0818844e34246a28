"""rockjoint: rough-rock-joint closure laws for FEniCSx.

SI units inside (Pa, m); compression positive; closure Δ net of intact-rock deformation.
"""
from ._rockjoint import constitutive as _cpp_constitutive
from ._rockjoint.constitutive import (  # noqa: F401
    BartonBandis,
    ClosureLaw,
    ExponentialLaw,
    LogarithmicLaw,
    Parameter,
    Status,
    composite_modulus,
)

__version__ = "0.1.0"
