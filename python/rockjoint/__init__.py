# SPDX-License-Identifier: MIT
"""rockjoint: rough-rock-joint closure laws for FEniCSx.

SI units inside (Pa, m); compression positive; closure Δ net of intact-rock deformation.
"""
# The pure-Python sources live in <src>/python/rockjoint; the compiled modules (_rockjoint,
# _rockjoint_fem_coupling) may sit in a build tree's python/rockjoint. extend_path joins every
# rockjoint/ folder on sys.path into this package (PYTHONPATH=<src>/python:<build>/python).
from pkgutil import extend_path

__path__ = extend_path(__path__, __name__)

from ._rockjoint import __version__  # noqa: E402,F401  (CMakeLists.txt's project(VERSION), one place)
from ._rockjoint import constitutive as _cpp_constitutive  # noqa: E402
from ._rockjoint.constitutive import (  # noqa: F401
    BartonBandis,
    ClosureLaw,
    ExponentialLaw,
    LogarithmicLaw,
    NormalHysteresis,
    Parameter,
    ParameterSpec,
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
from .tabulation import TabulatedLaw, curve_table, plot_table, tabulate  # noqa: F401
from . import laws  # noqa: F401,E402  (the law factory: rockjoint.laws.make_law, ...)
from .calibration import (  # noqa: F401, E402  (fit a law to a measured closure curve)
    Calibration,
    ClosureCurve,
    calibrate,
    read_closure_curve,
)

__version__ = "0.1.0"
