# SPDX-License-Identifier: MIT
"""Flow along a joint: the transmissivity of an aperture field (its solver: rockjoint.aperture_flow,
re-exported here) and the joint's transmissivity as a function of its normal closure
(docs/flow.md).

A transmissivity law gives T(Δ) at a closure Δ [m]. Its records (one per law, keys spelled here
only) are in :data:`TRANSMISSIVITY_LAWS`; :func:`transmissivity_law` builds one by key:

* ``walls``: tabulated from the same walls' contact and flow solutions (a closure curve computed
  with ``flow=True``): (0, T at first contact) and (Δ_i, T_i) at each load;
* ``cubic_law``: parallel plates at the mechanical aperture e = e0 - Δ, T = e³/12;
* ``barton_jrc``: e = e0 - Δ and Barton's conversion e_h = e²/JRC^2.5 (e, e_h in µm; Barton,
  Bandis & Bakhtar 1985), T = e_h³/12;
* ``hydraulic_history``: T(Δ, Δ_m) with history (flow_history.py): first loading on a virgin law
  (cubic_law or barton_jrc), unloading below the largest closure Δ_m recovering only 1 - d of the
  virgin hydraulic aperture's recovery.

The others follow Δ only: with a closure law with history (``NormalHysteresis``) the closure on its
branches (``closure_path``) gives T along load cycles.

SI units: m, m³.
"""
from __future__ import annotations

import dataclasses
from typing import Callable, Dict, Sequence

import numpy as np

from ._rockjoint import flow as _cpp
from .aperture_flow import (DEFAULT_SOLVER, ApertureFlow, Boundary, LinearSolver,  # noqa: F401  (re-exported)
                            Transmissivity, hydraulic_aperture, transmissivity)
from .flow_history import HYDRAULIC_LOSS, HistoryTransmissivityLaw
from .units import DIMENSIONS


# ---- transmissivity laws: T as a function of closure ---------------------------------------------
class TransmissivityLaw:
    """T(Δ) [m³] of a joint at normal closure Δ [m] (arrays or scalars), with the hydraulic
    aperture e_h(Δ) and the mechanical aperture e(Δ) it comes with."""

    def __init__(self, key: str, transmissivity: Callable[[np.ndarray], np.ndarray],
                 mechanical_aperture: Callable[[np.ndarray], np.ndarray], parameters: dict):
        self.key = key
        self.parameters = dict(parameters)
        self._transmissivity = transmissivity
        self._mechanical = mechanical_aperture

    @staticmethod
    def _closure(closure) -> np.ndarray:
        d = np.asarray(closure, dtype=float)
        if np.any(np.isnan(d)):
            raise ValueError("transmissivity law: closure contains NaN")
        return d

    def transmissivity(self, closure):
        """T [m³] at closure(s) Δ [m]."""
        out = self._transmissivity(self._closure(closure))
        return float(out) if np.ndim(out) == 0 else out

    def hydraulic_aperture(self, closure):
        """e_h = (12 T)^(1/3) [m] at closure(s) Δ [m]."""
        out = hydraulic_aperture(self._transmissivity(self._closure(closure)))
        return float(out) if np.ndim(out) == 0 else out

    def mechanical_aperture(self, closure):
        """Mean mechanical aperture e [m] at closure(s) Δ [m] (0 once closed)."""
        out = self._mechanical(self._closure(closure))
        return float(out) if np.ndim(out) == 0 else out

    def __repr__(self) -> str:
        shown = {k: v for k, v in self.parameters.items() if np.isscalar(v)}
        return f"TransmissivityLaw({self.key!r}, {shown})"


@dataclasses.dataclass(frozen=True)
class TransmissivityRecord:
    """One transmissivity law: its key, words, its SI parameters (name -> what it is, with its
    unit) and its builder ``build(**parameters) -> TransmissivityLaw``."""

    key: str
    label: str
    description: str
    parameters: Dict[str, str]
    build: Callable[..., TransmissivityLaw]


#: {key: TransmissivityRecord} of the transmissivity laws (filled by the registrations below).
TRANSMISSIVITY_LAWS: Dict[str, TransmissivityRecord] = {}
#: one micrometre [m]: the unit of Barton's conversion (rockjoint.units, the one unit table)
MICROMETRE = DIMENSIONS["length"]["µm"]


