# SPDX-License-Identifier: MIT
"""rockjoint.meshes.tunnel_section: a rock section around a circular or horseshoe opening cut by joint sets.

Reference values are closed-form geometry: the section's area W·H minus the opening's (exactly, for
the polygon the mesh puts on the opening, and to the inscribed-polygon bound for the circle), the
opening's perimeter (2πa, and πa + 2h_w + invert for the horseshoe), the length of every joint
clipped to the rectangle minus the chord the opening cuts out, and the combinatorics of the split
mesh checked by test_meshes.check_split_invariants.
"""
import math

import numpy as np
import pytest

from rockjoint.meshes import CircularOpening, HorseshoeOpening, Joint, joint_set, tunnel_section
from test_meshes import check_split_invariants, facet_normal

W, H, CENTRE, A = 40.0, 30.0, (20.0, 14.0), 4.0
CIRCLE = CircularOpening(CENTRE, A)
# Bedding through and beside the opening (y = 12.5 and 15.5 cut it, 18.5 passes above) and a cross
# set dipping 60° toward +x, the first through the centre.
BEDDING = joint_set(3.0, 0.0, 90.0, origin=(20.0, 12.5), count=3, name="bedding")
CROSS = joint_set(6.0, 60.0, 90.0, origin=CENTRE, count=2, name="cross")
SIZES = dict(mesh_size=3.0, opening_mesh_size=0.5, joint_mesh_size=1.0)


def segment_lengths(points, facets):
    return np.linalg.norm(points[facets[:, 1]] - points[facets[:, 0]], axis=1)


def boundary(m, name):
    return m.boundary_facets[m.boundary_tags == m.tag("boundaries", name)]


def polygon_area(points, facets, centre=CENTRE):
    """Area of the polygon bounded by the segments, seen from a point inside it that sees all of it
    (both openings are convex around their centre): the sum of the triangles (centre, p, q)."""
    p, q = points[facets[:, 0]] - centre, points[facets[:, 1]] - centre
    return 0.5 * float(np.abs(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]).sum())


def deficit_bound(h, radius):
    """Upper bound of the relative area deficit of a polygon inscribed in a circle (or an arc) with
    chords at most h: each chord of angle φ = 2 asin(h / 2a) cuts a segment a²(φ - sin φ)/2 <= a²φ³/12,
    so the deficit relative to the sector's area is at most φ²/6. Half of that bounds the relative
    length deficit (φ - 2 sin(φ/2) <= φ³/24 per chord)."""
    phi = 2.0 * math.asin(h / (2.0 * radius))
    return phi ** 2 / 6.0


def clipped_length(point, dip_deg, opening_centre, radius):
    """Length of the 2D line (point, dip toward +x) inside [0, W] x [0, H] minus the chord in the circle."""
    return clipped_length3(point, dip_deg, opening_centre, radius, W, H)


def clipped_length3(point, dip_deg, opening_centre, radius, width, height):
    """clipped_length in the section [0, width] x [0, height]."""
    d = math.radians(dip_deg)
    t = np.array([math.cos(d), -math.sin(d)])
    p = np.asarray(point, float)
    lo, hi = -1e9, 1e9
    for axis, size in ((0, width), (1, height)):
        if abs(t[axis]) > 1e-14:
            s0, s1 = sorted(((0.0 - p[axis]) / t[axis], (size - p[axis]) / t[axis]))
            lo, hi = max(lo, s0), min(hi, s1)
    n = np.array([t[1], -t[0]])
    dist = abs(float(n @ (np.asarray(opening_centre) - p)))
    chord = 2.0 * math.sqrt(radius ** 2 - dist ** 2) if dist < radius else 0.0
    return (hi - lo) - chord


@pytest.fixture(scope="module")
def jointed():
    return tunnel_section(W, H, CIRCLE, BEDDING + CROSS, **SIZES)


