# SPDX-License-Identifier: MIT
"""The planner's rungs: every way rockjoint gets a joint's closure curve from its topography, with
its error against the exact elastic contact of the walls and its total cost, read from the
accuracy ladder's result file (bench/results/accuracy_ladder.json, written by
bench/bench_accuracy_ladder.py beside its .md: the one source of these numbers;
tests/python/test_scenes_planner.py keeps the two equal).

Rungs: the laws of rockjoint.laws.laws_from_topography that the ladder measures (the registry's
topography laws with a ladder row), each built from the scan's summit statistics and tabulated;
and the exact contact curve of the walls themselves (EXACT_CONTACT: the BEM of rockjoint.contact
on the scan, tabulated by contact.exact_elastic_law). Error, per joint family of the bench
(granite-like, sandstone-like; the planner takes the worse), against the walls' contact resolved
at half the scan's spacing: for the exact contact its own resolution error (the scan's BEM
against the same walls at half its spacing) plus its table's; for a law its closure error
against the BEM of the same scan plus that resolution error (the law reproduces the scan's
contact at best: the triangle inequality). Each is the upper prediction limit of the bench's
per-joint errors (each joint's mean closure error over the loads) for one more joint of the type
(upper_prediction_limit): the resolution error scatters from joint to joint (2 to 32 % on the
bench's granite-like joints: the finer walls' tallest asperities move the first contact), so the
mean over joints is no prediction for one scene's joint (bench/results/plan_check.md tests the
predictions on scenes the bench did not see). Total cost: the law's work on the scan (analysis,
statistics, the law) and its table, or the BEM solve at the scan's size, as measured by the bench
(wall time in a fresh process, as a scene run pays it; interpolated log-log in the scan's side);
the scan's synthesis is common to every rung and not counted.
"""
from __future__ import annotations

import dataclasses
import functools
import json
import math
import os
from typing import Optional

import numpy as np
from scipy import stats

import rockjoint

from .. import contact, law_registry

#: the exact contact curve of the walls (BEM), the rung that is not a parametric law
EXACT_CONTACT = contact.EXACT_CONTACT
#: the file of the evidence: in the installed package (rockjoint/evidence/) or the source tree
EVIDENCE_FILE = "accuracy_ladder.json"


def evidence_path() -> str:
    """The accuracy ladder's JSON: bench/results/ of the source tree this module sits in (where
    the bench writes it), else rockjoint/evidence/ of an installed package (python/CMakeLists.txt)."""
    here = os.path.dirname(os.path.abspath(__file__))
    source = os.path.normpath(os.path.join(here, "..", "..", "..", "bench", "results", EVIDENCE_FILE))
    if os.path.exists(source):
        return source
    for root in rockjoint.__path__:
        path = os.path.join(root, "evidence", EVIDENCE_FILE)
        if os.path.exists(path):
            return path
    raise FileNotFoundError(f"{EVIDENCE_FILE}: neither {source} nor rockjoint/evidence/ of the package "
                            "(bench/bench_accuracy_ladder.py writes it)")


@functools.lru_cache(maxsize=None)
def evidence(path: Optional[str] = None) -> dict:
    """The bench's JSON (cached)."""
    with open(path or evidence_path(), encoding="utf-8") as fh:
        return json.load(fh)


#: level of the planner's upper prediction limits
PREDICTION_LEVEL = 0.95


def upper_prediction_limit(samples, level: float = PREDICTION_LEVEL) -> float:
    """Upper limit below which one more draw of the population the samples come from falls with
    probability `level`: mean + t_level,n-1 s sqrt(1 + 1/n) (normal theory; s the sample standard
    deviation, t Student's quantile). Needs at least 2 finite samples."""
    x = np.asarray(samples, dtype=float)
    if x.ndim != 1 or x.size < 2 or not np.all(np.isfinite(x)):
        raise ValueError(f"upper_prediction_limit: needs at least 2 finite samples, got {x.tolist()}")
    if not 0.5 <= level < 1.0:
        raise ValueError(f"upper_prediction_limit: level must be in [0.5, 1), got {level!r}")
    n = x.size
    return float(x.mean() + stats.t.ppf(level, n - 1) * x.std(ddof=1) * math.sqrt(1.0 + 1.0 / n))


