# SPDX-License-Identifier: MIT
"""The intact-rock convergence of an opening (tests/python/test_fem_opening_convergence.py): a
section W x W with rollers on its four sides, the in-situ stress (σ_v = p, σ_h = K p, compression)
then the excavation of the opening, P1, plane strain; what an engineer reads off it: the crown's
settlement, the floor's heave, the wall closure at mid wall height and the area the opening loses."""
import math

import numpy as np
from mpi4py import MPI

from rockjoint import meshes
from rockjoint.fem import InSituStress, JointedRockModel, NewtonOptions, distribute
from rockjoint.fem.output.probe import probe

#: rock and in-situ stress of the study; the half span a = 1 m (every length in units of a)
YOUNG, POISSON, P = 20e9, 0.25, 10e6
SHEAR = YOUNG / (2.0 * (1.0 + POISSON))
WIDTH = 20.0                      # section W = 20 a; the opening's springline in its middle
CENTRE = (0.5 * WIDTH, 0.5 * WIDTH)
#: the shapes (docs/tunnel.md): a = 1 m, walls 1 m high; the horseshoe's invert sags 0.5 m
HORSESHOE = meshes.HorseshoeOpening(CENTRE, 1.0, 1.0, invert_depth=0.5)
D_SHAPE = meshes.HorseshoeOpening(CENTRE, 1.0, 1.0)


def equal_area_circle(opening) -> meshes.CircularOpening:
    """The circle of the opening's area, centred at the middle of its box."""
    x0, y0, x1, y1 = opening.bounds()
    return meshes.CircularOpening((0.5 * (x0 + x1), 0.5 * (y0 + y1)), math.sqrt(opening.area / math.pi))


def points(opening) -> dict:
    """Where the closures are read: the crown's top, the floor's lowest point, the walls at mid
    height (a circle: its top, bottom and the ends of its horizontal diameter)."""
    x0, y0, x1, y1 = opening.bounds()
    xm = 0.5 * (x0 + x1)
    wall = opening.centre[1] - 0.5 * getattr(opening, "wall_height", 0.0)
    return {"crown": (xm, y1), "floor": (xm, y0), "left": (x0, wall), "right": (x1, wall)}


def solve(opening, h, k0=1.0, comm=MPI.COMM_SELF) -> dict:
    """Crown settlement, floor heave, wall closure (inward positive) and area loss ΔA = ∮ u·n ds
    [m, m²] after the excavation, with element size h on the opening growing to 8 h (at most
    2 m) over 3 a: halving h halves every element size."""
    jm = meshes.tunnel_section(WIDTH, WIDTH, opening, mesh_size=min(8.0 * h, 2.0), opening_mesh_size=h,
                               opening_refine_distance=3.0, comm=comm)
    model = JointedRockModel(distribute(jm, comm), rock=(YOUNG, POISSON), joints={},
                             newton=NewtonOptions(verbose=False))
    for side, component in (("left", "x"), ("right", "x"), ("bottom", "y"), ("top", "y")):
        model.fix(side, component)
    model.set_in_situ_stress(InSituStress.uniform(np.diag([-k0 * P, -P])))
    model.solve(name="in-situ")
    model.excavate("opening")
    model.solve(name="excavation")
    at = points(opening)
    u = probe(model.u, np.array([at[k] for k in ("crown", "floor", "left", "right")]))
    return {"crown": -u[0, 1], "floor": u[1, 1], "walls": u[2, 0] - u[3, 0],
            "area": model.mean_normal_displacement("opening") * opening.perimeter,
            "dofs": model.u.function_space.dofmap.index_map.size_global * 2}


def richardson(values) -> tuple:
    """(extrapolated value, observed order) of the three finest of a sequence on element sizes
    halving: order r = log2(Δ1/Δ2) from the last two differences, value = last + Δ2 / (2^r - 1)."""
    a, b, c = values[-3:]
    r = math.log2((b - a) / (c - b))
    return c + (c - b) / (2.0 ** r - 1.0), r


def errors(values) -> tuple:
    """(reference, observed order, relative errors of all but the finest) of a sequence on element
    sizes halving: the reference is the Richardson extrapolation of its three finest."""
    reference, order = richardson(values)
    return reference, order, [abs(v - reference) / abs(reference) for v in values[:-1]]


def convergence(levels=(4, 8, 16, 32)) -> str:
    """The mesh-convergence table of docs/tunnel.md (K0 = 1): each quantity's relative error at
    h = a/n against the Richardson reference of the three finest, and the observed order."""
    lines = [f"{'shape':10}{'quantity':>10}" + "".join(f"{'a/' + str(n):>9}" for n in levels[:-1])
             + f"{'reference':>12}{'order':>7}"]
    for name, shape in (("horseshoe", HORSESHOE), ("D", D_SHAPE)):
        runs = [solve(shape, 1.0 / n) for n in levels]
        for key, unit in (("crown", 1e3), ("floor", 1e3), ("walls", 1e3), ("area", 1e4)):
            reference, order, errs = errors([r[key] for r in runs])
            lines.append(f"{name:10}{key:>10}" + "".join(f"{100 * e:8.2f}%" for e in errs)
                         + f"{reference * unit:12.4f}{order:7.2f}")
    return "\n".join(lines)


def kirsch_closures(circle, k0=1.0) -> dict:
    """The circle's crown settlement, floor heave, wall closure and area loss, Kirsch's closed form
    (rockjoint.reference.kirsch: u_r at the wall, Brady & Brown Eq. 7.8; ΔA = ∮ -u_r ds)."""
    from rockjoint.reference import KirschSolution  # the circle's closed form, only where compared
    kirsch = KirschSolution(circle.radius, P, k0, YOUNG, POISSON, circle.centre)
    a = circle.radius
    ur = kirsch.excavation_displacement(np.full(3, a), np.array([0.0, 0.5 * math.pi, -0.5 * math.pi]))[0]
    theta = np.linspace(0.0, 2.0 * math.pi, 721)[:-1]
    area = -kirsch.excavation_displacement(np.full(theta.size, a), theta)[0].mean() * 2.0 * math.pi * a
    return {"crown": -ur[1], "floor": -ur[2], "walls": -2.0 * ur[0], "area": area}


def comparison(n: int = 32) -> str:
    """The table of docs/tunnel.md: each shape at h = a/n beside the circle of equal area (FE on the
    same section, and Kirsch), K0 = 1 and 0.5; closures in mm, area loss in cm² (a = 1 m, p = 10 MPa,
    E = 20 GPa, ν = 0.25)."""
    lines = [f"{'K0':>4} {'shape':10}{'quantity':>10}{'shape FE':>10}{'circle FE':>10}{'Kirsch':>10}{'ratio':>8}"]
    for k0 in (1.0, 0.5):
        for name, shape in (("horseshoe", HORSESHOE), ("D", D_SHAPE)):
            circle = equal_area_circle(shape)
            fe, ref, closed = solve(shape, 1.0 / n, k0), solve(circle, 1.0 / n, k0), kirsch_closures(circle, k0)
            for key, unit in (("crown", 1e3), ("floor", 1e3), ("walls", 1e3), ("area", 1e4)):
                lines.append(f"{k0:4.1f} {name:10}{key:>10}{fe[key] * unit:10.4f}{ref[key] * unit:10.4f}"
                             f"{closed[key] * unit:10.4f}{fe[key] / ref[key]:8.3f}")
    return "\n".join(lines)


if __name__ == "__main__":   # the tables of docs/tunnel.md
    print(convergence())
    print(comparison())