def test_circular_section_area_and_opening_perimeter(jointed):
    m = jointed
    check_split_invariants(m)
    ring = boundary(m, "opening")
    area = m.cell_measures().sum()
    # exactly the rectangle minus the polygon the mesh puts on the circle
    assert area == pytest.approx(W * H - polygon_area(m.points, ring), rel=1e-12)
    # that polygon is inscribed in the circle: its area falls short of πa² by at most (h/a)²/6
    h = segment_lengths(m.points, ring).max()
    assert h <= 1.3 * SIZES["opening_mesh_size"]  # refined toward the opening
    deficit = 1.0 - polygon_area(m.points, ring) / CIRCLE.area
    assert 0.0 < deficit <= deficit_bound(h, A)
    assert area == pytest.approx(W * H - math.pi * A ** 2, rel=deficit_bound(h, A) * CIRCLE.area / (W * H))
    assert segment_lengths(m.points, ring).sum() == pytest.approx(2 * math.pi * A, rel=deficit_bound(h, A) / 4.0 + 1e-12)
    assert np.allclose(np.linalg.norm(m.points[ring.ravel()] - CENTRE, axis=1), A, rtol=1e-9)
    for name, length in (("left", H), ("right", H), ("bottom", W), ("top", W)):
        assert segment_lengths(m.points, boundary(m, name)).sum() == pytest.approx(length, rel=1e-12)


def test_joints_are_clipped_by_the_opening_and_end_on_it(jointed):
    m = jointed
    fm = m.joint_facets_minus
    on_opening = set(m.glue[boundary(m, "opening")].ravel().tolist())
    for joint in BEDDING + CROSS:
        sel = m.joint_tags == m.tag("joints", joint.name)
        length = segment_lengths(m.points, fm[sel]).sum()
        assert length == pytest.approx(clipped_length(joint.point, joint.dip, CENTRE, A), rel=1e-9), joint.name
        # a joint that crosses the opening ends on it: two of its nodes lie on the opening's boundary
        dist = abs(float(np.array([-math.sin(math.radians(joint.dip)), -math.cos(math.radians(joint.dip))])
                         @ (np.asarray(CENTRE) - joint.point)))
        ends = on_opening & set(m.glue[fm[sel]].ravel().tolist())
        assert len(ends) == (2 if dist < A else 0), joint.name
    # no joint facet inside the opening
    mid = m.points[fm].mean(axis=1)
    assert np.all(np.linalg.norm(mid - CENTRE, axis=1) > A * 0.99)


def test_pairs_count_is_the_number_of_joint_segments_and_blocks_are_counted(jointed):
    m = jointed
    # every pair is one joint segment; the joint segments tile the clipped joints (above), and the
    # refinement puts them at about joint_mesh_size (or finer near the opening)
    h = segment_lengths(m.points, m.joint_facets_minus)
    assert h.max() <= 1.3 * SIZES["joint_mesh_size"]
    total = sum(clipped_length(j.point, j.dip, CENTRE, A) for j in BEDDING + CROSS)
    assert m.joint_facets_minus.shape[0] >= total / (1.3 * SIZES["joint_mesh_size"])
    # blocks: 4 bedding strips x 3 cross strips = 12 regions; the opening splits none of them apart
    # (it removes the pieces of bedding_1, bedding_2 and cross_1 inside it, merging nothing)
    assert len(m.names["blocks"]) == 12
    assert sorted(m.names["joints"].values()) == sorted(j.name for j in BEDDING + CROSS)


def test_intact_variant_is_the_same_triangulation_as_one_block(jointed):
    intact = tunnel_section(W, H, CIRCLE, BEDDING + CROSS, intact=True, **SIZES)
    assert intact.names["joints"] == {} and list(intact.names["blocks"].values()) == ["block_1"]
    assert intact.joint_facets_minus.shape[0] == 0
    assert intact.points.shape[0] == jointed.num_original_nodes  # nothing split

    def triangles(m):
        return sorted(tuple(sorted(map(tuple, np.round(t, 9)))) for t in m.points[m.cells])

    assert triangles(intact) == triangles(jointed)
    assert intact.cell_measures().sum() == pytest.approx(jointed.cell_measures().sum(), rel=1e-12)


def test_intact_without_joints_is_refined_toward_the_opening():
    m = tunnel_section(W, H, CIRCLE, mesh_size=4.0, opening_mesh_size=0.4, opening_refine_distance=5.0)
    check_split_invariants(m)
    ring = boundary(m, "opening")
    assert segment_lengths(m.points, ring).max() <= 1.3 * 0.4
    # coarse beyond the refinement distance (the bottom is 10 m from the opening, the others farther)
    outer = np.concatenate([boundary(m, s) for s in ("left", "right", "bottom", "top")])
    assert segment_lengths(m.points, outer).min() >= 0.7 * 4.0