def _interpolate_log(table: dict, x: float) -> float:
    """log-log interpolation of {x: y} at x (the end segments extrapolate)."""
    xs = np.array(sorted(float(k) for k in table))
    ys = np.array([table[k] for k in sorted(table, key=float)], dtype=float)
    i = int(np.clip(np.searchsorted(xs, x) - 1, 0, xs.size - 2))
    slope = math.log(ys[i + 1] / ys[i]) / math.log(xs[i + 1] / xs[i])
    return float(ys[i] * (x / xs[i]) ** slope)


@dataclasses.dataclass(frozen=True)
class Rung:
    """One law of the bench's ladder of closure laws: its errors against the walls and its costs.

    Fields: key (laws_from_topography key, or EXACT_CONTACT), label (the bench's words), errors
    (joint family -> relative error [-] against the exact contact at half the scan's spacing),
    evaluation (one σ + k evaluation [s]), tabulation (tolerance -> seconds to tabulate, None if it
    cannot be), work (scan side -> seconds of the law's work before its table).
    """

    key: str                 # laws_from_topography key, or EXACT_CONTACT
    label: str               # the bench's words
    errors: dict             # joint family -> error [-] against the walls at half the scan's spacing
    evaluation: float        # one σ + k evaluation [s] (0 for the exact contact: a table)
    tabulation: dict         # tolerance (str) -> seconds to tabulate (None: cannot); {} for EXACT_CONTACT
    work: dict               # scan side (str) -> seconds of the law's work before its table

    @property
    def error(self) -> float:
        """The error the planner uses: the worse of the joint families."""
        return max(self.errors.values())

    def seconds(self, points: int, tolerance: float) -> float:
        """Total cost [s] of this rung on a points² scan with tables at `tolerance`."""
        if not self.tabulation:   # the exact contact: the BEM solve is its whole work
            return _interpolate_log(self.work, points)
        before_table = _interpolate_log(self.work, points)
        known = {float(t): s for t, s in self.tabulation.items() if s is not None}
        usable = [t for t in known if t <= max(tolerance, self.tightest_tolerance)]
        return before_table + known[max(usable)]

    @property
    def tightest_tolerance(self) -> float:
        """The tightest table tolerance the bench could tabulate this law at on every joint (laws
        over measured summits have a kink per summit: 1e-6 fails there); 0 for the exact
        contact (its table is the curve's own)."""
        known = [float(t) for t, s in self.tabulation.items() if s is not None]
        return min(known) if known else 0.0


def _law_limit(errors) -> float:
    """A law's upper prediction limit over the joints it was defined on (inf on fewer than 2)."""
    return upper_prediction_limit(errors) if len(errors) >= 2 else math.inf


def rungs() -> tuple:
    """Every rung, from the bench's JSON."""
    data = evidence()
    exact = data["bem"]["families"]
    resolution = {f: upper_prediction_limit(list(v["resolution_errors"].values())) for f, v in exact.items()}
    out = []
    derived = law_registry.topography_laws()
    for key, record in derived.items():
        if record.ladder_row is None:
            continue
        law = data["laws"][record.ladder_row]
        out.append(Rung(key, law["label"], {f: _law_limit(v["closure_errors"]) + resolution[f]
                                            for f, v in law["families"].items()},
                        law["evaluation_seconds"], law["tabulation_seconds"], law["law_seconds"]))
    out.append(Rung(EXACT_CONTACT, derived[EXACT_CONTACT].label,
                    {f: resolution[f] + v["table_error"] for f, v in exact.items()}, 0.0, {},
                    data["bem_seconds"]))
    return tuple(out)


def by_key() -> dict:
    """{key: Rung} of the ladder's rungs."""
    return {r.key: r for r in rungs()}


def contact_stresses(top: float) -> np.ndarray:
    """The loads [Pa] of the exact-contact rung up to `top`: the bench's loads scaled to it (its
    table error is measured on those)."""
    s = np.asarray(evidence()["stresses"], dtype=float)
    return s * (top / s[-1])


def evidence_spacing() -> float:
    """The scan spacing [m] the bench measured the resolution error at."""
    return float(evidence()["bem"]["spacing"])


def cheapest_within(budget: float, points: int, tolerance: float):
    """(rung, met): the rung of least total cost on a points² scan whose error is within
    `budget`; else the most accurate one (met False)."""
    ladder = rungs()
    fits = [r for r in ladder if r.error <= budget]
    if fits:
        return min(fits, key=lambda r: r.seconds(points, tolerance)), True
    return min(ladder, key=lambda r: r.error), False
