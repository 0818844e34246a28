# SPDX-License-Identifier: MIT
"""A joint's point state over all ranks, and the one check that a law was not driven past its
range (issue 39: never silent past a table, in every path).

A tabulated law answers past its last knot with the table's linear continuation, a Tang & Jiao
law past its cap with the response frozen there: both are status ``validity_limit``
(rockjoint.Status, constitutive/closure_law.hpp), and the answer is then not the law's. A
closure law tabulated to 2 MPa in a model loaded to 10 MPa closes 35 % more than the law says,
and SNES converges all the same. So after every solve the paths that solve (JointCoupling's
``check_range``, called by JointedNonlinearProblem.solve() and by ``commit_state``, and
JointedRockModel once per stage) hand their point state to `check_range`:

- `summarize` gathers per joint the points, closure and normal-stress extremes, the largest shear
  traction and the count of every status and shear state over all ranks (allreduce: the same
  JointSummary on every rank);
- a joint with points at ``validity_limit`` gives one message naming the joint, the largest σ_n
  reached and the range of its law (`law_range`); beyond_range="warn" (default) issues it on
  rank 0 only, as a `RangeWarning` (a Python warning users can filter or make an error; the
  CLI prints it as one line); beyond_range="raise" raises `BeyondRangeError`
  on every rank (the summary is the same everywhere, so no rank is left in a collective).
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Mapping

import numpy as np
from mpi4py import MPI

from ..._rockjoint import constitutive as _constitutive
from ..._rockjoint import joint as _joint


#: the per-point status codes of a joint's state (coupling.state(u)["status"]): rockjoint.Status
Status = _constitutive.Status
#: what beyond_range= accepts
BEYOND_RANGE = ("warn", "raise")
_STATUSES = sorted(Status.__members__.values(), key=int)
_SHEAR_STATES = sorted(_joint.ShearState.__members__.values(), key=int)


class RangeWarning(UserWarning):
    """A joint law answered past its range (a table beyond its last knot, a law past its validity
    limit): the result there is not the law's. Filter it like any warning; under MPI it is issued
    on rank 0 only, so make it an error with beyond_range="raise" (every rank raises), not with
    warnings.simplefilter("error", RangeWarning) (rank 0 alone would raise)."""


class BeyondRangeError(RuntimeError):
    """beyond_range="raise" and a joint law answered past its range (raised on every rank)."""


def check_beyond_range(value) -> str:
    """The beyond_range option, checked: "warn" or "raise"."""
    if value not in BEYOND_RANGE:
        raise ValueError(f"beyond_range must be one of {list(BEYOND_RANGE)}, got {value!r}")
    return value


@dataclass(frozen=True)
class JointSummary:
    """One joint's point state over all ranks (the same on every rank). Extremes are NaN for a
    joint without points."""
    joint: str
    points: int
    min_closure: float         #: [m] (negative: open)
    max_closure: float         #: [m]
    min_normal_stress: float   #: [Pa], compression positive
    max_normal_stress: float   #: [Pa]
    max_shear_traction: float  #: largest shear traction magnitude ‖τ‖ [Pa]
    #: {status name: points} (rockjoint.Status names), every status listed
    status: dict = field(default_factory=dict)
    #: {shear state name: points} (ShearState: stick, slip, open; empty for smeared sets)
    shear_state: dict = field(default_factory=dict)

    @property
    def beyond_range(self) -> int:
        """Points whose law answered past its range (status validity_limit)."""
        return self.status.get("validity_limit", 0)


def summarize(comm, state: Mapping, joint_tags: Mapping[str, int]) -> dict:
    """{joint name: JointSummary} of a point state on this rank (JointInterface.state's dict),
    gathered over `comm` (collective: three allreduce)."""
    names = sorted(joint_tags)
    tags = np.asarray(state["tag"])
    closure, sn = np.asarray(state["closure"]), np.asarray(state["normal_stress"])
    tau = np.asarray(state["shear_traction"], dtype=float)   # (points, gdim - 1)
    tau = np.linalg.norm(tau.reshape(tags.size, -1), axis=1) if tags.size else np.zeros(0)
    shear = state.get("shear_state")   # none for smeared sets
    codes = [(np.asarray(state["status"]), s) for s in _STATUSES] + \
        ([(np.asarray(shear), s) for s in _SHEAR_STATES] if shear is not None else [])
    n, k = len(names), len(_STATUSES)
    lows, highs = np.full(2 * n, np.inf), np.full(3 * n, -np.inf)
    counts = np.zeros((n, 1 + len(codes)), dtype=np.int64)
    for i, name in enumerate(names):
        at = tags == joint_tags[name]
        counts[i, 0] = np.count_nonzero(at)
        counts[i, 1:] = [np.count_nonzero(values[at] == int(s)) for values, s in codes]
        if counts[i, 0]:
            lows[[i, n + i]] = closure[at].min(), sn[at].min()
            highs[[i, n + i, 2 * n + i]] = closure[at].max(), sn[at].max(), tau[at].max()
    lows, highs, counts = (_allreduce(comm, a, op) for a, op in ((lows, MPI.MIN), (highs, MPI.MAX),
                                                                   (counts, MPI.SUM)))
    out = {}
    for i, name in enumerate(names):
        points = int(counts[i, 0])
        ext = [float(v) if points else math.nan for v in (lows[i], highs[i], lows[n + i], highs[n + i],
                                                          highs[2 * n + i])]
        out[name] = JointSummary(name, points, *ext,
                                 {s.name: int(c) for s, c in zip(_STATUSES, counts[i, 1:k + 1])},
                                 {s.name: int(c) for s, c in zip(_SHEAR_STATES if shear is not None else [],
                                                                 counts[i, k + 1:])})
    return out


def _allreduce(comm, a: np.ndarray, op) -> np.ndarray:
    out = np.empty_like(a)
    comm.Allreduce(a, out, op=op)
    return out


def law_range(law) -> tuple:
    """(words for the range in which a closure law, or a JointBehaviour's law, answers as itself;
    what happens past it and what to do)."""
    law = getattr(law, "law", law)                      # a JointBehaviour's closure law
    while hasattr(law, "virgin"):                       # NormalHysteresis: its virgin curve's range
        law = law.virgin
    if hasattr(law, "table_maximum_stress"):
        return (f"its table covers σ_n 0 - {law.table_maximum_stress * 1e-6:.4g} MPa (closure up to "
                f"{law.table_maximum_closure * 1e3:.4g} mm)",
                "Past a table's last knot the answer is its linear continuation, not the law: tabulate "
                "to a higher max_stress.")
    limit = float(law.maximum_closure)
    if math.isfinite(limit):   # a capped law (Tang & Jiao): frozen at its cap
        cap = float(law.normal_stress(limit))
        return (f"its law ({law.name}) is valid below closure {limit * 1e3:.4g} mm"
                + (f", σ_n {cap * 1e-6:.4g} MPa" if math.isfinite(cap) else ""),
                "Past a law's validity limit its response is frozen there, not the law's.")
    return f"its law ({law.name}) left its validity range", "The answer there is not the law's."


def range_words(summary: JointSummary, law) -> tuple:
    """(the message of one joint past its law's range, what that means)."""
    where, meaning = law_range(law)
    return (f"joint {summary.joint!r}: {summary.beyond_range} of {summary.points} points past the "
            f"range of its law; σ_n reaches {summary.max_normal_stress * 1e-6:.4g} MPa where {where}"), meaning


def check_range(comm, summaries: Mapping[str, JointSummary], laws: Mapping[str, object],
                beyond_range: str = "warn", where: str = "") -> list:
    """Report the joints of `summaries` (summarize's, the same on every rank) with points past
    their law's range: beyond_range "warn" → a RangeWarning on rank 0 (one message; the CLI shows
    warnings as lines, rockjoint.console.warnings_as_lines), "raise" → BeyondRangeError on every rank.
    laws: {joint name: closure law or JointBehaviour}; where: what was solved ("after stage 'x'").
    Returns the messages (the same on every rank; empty when every point is inside its range)."""
    found = [range_words(s, laws[name]) for name, s in summaries.items() if s.beyond_range]
    if not found:
        return []
    words = [w for w, _ in found]
    meanings = " ".join(dict.fromkeys(m for _, m in found))   # each once, in order
    text = f"joint law driven past its range{' ' + where if where else ''}: " + "; ".join(words) + ". " + meanings
    if check_beyond_range(beyond_range) == "raise":
        raise BeyondRangeError(text)
    if comm.rank == 0:
        text += ' beyond_range="raise" makes this an error.'
        warnings.warn(text, RangeWarning, stacklevel=3)
    return words