@pytest.mark.parametrize("invert_depth", [0.0, 1.5])
def test_horseshoe_area_and_perimeter(invert_depth):
    shoe = HorseshoeOpening(CENTRE, 3.0, 2.5, invert_depth)
    m = tunnel_section(W, H, shoe, [Joint((20.0, 13.0), 0.0, 90.0, "bed")], mesh_size=3.0, opening_mesh_size=0.3)
    check_split_invariants(m)
    ring = boundary(m, "opening")
    # closed forms: crown πa²/2, walls 2a·h_w, invert circular segment R²(θ - sinθ cosθ)
    a, hw, s = 3.0, 2.5, invert_depth
    area = 0.5 * math.pi * a * a + 2 * a * hw
    perimeter = math.pi * a + 2 * hw + 2 * a
    if s:
        R = (a * a + s * s) / (2 * s)
        th = math.asin(a / R)
        area += R * R * (th - math.sin(th) * math.cos(th))
        perimeter += 2 * R * th - 2 * a
    assert shoe.area == pytest.approx(area, rel=1e-14) and shoe.perimeter == pytest.approx(perimeter, rel=1e-14)
    h = segment_lengths(m.points, ring).max()
    assert m.cell_measures().sum() == pytest.approx(W * H - polygon_area(m.points, ring), rel=1e-12)
    assert polygon_area(m.points, ring) == pytest.approx(area, rel=deficit_bound(h, a))
    assert segment_lengths(m.points, ring).sum() == pytest.approx(perimeter, rel=deficit_bound(h, a) / 4.0)
    # the bedding joint crosses the walls: its length is the section width minus the opening's 2a
    sel = m.joint_tags == m.tag("joints", "bed")
    assert segment_lengths(m.points, m.joint_facets_minus[sel]).sum() == pytest.approx(W - 2 * a, rel=1e-9)


@pytest.mark.parametrize("invert_depth", [0.0, 1.5])
def test_segmental_arch_area_perimeter_and_extrusion(invert_depth):
    """A flatter crown: arch radius R = 5 m over the 6 m span (a = 3 m), centre sqrt(R² - a²) = 4 m
    below the springline, rise 1 m, half angle asin(3/5). Closed forms: crown segment R²(θ - sinθ cosθ)
    and arc 2Rθ, the walls and the invert as before. Meshed in 2D (the mesh's hole is the inscribed
    polygon) and extruded to 3D (volume (W H - area) L to the polygon's deficit)."""
    shoe = HorseshoeOpening(CENTRE, 3.0, 2.5, invert_depth, arch_radius=5.0)
    th = math.asin(0.6)
    area, perimeter = 25.0 * (th - 0.6 * 0.8) + 2 * 3.0 * 2.5, 10.0 * th + 2 * 2.5 + 6.0
    if invert_depth:
        R = (9.0 + invert_depth ** 2) / (2 * invert_depth)
        ti = math.asin(3.0 / R)
        area += R * R * (ti - math.sin(ti) * math.cos(ti))
        perimeter += 2 * R * ti - 6.0
    assert shoe.rise == pytest.approx(1.0, rel=1e-14)
    assert shoe.area == pytest.approx(area, rel=1e-14) and shoe.perimeter == pytest.approx(perimeter, rel=1e-14)
    assert shoe.bounds() == pytest.approx((17.0, 14.0 - 2.5 - invert_depth, 23.0, 15.0), rel=1e-14)
    m = tunnel_section(W, H, shoe, [Joint((20.0, 14.5), 0.0, 90.0, "crown")], mesh_size=3.0, opening_mesh_size=0.3)
    check_split_invariants(m)
    ring = boundary(m, "opening")
    h = segment_lengths(m.points, ring).max()
    assert polygon_area(m.points, ring) == pytest.approx(area, rel=deficit_bound(h, 3.0))
    # the crown joint at 0.5 m above the springline: chord 2 sqrt(R² - 4.5²) of the arch
    sel = m.joint_tags == m.tag("joints", "crown")
    assert segment_lengths(m.points, m.joint_facets_minus[sel]).sum() == pytest.approx(
        W - 2 * math.sqrt(25.0 - 4.5 ** 2), rel=1e-9)
    L = 2.0
    m3 = tunnel_section(W, H, shoe, mesh_size=3.0, opening_mesh_size=0.5, length=L)
    assert m3.cell_type == "tetrahedron" and "opening" in m3.names["boundaries"].values()
    volume = m3.cell_measures().sum()
    assert (W * H - area) * L <= volume * (1 + 1e-12) and volume <= (W * H - area * (1 - deficit_bound(0.5, 3.0))) * L


