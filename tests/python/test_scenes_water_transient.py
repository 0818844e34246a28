# SPDX-License-Identifier: MIT
"""A scene's transient water stage (`stages: [{..., water: {duration, steps}}]`, docs/flow.md
"Water in scenes"): the column scene of test_scenes_water.py below its table (p0 in the joint, the
joint pre-closed at σ - p0), the left end's head raised by 100 m, one way for a time t. With T and
the storage S = 1/k_n + e c_w of the joint at that closure, the pressure diffuses between the two
held ends (D = T / (μ S)) from the uniform p0 toward the linear steady profile; the closed form
(the sine series of the initial departure, Carslaw & Jaeger 1959, §3.3)::

    p(x, t) = p0 + Δp (1 - x/L) - Σ_n (2 Δp / (n π)) sin(n π x / L) exp(-n² π² D t / L²),

with k_n Barton-Bandis' tangent K / (1 - Δ/V_m)², e = (12 T)^(1/3) and water's c_w written out
here. Backward Euler: first order in the time step."""
import math

import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from test_scenes_water import (E0, G, KNI, MU, P0, RHO, SIGMA, TABLE, VM, WIDTH, Z_JOINT, closure, run,  # noqa: E402
                               scene_text, transmissivity)

RISE = 100.0                                    # the left head above the table [m]
C_WATER = 4.59e-10                              # water's compressibility [1/Pa] (Fine & Millero 1973)


def diffusivity():
    d = closure(SIGMA - P0)
    t = transmissivity(SIGMA - P0)
    storage = (1 - d / VM) ** 2 / KNI + (12 * t) ** (1 / 3) * C_WATER
    return t / (MU * storage)


def reference(x, t):
    dp, length, d = RHO * G * RISE, WIDTH, diffusivity()
    series = sum(2 * dp / (n * math.pi) * np.sin(n * math.pi * x / length) * math.exp(-(n * math.pi) ** 2 * d * t / length ** 2)
                 for n in range(1, 200))
    return P0 + dp * (1 - x / length) - series


def transient_run(tmp_path, steps, duration):
    water = f"{{table: {TABLE:g} m, heads: {{left: {TABLE + RISE:g} m, right: {TABLE:g} m}}}}"
    stages = f"  - name: flow\n    water: {{duration: {duration:.6g} s, steps: {steps}}}\n"
    result = run(tmp_path / f"n{steps}", scene_text(water, stages))
    network = result.row("jointed", "flow").water.network
    inside = (network.nodes[:, 0] > 1e-9) & (network.nodes[:, 0] < WIDTH - 1e-9)
    x = network.nodes[inside, 0]
    return np.max(np.abs(network.pressure[inside] - reference(x, duration))) / (RHO * G * RISE), result


def test_a_raised_head_diffuses_along_the_joint_as_the_closed_form(tmp_path):
    duration = 0.05 * WIDTH ** 2 / diffusivity()          # D t / L² = 0.05: half way to steady
    errors = []
    for steps in (10, 20):
        error, result = transient_run(tmp_path, steps, duration)
        errors.append(error)
        print(f"{steps} steps over {duration:.3g} s: max |p - p_ref| / Δp = {error:.3e}")
    # the profile is far from both its start and its end: the test tells a wrong D apart
    x = np.linspace(0.01, 0.09, 9)
    assert np.max(np.abs(reference(x, duration) - P0)) > 0.3 * RHO * G * RISE
    assert np.max(np.abs(reference(x, duration) - (P0 + RHO * G * RISE * (1 - x / WIDTH)))) > 0.1 * RHO * G * RISE
    assert errors[-1] < 0.03 and errors[-1] < 0.65 * errors[0]        # first order in Δt
    row = result.row("jointed", "flow")
    assert row.water.max_pressure == pytest.approx(P0, rel=1e-9)       # one way: the joints keep p0


@pytest.mark.parametrize("stage, words", [
    ("  - name: flow\n    water: {duration: 0 s}\n", "out of range"),
    ("  - name: flow\n    water: {duration: 3 weeks}\n", "unit"),
    ("  - name: flow\n    water: {duration: 1 d, steps: 0}\n", "out of range"),
])
def test_bad_transient_water_is_named(tmp_path, stage, words):
    from rockjoint.scenes import SceneError, load_scene
    from scene_cases import write
    text = scene_text(f"{{table: {TABLE:g} m, heads: {{left: {TABLE:g} m}}}}", stage)
    with pytest.raises(SceneError, match=words):
        load_scene(write(tmp_path, text))


def test_a_transient_stage_needs_the_water_s_boundaries(tmp_path):
    from rockjoint.scenes import SceneError, load_scene
    from scene_cases import write
    text = scene_text(f"{{table: {TABLE:g} m}}", "  - name: flow\n    water: {duration: 1 d}\n")
    with pytest.raises(SceneError, match="transient water stage needs the scene's water with the flow's boundaries"):
        load_scene(write(tmp_path, text))