def _register(record: TransmissivityRecord) -> None:
    TRANSMISSIVITY_LAWS[record.key] = record


def transmissivity_law(key: str, **parameters) -> TransmissivityLaw:
    """The transmissivity law `key` of TRANSMISSIVITY_LAWS built from its SI parameters (ValueError
    naming an unknown key, a missing or unknown parameter)."""
    if key not in TRANSMISSIVITY_LAWS:
        raise ValueError(f"unknown transmissivity law {key!r}; expected one of "
                         f"{', '.join(sorted(TRANSMISSIVITY_LAWS))}")
    record = TRANSMISSIVITY_LAWS[key]
    required = {k for k, v in record.parameters.items() if not v.startswith("optional")}
    missing, unknown = sorted(required - set(parameters)), sorted(set(parameters) - set(record.parameters))
    if missing or unknown:
        raise ValueError(f"transmissivity law {key!r}: " + "; ".join(
            ([f"missing {', '.join(missing)}"] if missing else []) +
            ([f"unknown {', '.join(unknown)}"] if unknown else [])) +
            f" (parameters: {', '.join(f'{k} ({v})' for k, v in record.parameters.items())})")
    return record.build(**parameters)


def _positive(key: str, name: str, value: float, unit: str) -> float:
    value = float(value)
    if not (np.isfinite(value) and value > 0):
        raise ValueError(f"transmissivity law {key!r}: {name} = {value} {unit} must be finite and > 0")
    return value


def _mechanical(e0: float) -> Callable[[np.ndarray], np.ndarray]:
    """e = e0 - Δ, 0 once closed [m]."""
    return lambda d: np.maximum(e0 - d, 0.0)


def _cubic_law(initial_aperture: float) -> TransmissivityLaw:
    e0 = _positive("cubic_law", "initial_aperture", initial_aperture, "m")
    e = _mechanical(e0)
    return TransmissivityLaw("cubic_law", lambda d: e(d) ** 3 / 12.0, e, {"initial_aperture": e0})


def _barton_jrc(initial_aperture: float, jrc: float) -> TransmissivityLaw:
    """e_h = e²/JRC^2.5 with e, e_h in µm (Barton, Bandis & Bakhtar 1985, stated for e >= e_h):
    above e = JRC^2.5 µm (316 µm for JRC 10) the conversion would give e_h > e; e_h = e is kept
    there (the walls far apart: parallel plates)."""
    e0 = _positive("barton_jrc", "initial_aperture", initial_aperture, "m")
    jrc = _positive("barton_jrc", "jrc", jrc, "")
    e = _mechanical(e0)

    def t(d):
        e_um = e(d) / MICROMETRE
        e_h = np.minimum(e_um * e_um / jrc ** 2.5, e_um) * MICROMETRE
        return e_h ** 3 / 12.0

    return TransmissivityLaw("barton_jrc", t, e, {"initial_aperture": e0, "jrc": jrc})


#: the transmissivity component a "walls" law tabulates by default: the mean of the principal
#: values (T_xx + T_yy)/2
WALLS_COMPONENTS = ("mean", "xx", "yy")


def _walls(curve, component: str = "mean") -> TransmissivityLaw:
    """Tabulated from a closure curve computed with flow=True (contact.closure_curve): knots
    (0, T at first contact) and (Δ_i, T_i); the mean mechanical aperture is mean(e) - Δ (the
    closure's datum, docs/contact.md)."""
    if getattr(curve, "transmissivity_xx", None) is None:
        raise ValueError("transmissivity law 'walls': the closure curve carries no flow; compute it "
                         "with contact.closure_curve(..., flow=True)")
    if component not in WALLS_COMPONENTS:
        raise ValueError(f"transmissivity law 'walls': component {component!r}; expected one of "
                         f"{', '.join(WALLS_COMPONENTS)}")

    def pick(tensor_xx, tensor_yy):
        return {"mean": 0.5 * (tensor_xx + tensor_yy), "xx": tensor_xx, "yy": tensor_yy}[component]

    first = curve.initial_flow.tensor
    closure = np.concatenate([[0.0], curve.closure])
    t = np.concatenate([[pick(first[0, 0], first[1, 1])],
                        pick(curve.transmissivity_xx, curve.transmissivity_yy)])
    table = _cpp.TransmissivityTable(closure, t)
    e0 = curve.initial_flow.mechanical_aperture
    return TransmissivityLaw("walls", table.transmissivity, _mechanical(e0),
                             {"component": component, "initial_aperture": e0,
                              "closure": closure, "transmissivity": t})