def test_arch_radius_below_half_the_span_is_refused():
    with pytest.raises(ValueError, match=r"arch_radius \(2.9 m\) is less than half the span \(3 m\)"):
        HorseshoeOpening(CENTRE, 3.0, 2.5, arch_radius=2.9)


def horseshoe_chord_of_vertical(shoe, d):
    """Closed form: the length of the vertical line x = x_c + d (|d| < a) inside a horseshoe, from
    its invert (flat at y_c - h_w, or the arc of radius R = (a² + s²)/2s through the wall feet) to
    its crown y_c + sqrt(a² - d²)."""
    (_, yc), a, hw, s = shoe.centre, shoe.radius, shoe.wall_height, shoe.invert_depth
    bottom = yc - hw
    if s:
        R = (a * a + s * s) / (2 * s)
        bottom = yc - hw - s + R - math.sqrt(R * R - d * d)
    return yc + math.sqrt(a * a - d * d) - bottom


@pytest.mark.parametrize("invert_depth", [0.0, 1.5])
def test_crossing_of_the_openings_is_the_closed_form_chord(invert_depth):
    """crossing(a, b) gives the parameters where the line a + t (b - a) enters and leaves the
    opening: the chords of a circle (2 sqrt(a² - h²)) and of a horseshoe's walls, crown and invert."""
    lo, hi = CIRCLE.crossing((0.0, 15.0), (40.0, 15.0))
    assert 40.0 * (hi - lo) == pytest.approx(2 * math.sqrt(A * A - 1.0), rel=1e-13)
    assert 40.0 * lo == pytest.approx(20.0 - math.sqrt(A * A - 1.0), rel=1e-13)
    assert CIRCLE.crossing((0.0, 18.5), (40.0, 18.5)) is None   # misses
    assert CIRCLE.crossing((0.0, 18.0), (40.0, 18.0)) is None   # tangent: touches only
    shoe = HorseshoeOpening(CENTRE, 3.0, 2.5, invert_depth)
    for y, chord in ((13.0, 6.0), (15.5, 2 * math.sqrt(9.0 - 1.5 ** 2))):   # walls, crown
        lo, hi = shoe.crossing((0.0, y), (40.0, y))
        assert 40.0 * (hi - lo) == pytest.approx(chord, rel=1e-13)
    lo, hi = shoe.crossing((21.0, 0.0), (21.0, 30.0))   # through the invert and the crown
    assert 30.0 * (hi - lo) == pytest.approx(horseshoe_chord_of_vertical(shoe, 1.0), rel=1e-13)
    assert shoe.crossing((0.0, 17.5), (40.0, 17.5)) is None
    assert shoe.crossing((24.0, 0.0), (24.0, 30.0)) is None


@pytest.mark.parametrize("invert_depth", [0.0, 1.5])
def test_joints_crossing_a_horseshoe_end_on_its_outline(invert_depth):
    """Joints through the walls, the crown and the invert are cut where they meet the outline:
    each keeps the section's width (height) minus the closed-form chord, ends on two nodes of the
    opening's boundary, and none of its facets lies inside the opening."""
    shoe = HorseshoeOpening(CENTRE, 3.0, 2.5, invert_depth)
    joints = [Joint((20.0, 13.0), 0.0, 90.0, "walls"), Joint((20.0, 15.5), 0.0, 90.0, "crown"),
              Joint((21.0, 14.0), 90.0, 90.0, "vertical")]
    m = tunnel_section(W, H, shoe, joints, mesh_size=3.0, opening_mesh_size=0.3, joint_mesh_size=1.0)
    check_split_invariants(m)
    assert m.names["joints"] == {100: "walls", 101: "crown", 102: "vertical"}
    assert sorted(m.names["boundaries"].values()) == ["bottom", "left", "opening", "right", "top"]
    expected = {"walls": W - 6.0, "crown": W - 2 * math.sqrt(9.0 - 1.5 ** 2),
                "vertical": H - horseshoe_chord_of_vertical(shoe, 1.0)}
    on_opening = set(m.glue[boundary(m, "opening")].ravel().tolist())
    for name, length in expected.items():
        facets = m.joint_facets_minus[m.joint_tags == m.tag("joints", name)]
        assert segment_lengths(m.points, facets).sum() == pytest.approx(length, rel=1e-9), name
        assert len(on_opening & set(m.glue[facets].ravel().tolist())) == 2, name
    # no joint facet inside the horseshoe (its midpoint strictly inside by more than round-off)
    x, y = m.points[m.joint_facets_minus].mean(axis=1).T
    (xc, yc), a, hw = CENTRE, 3.0, 2.5
    inside_walls = (np.abs(x - xc) < a - 1e-9) & (y < yc) & (y > yc - hw + 1e-9)
    inside_crown = (y >= yc) & (np.hypot(x - xc, y - yc) < a - 1e-9)
    assert not np.any(inside_walls | inside_crown)


