# SPDX-License-Identifier: MIT
"""Issue 40: the horseshoe's and the D's intact-rock convergence (tests/python/opening_cases.py: W = 20 a,
rollers, hydrostatic in-situ stress p then the excavation, P1, plane strain; docs/tunnel.md).

(a) Mesh convergence: the same shape on four meshes, every element size halved each time (h = a/4 ..
a/32 on the opening); the reference is the Richardson extrapolation of the three finest (order
observed from them). The error of the crown settlement, the floor heave, the wall closure and the area
loss falls by more than 1.5 at each halving: the 270° rock corners where the walls meet a flat
floor or an invert make the elastic field singular (Williams: u ~ r^0.544), which caps the order
of these energy-like quantities near 2 x 0.544 = 1.09 (observed 1.5-2.5); 1.5 = 2^0.58 is below it.

(b) Against the circle of equal area: under a hydrostatic far field every hole loses more area than
the circle of the same area (the circle is the stiffest hole: the Hashin-Shtrikman bound on the bulk
modulus of a porous plate is attained to first order in porosity by circular holes, and a hole's area
change under a hydrostatic load does not depend on its orientation). The FE section is a W = 20 a
box with rollers, not an infinite plate: the box's own effect, measured on the circle against
Kirsch's closed form (rockjoint.reference.kirsch), stays below 5 %, and it acts on both holes alike
to first order (the far field of either is a centre of dilatation of strength ΔA / 2π), so the
ratio is read on the same box. Only the ordering is asserted: the ratio's size is a result
(docs/tunnel.md).
"""
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

import opening_cases as cases  # noqa: E402

KEYS = ("crown", "floor", "walls", "area")
LEVELS = (4, 8, 16, 32)


@pytest.fixture(scope="module", params=["horseshoe", "D"])
def study(request):
    shape = {"horseshoe": cases.HORSESHOE, "D": cases.D_SHAPE}[request.param]
    runs = [cases.solve(shape, 1.0 / n) for n in LEVELS]
    circle = cases.equal_area_circle(shape)
    return request.param, shape, runs, [cases.solve(circle, 1.0 / n) for n in LEVELS[1:]], circle


def test_error_falls_with_the_element_size(study):
    name, _, runs, _, _ = study
    for key in KEYS:
        values = [r[key] for r in runs]
        _, order, errors = cases.errors(values)
        assert all(v > 0.0 for v in values), (name, key, values)   # the opening closes
        for coarse, fine in zip(errors, errors[1:]):
            assert coarse > 1.5 * fine, (name, key, errors, order)
        assert errors[-1] < 0.02, (name, key, errors)   # at a/16
    assert runs[-1]["dofs"] > 20 * runs[0]["dofs"]   # the sequence really refines


def test_the_shape_loses_more_area_than_the_circle_of_equal_area(study):
    name, shape, runs, circles, circle = study
    area = cases.richardson([r["area"] for r in runs[1:]])[0]
    circle_area = cases.richardson([r["area"] for r in circles])[0]
    kirsch = cases.kirsch_closures(circle)["area"]
    # the set-up: the circle's FE area loss is Kirsch's up to the box (rollers at W = 20 a stiffen it)
    assert 0.95 * kirsch < circle_area < kirsch, (circle_area, kirsch)
    assert kirsch == pytest.approx(circle.area * cases.P / cases.SHEAR, rel=1e-9)   # ΔA = A p / G
    assert area > circle_area, (name, area, circle_area)


SCENE = """\
name: shoe
geometry:
  kind: tunnel
  width: 40 m
  height: 40 m
  opening: {shape: horseshoe, centre: [20 m, 20 m], span: 8 m, wall_height: 3 m, invert_depth: 1 m}
rock: {young: 50 GPa, poisson: 0.25}
in_situ: {vertical: 8 MPa, horizontal_ratio: 0.5}
supports: {left: x, right: x, bottom: y, top: y}
stages:
  - {name: excavation, excavate: opening, steps: 1}
error_budget: 10 %
mesh: {size: 4 m}
outputs: {pictures: false, xdmf: false, monitor: [opening]}
"""


@pytest.mark.parametrize("opening", [
    "{shape: horseshoe, centre: [20 m, 20 m], span: 8 m, wall_height: 3 m, invert_depth: 1 m}",
    "{shape: D, centre: [20 m, 20 m], span: 8 m, wall_height: 3 m, arch_radius: 5 m}"], ids=["horseshoe", "D segmental"])
def test_the_extruded_scene_is_the_plane_strain_section(tmp_path, opening):
    """The scene (a horseshoe; a D with a segmental crown) extruded 2 m along the axis (rollers on front
    and back: plane strain), intact rock: the opening's mean normal displacement is the 2D scene's to
    the meshes' difference (tetrahedra against triangles of the same sizes, 0.5 m on the opening:
    observed -0.17 % and -0.04 %, bound 1 %)."""
    from rockjoint.scenes import load_scene, make_plan, run_scene
    from scene_cases import write
    scene2 = SCENE.replace("{shape: horseshoe, centre: [20 m, 20 m], span: 8 m, wall_height: 3 m, invert_depth: 1 m}",
                           opening)
    three = (scene2.replace("  height: 40 m\n", "  height: 40 m\n  length: 2 m\n")
             .replace("{left: x, right: x, bottom: y, top: y}", "{left: x, right: x, bottom: z, top: z, front: y, back: y}"))
    runs = {}
    for dim, body in ((2, scene2), (3, three)):
        scene = load_scene(write(tmp_path, body, f"scene{dim}.yaml"))
        plan = make_plan(scene)
        assert plan.dimension == dim
        runs[dim] = run_scene(scene, plan, str(tmp_path / f"out{dim}")).row("intact", "excavation")
    assert runs[3].monitors["opening"][-1] > 0.0
    assert runs[3].monitors["opening"][-1] == pytest.approx(runs[2].monitors["opening"][-1], rel=0.01)