#: the virgin laws a law with history can take (parameters given, not the walls)
HISTORY_VIRGINS = ("cubic_law", "barton_jrc")


def _hydraulic_history(initial_aperture: float, hydraulic_loss: float, virgin: str = "cubic_law",
                       **virgin_parameters) -> HistoryTransmissivityLaw:
    """T(Δ, Δ_m) of flow_history.py over the virgin law `virgin` with its own parameters."""
    if virgin not in HISTORY_VIRGINS:
        raise ValueError(f"transmissivity law 'hydraulic_history': virgin = {virgin!r}; expected one of "
                         f"{', '.join(HISTORY_VIRGINS)}")
    base = transmissivity_law(virgin, initial_aperture=initial_aperture, **virgin_parameters)
    return HistoryTransmissivityLaw(base, hydraulic_loss)


for _record in (
        TransmissivityRecord(
            "walls", "the walls' own flow (BEM + Reynolds), tabulated",
            "T(Δ) through the transmissivity of the walls' gap field at first contact and at each "
            "load of their contact solution (monotone Hermite in -ln T)",
            {"curve": "a contact.ClosureCurve computed with flow=True",
             "component": "optional: 'mean' (default), 'xx' or 'yy'"}, _walls),
        TransmissivityRecord(
            "cubic_law", "cubic law on the mechanical aperture",
            "parallel plates at e = e0 - Δ: T = e³/12", {"initial_aperture": "e0 [m]"}, _cubic_law),
        TransmissivityRecord(
            "barton_jrc", "Barton's JRC conversion",
            "e = e0 - Δ, e_h = e²/JRC^2.5 (µm; Barton, Bandis & Bakhtar 1985), T = e_h³/12",
            {"initial_aperture": "e0 [m]", "jrc": "JRC [-]"}, _barton_jrc),
        TransmissivityRecord(
            "hydraulic_history", "with history: unloading recovers a fraction of the aperture",
            "T(Δ, Δ_m): the virgin law on first loading; below the largest closure Δ_m the hydraulic "
            "aperture e_v(Δ_m) + (1 - d)(e_v(Δ) - e_v(Δ_m)) (docs/flow.md)",
            {"initial_aperture": "e0 [m]", HYDRAULIC_LOSS[0]: HYDRAULIC_LOSS[1],
             "virgin": "optional: the law of first loading, cubic_law (default) or barton_jrc",
             "jrc": "optional: JRC [-] (virgin barton_jrc)"}, _hydraulic_history)):
    _register(_record)


def built_from_walls(key: str) -> bool:
    """Whether the transmissivity law `key` is built from the joint's own walls (its closure curve
    with flow), not from parameters a user gives."""
    return "curve" in TRANSMISSIVITY_LAWS[key].parameters


def user_parameters(key: str, required: bool = False) -> list:
    """The parameters of law `key` a user gives (its walls' curve excluded), or only the
    required ones."""
    record = TRANSMISSIVITY_LAWS[key]
    return [k for k, v in record.parameters.items()
            if k != "curve" and not (required and v.startswith("optional"))]


def transmissivity_along(law: TransmissivityLaw, closure_law, stresses: Sequence[float],
                         maximum_closure: float = 0.0) -> np.ndarray:
    """T [m³] along a path of normal stresses [Pa] (load cycles): the closures of `closure_law`
    on that path (a law with history, NormalHysteresis: on its branches, from the largest closure
    `maximum_closure` [m] reached before; a law without history: its curve), then T(Δ), or
    T(Δ, Δ_m) for a transmissivity law with history (Δ_m the running maximum from
    `maximum_closure` on)."""
    stresses = np.asarray(stresses, dtype=float)
    if getattr(closure_law, "has_history", False):
        closure = closure_law.closure_path(stresses, maximum_closure)
    else:
        closure = closure_law.closure_at_stress(stresses)
    if getattr(law, "has_history", False):
        closure = np.asarray(closure, dtype=float)
        return np.asarray(law.transmissivity(closure, np.maximum.accumulate(np.maximum(closure, maximum_closure))))
    return np.asarray(law.transmissivity(closure))