def test_dense_joint_sets_leave_nothing_inside_the_opening():
    """Many joints crossing a circular opening (the continuum bench's sets at s = 1 m): every joint
    keeps its closed-form length (the section's chord minus the opening's), its tag (100 + its
    index) and its name; no joint facet lies inside the opening; the joint nodes on the opening lie
    on the circle."""
    width, centre, radius = 40.0, (20.0, 20.0), 4.0
    bedding = joint_set(1.0, 0.0, 90.0, origin=(20.0, 0.65), count=40, name="bedding")
    normal = np.array([math.sin(math.radians(60.0)), math.cos(math.radians(60.0))])
    origin = np.asarray(centre) - 13.65 * 2.0 * normal
    cross = joint_set(2.0, 60.0, 90.0, origin=tuple(origin), count=28, name="cross")
    joints = [j for j in bedding + cross
              if clipped_length3(j.point, j.dip, centre, radius, width, width) > 0.0]
    m = tunnel_section(width, width, CircularOpening(centre, radius), joints, mesh_size=1.5,
                       opening_mesh_size=0.375, opening_refine_distance=8.0)
    check_split_invariants(m)
    assert m.names["joints"] == {100 + i: j.name for i, j in enumerate(joints)}
    for j in joints:
        facets = m.joint_facets_minus[m.joint_tags == m.tag("joints", j.name)]
        assert segment_lengths(m.points, facets).sum() == pytest.approx(
            clipped_length3(j.point, j.dip, centre, radius, width, width), rel=1e-9), j.name
    mid = m.points[m.joint_facets_minus].mean(axis=1)
    assert np.linalg.norm(mid - centre, axis=1).min() > radius * (1 - 1e-3)
    ends = np.array(sorted(set(m.glue[m.joint_facets_minus].ravel().tolist())
                           & set(m.glue[boundary(m, "opening")].ravel().tolist())))
    assert ends.size > 0
    assert np.allclose(np.linalg.norm(m.points[ends] - centre, axis=1), radius, rtol=1e-9)


# ---- bad input ----------------------------------------------------------------------------------
@pytest.mark.parametrize("opening, message", [
    (CircularOpening((2.0, 14.0), 4.0), "not inside the section"),
    (CircularOpening((20.0, 28.0), 4.0), "not inside the section"),
    (HorseshoeOpening((20.0, 4.0), 3.0, 3.0), "not inside the section"),
])
def test_opening_outside_the_section_is_refused(opening, message):
    with pytest.raises(ValueError, match=message):
        tunnel_section(W, H, opening, mesh_size=2.0)


def test_joints_that_miss_the_rock_are_refused():
    # entirely above the section
    with pytest.raises(ValueError, match="'high'.*does not cut"):
        tunnel_section(W, H, CIRCLE, [Joint((20.0, 35.0), 0.0, 90.0, "high")], mesh_size=3.0)
    # a vertical joint bounded by two bedding joints that both cross the opening: all inside it
    bed = [Joint((20.0, 12.0), 0.0, 90.0, "lower"), Joint((20.0, 16.0), 0.0, 90.0, "upper")]
    inside = Joint((20.0, 14.0), 90.0, 90.0, "inside", ("lower", "upper"))
    with pytest.raises(ValueError, match="'inside' misses the rock section"):
        tunnel_section(W, H, CIRCLE, bed + [inside], mesh_size=3.0)


