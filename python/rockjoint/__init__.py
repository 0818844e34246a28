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
from ._rockjoint.constitutive import (  # noqa: F401  (GW and Tang substrate, theory §2, §4)
    AsperityLaw,
    AsperityParameters,
    GreenwoodWilliamson,
    SummitPopulationLaw,
    TangSubstrate,
)
from ._rockjoint.constitutive import (  # noqa: F401  (Tang & Jiao 2018, theory §5)
    InteractionCell,
    NumericInteractionCell,
    TangJiao,
    TangJiaoLimit,
)
from .tabulation import TabulatedLaw, plot_table, tabulate  # noqa: F401  (issue 4)

__version__ = "0.1.0"
