# SPDX-License-Identifier: MIT
"""docs/flow.md's checkerboard figures are what the flow solver gives (issue 39, item 7): the
page's series of errors against √(k1 k2) (Keller 1964, Dykhne 1971), its observed order and its
Richardson extrapolation are recomputed here and compared to the digits the page writes, so a
change of the solver or of the page that separates them fails."""
import os
import re

import numpy as np
import pytest

from rockjoint.flow import transmissivity

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")


def digits(token: str) -> int:
    return len(token.split(".")[1]) if "." in token else 0


def test_checkerboard_figures_of_the_flow_page_are_the_solver_s():
    with open(os.path.join(ROOT, "docs", "flow.md"), encoding="utf-8") as fh:
        page = " ".join(fh.read().split())
    found = re.search(r"\(([-\d., ]+) % at ([\d, ]+) cells per square, order ([\d.]+) from the last "
                      r"three.*?extrapolation of the last three grids within 0\.5 % \(([\d.]+) %\)", page)
    assert found, "docs/flow.md: the checkerboard sentence is not where this test reads it"
    errors = [t.strip() for t in found.group(1).split(",")]
    cells = [int(t) for t in found.group(2).split(",")]
    assert len(errors) == len(cells) and cells == sorted(cells)
    k1 = 1e-12 / 12.0                       # e = 0.1 mm: k = e³/12 [m³]
    k2, h = 10.0 * k1, 1e-4
    exact = np.sqrt(k1 * k2)
    t = []
    for m, written in zip(cells, errors):
        i, j = np.meshgrid(np.arange(2 * m), np.arange(2 * m), indexing="ij")
        e = np.where((i // m + j // m) % 2, np.cbrt(12 * k2), np.cbrt(12 * k1))
        t.append(transmissivity(e, h).tensor[0, 0])
        assert round(100 * (t[-1] / exact - 1), digits(written)) == pytest.approx(float(written)), m
    ratio = (t[-2] - t[-3]) / (t[-1] - t[-2])
    assert round(np.log2(ratio), digits(found.group(3))) == pytest.approx(float(found.group(3)))
    extrapolated = t[-1] + (t[-1] - t[-2]) / (ratio - 1.0)
    assert round(100 * abs(extrapolated / exact - 1), digits(found.group(4))) == pytest.approx(
        float(found.group(4)))