def test_tangent_joint_and_joint_along_the_invert_are_refused():
    with pytest.raises(ValueError, match="'tangent' touches the opening's outline"):
        tunnel_section(W, H, CIRCLE, [Joint((20.0, 18.0), 0.0, 90.0, "tangent")], mesh_size=3.0)
    shoe = HorseshoeOpening(CENTRE, 3.0, 2.5)  # flat invert at y = 11.5
    with pytest.raises(ValueError, match="'floor'"):
        tunnel_section(W, H, shoe, [Joint((20.0, 11.5), 0.0, 90.0, "floor")], mesh_size=3.0)


@pytest.mark.parametrize("kwargs, message", [
    (dict(mesh_size=-1.0), "mesh_size must be a finite number > 0"),
    (dict(mesh_size=3.0, opening_mesh_size=5.0), "opening_mesh_size .* must not exceed mesh_size"),
    (dict(mesh_size=3.0, joint_mesh_size=float("nan")), "joint_mesh_size must be a finite number > 0"),
    (dict(mesh_size=20.0), "exceeds half the section size"),
])
def test_bad_sizes_are_named(kwargs, message):
    with pytest.raises(ValueError, match=message):
        tunnel_section(W, H, CIRCLE, **kwargs)


def test_bad_opening_and_names_are_named():
    with pytest.raises(ValueError, match="CircularOpening.radius must be a finite number > 0"):
        CircularOpening(CENTRE, 0.0)
    with pytest.raises(ValueError, match="invert_depth must be in"):
        HorseshoeOpening(CENTRE, 3.0, 2.0, 4.0)
    with pytest.raises(ValueError, match="opening must be a CircularOpening or a HorseshoeOpening"):
        tunnel_section(W, H, (CENTRE, A), mesh_size=3.0)
    with pytest.raises(ValueError, match="cannot be named 'opening'"):
        tunnel_section(W, H, CIRCLE, [Joint((20.0, 5.0), 0.0, 90.0, "opening")], mesh_size=3.0)


def test_quarter_section_of_a_symmetric_problem():
    m = tunnel_section(10.0, 8.0, CircularOpening((0.0, 0.0), 1.0), mesh_size=1.0, opening_mesh_size=0.1,
                       quarter=True)
    check_split_invariants(m)
    ring = boundary(m, "opening")
    h = segment_lengths(m.points, ring).max()
    # the quarter ring: the rectangle minus πa²/4 (the polygon is inscribed), arc length πa/2
    polygon = polygon_area(m.points, ring, centre=(0.0, 0.0))
    assert m.cell_measures().sum() == pytest.approx(80.0 - polygon, rel=1e-12)
    assert polygon == pytest.approx(math.pi / 4, rel=deficit_bound(h, 1.0))
    assert segment_lengths(m.points, ring).sum() == pytest.approx(math.pi / 2, rel=deficit_bound(h, 1.0) / 4.0)
    # the symmetry planes start at the opening: x = 0 from y = a, y = 0 from x = a
    assert segment_lengths(m.points, boundary(m, "left")).sum() == pytest.approx(7.0, rel=1e-12)
    assert segment_lengths(m.points, boundary(m, "bottom")).sum() == pytest.approx(9.0, rel=1e-12)
    with pytest.raises(ValueError, match="quarter=True needs a CircularOpening centred at"):
        tunnel_section(10.0, 8.0, CircularOpening((1.0, 0.0), 1.0), mesh_size=1.0, quarter=True)


