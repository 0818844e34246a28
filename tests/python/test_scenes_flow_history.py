# SPDX-License-Identifier: MIT
"""A scene's joint set with a transmissivity law with history (`flow: {law: hydraulic_history,
initial_aperture, hydraulic_loss, virgin}`, issue 41): the column scene of test_scenes_water.py
loaded (the in-situ 10 MPa) then unloaded by 6 MPa, one way between two heads. On unloading the
joint's T is the closed form of the law at its closure and the in-situ peak (written out here:
e = e_p + (1 - d)(e_now - e_p) of the cubic law's apertures); bad values named."""
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from rockjoint.scenes import SceneError, load_scene  # noqa: E402
from scene_cases import write  # noqa: E402
from test_scenes_water import E0, G, MU, RHO, SIGMA, WIDTH, closure, run, scene_text  # noqa: E402

LOSS = 0.4
HISTORY = "    flow: {law: hydraulic_history, initial_aperture: 0.3 mm, hydraulic_loss: %s, virgin: cubic_law}\n"


def history_scene(loss=LOSS):
    text = scene_text("", "  - name: unload\n    loads: {top: {traction: [0 MPa, 6 MPa]}}\n")
    text = text.replace("    flow: {law: cubic_law, initial_aperture: 0.3 mm}\n", HISTORY % loss)
    return text.replace("outputs: {monitor: [top]}", "outputs: {monitor: [top], flow: {heads: {left: 10 m, right: 0 m}}}")


def test_unloading_follows_the_law_with_history(tmp_path):
    result = run(tmp_path, history_scene())
    peak, now = closure(SIGMA), closure(SIGMA - 6e6)
    e_peak, e_now = E0 - peak, E0 - now
    t = (e_peak + (1 - LOSS) * (e_now - e_peak)) ** 3 / 12
    expected = RHO * G / MU * t * 10.0 / WIDTH
    row = result.row("jointed", "unload")
    assert row.flow_rates["left"] == pytest.approx(expected, rel=1e-4)
    virgin = RHO * G / MU * e_now ** 3 / 12 * 10.0 / WIDTH
    assert row.flow_rates["left"] < 0.9 * virgin            # the history costs flow: the test tells it apart


def test_a_hydraulic_loss_of_one_is_refused_by_name(tmp_path):
    with pytest.raises(SceneError, match="hydraulic_loss.*must be in \\[0, 1\\)"):
        load_scene(write(tmp_path, history_scene(1.0)))