def test_3d_extrusion_volumes_joint_areas_and_faces():
    """The section extruded along y: joints become planes (area = clipped length x L), the opening a
    prism (lateral area 2πa L to the inscribed-polygon bound), front/back faces the 2D section."""
    a, L = 2.0, 6.0
    opening = CircularOpening((10.0, 8.0), a)
    joints = joint_set(3.0, 0.0, 90.0, origin=(10.0, 6.5), count=2, name="bed") + [Joint((10.0, 8.0), 60.0, 90.0,
                                                                                          "cross")]
    m = tunnel_section(20.0, 16.0, opening, joints, mesh_size=2.0, opening_mesh_size=0.5, length=L)
    assert m.cell_type == "tetrahedron" and m.points.shape[1] == 3
    check_split_invariants(m)
    f = m.boundary_facets
    x = m.points[f]
    area = 0.5 * np.linalg.norm(np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]), axis=1)
    by_name = {name: area[m.boundary_tags == tag].sum() for tag, name in m.names["boundaries"].items()}
    ring = m.points[f[m.boundary_tags == m.tag("boundaries", "opening")]]
    h = np.linalg.norm(ring[:, [1, 2, 0]] - ring, axis=2).max()
    bound = deficit_bound(h, a)
    assert by_name["opening"] == pytest.approx(2 * math.pi * a * L, rel=bound)
    for name, expected in (("left", 16.0 * L), ("right", 16.0 * L), ("bottom", 20.0 * L), ("top", 20.0 * L)):
        assert by_name[name] == pytest.approx(expected, rel=1e-12), name
    for name in ("front", "back"):
        assert by_name[name] == pytest.approx(320.0 - math.pi * a * a, rel=bound * math.pi * a * a / 320.0), name
    volume = m.cell_measures().sum()
    assert (320.0 - math.pi * a * a) * L <= volume <= (320.0 - math.pi * a * a * (1 - bound)) * L
    fm = m.joint_facets_minus
    xj = m.points[fm]
    jarea = 0.5 * np.linalg.norm(np.cross(xj[:, 1] - xj[:, 0], xj[:, 2] - xj[:, 0]), axis=1)
    W_, H_ = 20.0, 16.0
    for joint in joints:
        sel = m.joint_tags == m.tag("joints", joint.name)
        expected = clipped_length3(joint.point, joint.dip, (10.0, 8.0), a, W_, H_) * L
        assert jarea[sel].sum() == pytest.approx(expected, rel=1e-9), joint.name
        # the joint planes are planes y-independent: the section's normal with no y component
        n = facet_normal(m.points[fm[sel]])
        d = math.radians(joint.dip)
        assert np.allclose(np.abs(n), [math.sin(d), 0.0, math.cos(d)], atol=1e-9)


@pytest.mark.parametrize("opening", [CIRCLE, HorseshoeOpening(CENTRE, 3.0, 2.5, 1.0)])
@pytest.mark.parametrize("joint_mesh_size", [None, 0.7])
def test_joint_pieces_get_the_node_counts_gmsh_gives_them(opening, joint_mesh_size, monkeypatch):
    """The 2D section's joint pieces are given their node counts up front (tunnel._set_node_counts,
    from planar_section.line_node_counts on the same size fields), which spares gmsh integrating its
    field along each of them: the counts are the ones gmsh finds itself. Measured against gmsh's
    own 1D meshing of the same model: every joint within one facet (gmsh samples the opening's
    distance at points, the counts here use the exact distance, so a piece whose integral sits at
    an integer may tip either way), at most 10 % of the joints off at all, the same cells to 1 %."""
    from rockjoint.meshes import tunnel, unit_normal
    origin = tuple(np.asarray(CENTRE) - 10.2 * 1.5 * np.asarray(unit_normal(60.0, 90.0, 2)))
    joints = (joint_set(1.0, 0.0, 90.0, origin=(20.0, 0.3), count=28, name="bedding")
              + joint_set(1.5, 60.0, 90.0, origin=origin, count=20, name="cross"))
    sizes = dict(mesh_size=2.0, opening_mesh_size=0.5, opening_refine_distance=4.0, joint_mesh_size=joint_mesh_size)
    calls = []
    given = tunnel._set_node_counts
    monkeypatch.setattr(tunnel, "_set_node_counts", lambda *args: calls.append(len(args[1])) or given(*args))
    m = tunnel_section(W, H, opening, joints, **sizes)
    monkeypatch.setattr(tunnel, "_set_node_counts", lambda *args: None)
    natural = tunnel_section(W, H, opening, joints, **sizes)
    assert len(calls) == 1 and calls[0] > 500
    check_split_invariants(m)
    ours = np.bincount(m.joint_tags - 100, minlength=len(joints))
    gmsh_own = np.bincount(natural.joint_tags - 100, minlength=len(joints))
    assert np.abs(ours - gmsh_own).max() <= 1
    assert np.count_nonzero(ours != gmsh_own) <= 0.1 * len(joints)
    assert m.cells.shape[0] == pytest.approx(natural.cells.shape[0], rel=0.01)