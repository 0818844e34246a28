# SPDX-License-Identifier: MIT
"""`rockjoint run`: a scene through the staged API, jointed beside intact on the same mesh (the
FE stack is needed: rockjoint.scenes imports this module only when a scene is run).

Outputs go to a fresh temporary folder beside the output folder and are moved in only when the
whole run succeeded, so a failed run leaves nothing half-written.
"""
from __future__ import annotations

import dataclasses
import logging
import os
import shutil
import tempfile
import time

import numpy as np
from mpi4py import MPI

from ..continuum import EquivalentContinuum, JointSet
from .. import curve_table
from ..joint import joint_behaviours
from ..meshes import joint_sets_of
from ..fem import (ConvergenceError, InSituStress, JointedRockModel, LinearSolveError, NewtonOptions,
                            ShearState, distribute)
from ..fem.water.joint_pressure import set_joint_pressure
from . import water as scene_water
from . import geometry, joint_laws, pictures, slope_keys, slope_picture, slope_run, statics
from .summary import summary_table  # noqa: F401  (re-exported: `rockjoint run` prints it)

log = logging.getLogger("rockjoint.scenes")


@dataclasses.dataclass
class StageRow:
    """One stage of one model: monitored mean displacements [m] and the joints' state."""

    model: str
    stage: str
    newton_iterations: int
    monitors: dict                 # boundary -> mean displacement vector [m]
    max_displacement: float        # max |u| [m]
    max_closure: float = 0.0       # [m], all joints
    max_normal_stress: float = 0.0  # [Pa]
    slipping: int = 0              # joint points in the slip state (smeared: quadrature points)
    max_slip: float = 0.0          # the largest |slip| [m] of the discrete joints (slipped so far)
    per_set: dict = dataclasses.field(default_factory=dict)  # set -> (max closure [m], max σ_n [Pa])
    slipping_per_set: dict = dataclasses.field(default_factory=dict)  # set -> slipping points
    smeared: tuple = ()            # the sets of per_set that are smeared (equivalent continuum)
    #: discrete sets with points past their table (the model's own check, from the points' status)
    past_table: tuple = ()
    #: the stage's water (scenes.water.StageWater: flow rates, the network, the largest joint
    #: pressure, the joints opened by water, the coupling's iterations)
    water: object = dataclasses.field(default_factory=scene_water.StageWater, repr=False)

    @property
    def flow_rates(self) -> dict | None:
        """{boundary with a condition: flow into the rock there}, or None (water.flow_rates)."""
        return self.water.flow_rates

    @property
    def network(self):
        """The jointed model's NetworkFlow of the stage, or None."""
        return self.water.network


class NoEquilibrium(RuntimeError):
    """A valid scene whose jointed model has no static equilibrium (statics.diagnose's words)."""


@dataclasses.dataclass
class SceneResult:
    """What running a scene produced: its plan, one StageRow per model and stage, the law tables
    used, the files written, the wall-clock time [s] and the geometric dimension solved.
    """

    plan: object
    rows: list
    tables: dict
    files: list
    seconds: float
    gdim: int = 0                  # geometric dimension of the meshes solved
    safety: object = None          # a slope's factor of safety (slope_run.SlopeSafety), if asked for

    def row(self, model: str, stage: str) -> StageRow:
        """The StageRow of `model` at `stage` (StopIteration if there is none)."""
        return next(r for r in self.rows if r.model == model and r.stage == stage)


def _components(text: str):
    return "all" if text in ("all", "xyz") else (text if len(text) == 1 else list(text))


def build_model(scene, plan, dmesh, tables: dict | None):
    """A JointedRockModel of the scene on `dmesh` (tables None: the intact model)."""
    d = scene.data
    rock = d["rock"]
    blocks = dmesh.names["blocks"].values()
    unknown = set(rock.get("blocks", {})) - set(blocks)
    if unknown:
        scene.fail(("rock", "blocks", sorted(unknown)[0]), f"no such block; blocks: {', '.join(blocks)}")
    own = {b: rock.get("blocks", {}).get(b, rock) for b in blocks}
    rocks = {b: (v["young"], v["poisson"]) for b, v in own.items()}
    kw = {}
    if tables is not None:
        of = joint_sets_of(dmesh.names)   # {joint: its set}, as the mesh records it
        names = list(of)
        j = d["joints"]
        kw = dict(joints={n: tables[of[n]] for n in names},
                  shear_stiffness_ratio={n: j[of[n]]["shear_stiffness_ratio"] for n in names},
                  residual_stiffness={n: j[of[n]]["residual_stiffness"] for n in names},
                  strength={n: scene.strengths[of[n]] if plan.slip.get(of[n]) else None for n in names})
    if tables is not None and plan.smeared:
        kw["continuum"] = smeared_material(scene, plan, tables, rocks)
    if d["geometry"]["kind"] == "slope":   # a slope is loaded by its own weight (ρ g, ramped in the first stage)
        kw["density"] = {b: v.get("density", rock["density"]) for b, v in own.items()}
    model = JointedRockModel(dmesh, element_degree=plan.element_degree, rock=rocks,
                             plane="strain" if plan.dimension == 2 else None,
                             quadrature=plan.quadrature, newton=NewtonOptions(verbose=False), **kw)
    for face, comps in d["supports"].items():
        model.fix(face, _components(comps))
    if "in_situ" in d:
        sv, k = d["in_situ"]["vertical"], d["in_situ"]["horizontal_ratio"]
        s0 = -k * sv * np.eye(plan.dimension)
        s0[-1, -1] = -sv
        model.set_in_situ_stress(InSituStress.uniform(s0.tolist()))
    return model


def smeared_material(scene, plan, tables: dict, rocks: dict) -> dict:
    """{block: EquivalentContinuum} with the plan's smeared sets in every block's rock: each set's
    normal and spacing from the scene, its behaviour (law table, shear model, residual stiffness,
    strength if the plan lets it slip) built as for its discrete joints."""
    d = scene.data
    sets = []
    for s in d["geometry"]["joint_sets"]:
        if s["name"] not in plan.smeared:
            continue
        j = d["joints"][s["name"]]
        behaviour = joint_behaviours({s["name"]: 0}, {s["name"]: tables[s["name"]]},
                                     shear_stiffness_ratio=j["shear_stiffness_ratio"],
                                     residual_stiffness=j["residual_stiffness"],
                                     strength=scene.strengths[s["name"]] if plan.slip.get(s["name"]) else None)[0]
        normal = geometry.set_normal(s, plan.dimension)
        sets.append(JointSet([float(x) for x in normal], s["spacing"], behaviour, label=s["name"]))
    return {b: EquivalentContinuum(plan.dimension, e, nu, sets) for b, (e, nu) in rocks.items()}


def _record(scene, plan, model, label, stage, solution, water) -> StageRow:
    monitors = {b: np.r_[model.boundary_mean_displacement(b), model.mean_normal_displacement(b)]
                for b in scene.data["outputs"]["monitor"]}
    u = model.u.x.array.reshape(-1, model.gdim)
    umax = model.comm.allreduce(float(np.linalg.norm(u, axis=1).max(initial=0.0)), op=_max())
    row = StageRow(label, stage, solution.newton_iterations, monitors, umax)
    state = solution.gather_joints()
    set_of = joint_sets_of(model.dmesh.names)
    row.past_table = tuple(sorted({set_of[n] for n in solution.beyond_law_range()}))
    if np.asarray(state.get("closure", [])).size:
        row.max_closure = float(np.max(state["closure"]))
        row.max_normal_stress = float(np.max(state["normal_stress"]))
        names = model.dmesh.names["joints"]
        sets = np.array([set_of[names[int(t)]] for t in state["tag"]])
        for name in np.unique(sets):
            at = sets == name
            row.per_set[str(name)] = (float(np.max(state["closure"][at])),
                                      float(np.max(state["normal_stress"][at])))
        if "shear_state" in state:
            slip = np.asarray(state["shear_state"]) == int(ShearState.slip)
            row.slipping = int(np.sum(slip))
            row.max_slip = float(np.linalg.norm(np.asarray(state["slip"]).reshape(slip.size, -1), axis=1).max(initial=0.0))
            row.slipping_per_set = {str(name): int(np.sum(slip[sets == name])) for name in np.unique(sets)}
    smeared = model.smeared.set_summary() if model.smeared is not None else {}
    for name, (closure, sn, slipping) in smeared.items():
        row.per_set[name] = (closure, sn)
        row.slipping_per_set[name] = slipping
        row.slipping += slipping
    if smeared:  # the largest over every set, discrete and smeared (an opening is a negative closure)
        row.max_closure = max(c for c, _ in row.per_set.values())
        row.max_normal_stress = max(s for _, s in row.per_set.values())
    row.smeared = tuple(smeared)
    row.water = water
    return row


def beyond_tables(rows, tables: dict) -> list:
    """Words for every (stage, set) past its table's last knot: the answer there is the table's
    linear continuation, not the law. Discrete joints are found and reported by the model itself
    after every stage (rockjoint.fem.mechanics.law_range, the check of every path, from the points' status):
    here only the scene's remedy is added; a smeared set has no such status, so its largest σ_n
    is compared with its table's range here."""
    out = [f"joint set {name}: past its table in stage '{row.stage}' (the model's warning above names the "
           "points and σ_n); raise plan: {table_max_stress: ...}" for row in rows for name in row.past_table]
    for row in rows:
        for name, (_, sn) in row.per_set.items():
            top = curve_table(tables[name]).table_maximum_stress
            if name in row.smeared and sn > top * (1.0 + 1e-9):
                out.append(f"smeared joint set {name}: σ_n reaches {sn * 1e-6:.4g} MPa in stage '{row.stage}', beyond "
                           f"its table (0 - {top * 1e-6:.4g} MPa): the response there is the table's linear "
                           "continuation, not the law; raise plan: {table_max_stress: ...}")
    return out


def _max():
    return MPI.MAX


def run_stages(scene, plan, model, label: str, current: list | None = None, transmissivity=None) -> list:
    """In-situ (when given), then every stage; a StageRow after each. current[0]: the stage
    being solved (for the caller's message when a solve fails). transmissivity: {joint set:
    TransmissivityLaw} of the jointed model when the scene asks for flow."""
    current = current if current is not None else [None]
    rows, excavated = [], set()
    jointed = bool(model.behaviours)

    def record(name, solution, transient=None):
        solution, water = scene_water.after_stage(scene, model, solution, transmissivity, excavated, name, transient)
        rows.append(_record(scene, plan, model, label, name, solution, water))
        return solution

    if "in_situ" in scene.data:
        current[0] = "in-situ"
        if jointed:
            scene_water.initial_water(scene, model)
        record("in-situ", model.solve(name="in-situ"))
    handles = {}
    for stage in scene.data["stages"]:
        t0 = time.perf_counter()
        current[0] = stage["name"]
        if "excavate" in stage:
            model.excavate(stage["excavate"])
            excavated.add(stage["excavate"])
        for face, load in stage["loads"].items():
            kind = "traction" if "traction" in load else "pressure"
            value = load[kind]
            if (face, kind) in handles:
                handles[face, kind].value = value
            else:
                add = model.add_traction if kind == "traction" else model.add_pressure
                handles[face, kind] = add(face, value)
        steps = stage.get("steps", plan.load_steps)
        scene_water.before_stage(scene, model, transmissivity, excavated, stage.get("water"))
        solution = record(stage["name"], model.solve(load_steps=steps, name=stage["name"]), stage.get("water"))
        log.info("%s: stage %s, %d load step(s), %d Newton iterations (%.1f s)", label, stage["name"],
                 steps, solution.newton_iterations, time.perf_counter() - t0)
    g, table = scene.data["geometry"], scene.data.get("water", {}).get("table")
    if g["kind"] == "slope" and table is not None:   # the prescribed water, after the stages (docs/slopes.md)
        current[0] = "water"
        if jointed:
            set_joint_pressure(model, slope_keys.phreatic(g, table))
        record("water", model.solve(load_steps=plan.load_steps, name="water"))
    return rows


def run_scene(scene, plan, output: str, comm=None) -> SceneResult:
    """Run the scene as planned; write its outputs to `output` (created; files replaced)."""
    comm = comm or MPI.COMM_WORLD
    t0 = time.perf_counter()
    tables = joint_laws.tables(scene, plan)
    transmissivity = scene_water.transmissivity_laws(scene, plan) if scene_water.requested(scene) else None
    jm = geometry.jointed_mesh(scene, plan, comm)
    meshes = {"jointed": distribute(jm, comm)}
    if plan.intact:
        meshes["intact"] = distribute(geometry.glued(jm), comm)
    log.info("mesh: %d cells, %d joint facet pairs", comm.allreduce(
        meshes["jointed"].mesh.topology.index_map(plan.dimension).size_local),
        comm.allreduce(len(meshes["jointed"].pairs)))
    parent = os.path.dirname(os.path.abspath(output)) or "."
    os.makedirs(parent, exist_ok=True)
    tmp = comm.bcast(tempfile.mkdtemp(prefix=".rockjoint-run-", dir=parent) if comm.rank == 0 else None)
    try:
        rows, files, models, safety = [], [], {}, None
        for label, dmesh in meshes.items():
            if label == "jointed" and "factor_of_safety" in scene.data:   # a slope's strength reduction
                model, found, safety = slope_run.search(scene, plan, dmesh, tables, build_model, run_stages,
                                                        transmissivity)
                if model is None:
                    raise NoEquilibrium(slope_run.no_equilibrium_words(safety))
                rows += found
            else:
                model = build_model(scene, plan, dmesh, tables if label == "jointed" else None)
                rows += _run_explained(scene, plan, model, label, jm, comm,
                                       transmissivity if label == "jointed" else None)
            models[label] = model
            if label == "jointed" and comm.rank == 0:
                for words in beyond_tables(rows, tables):
                    log.warning("warning: %s", words)
            if scene.data["outputs"]["xdmf"]:
                files += model.write_xdmf(os.path.join(tmp, f"{label}.xdmf"))
                if rows[-1].network is not None:   # the joint network after the last stage
                    files.append(rows[-1].network.write(os.path.join(tmp, f"{label}_flow.xdmf"), comm))
        if scene.data["outputs"]["pictures"]:
            files += pictures.draw(models, scene, os.path.join(tmp, "scene.png"))
            if safety is not None:
                files += slope_picture.draw(safety, jm, scene, os.path.join(tmp, "mechanism.png"))
        result = SceneResult(plan, rows, tables, [], time.perf_counter() - t0,
                             meshes["jointed"].mesh.geometry.dim, safety)
        if comm.rank == 0:
            with open(os.path.join(tmp, "summary.txt"), "w", encoding="utf-8") as f:
                f.write(summary_table(result) + "\n")
        comm.barrier()
        if comm.rank == 0:
            os.makedirs(output, exist_ok=True)
            for name in sorted(os.listdir(tmp)):
                os.replace(os.path.join(tmp, name), os.path.join(output, name))
        comm.barrier()
        result.files = sorted(os.listdir(output)) if comm.rank == 0 else []
        return result
    finally:
        if comm.rank == 0:
            shutil.rmtree(tmp, ignore_errors=True)


def _run_explained(scene, plan, model, label, jm, comm, transmissivity=None) -> list:
    """run_stages; a failed solve of the jointed model that statics.diagnose explains (a joint
    set that opens, slides or carries no shear and frees a block) becomes NoEquilibrium."""
    current = [None]
    try:
        return run_stages(scene, plan, model, label, current, transmissivity)
    except (ConvergenceError, LinearSolveError) as err:
        words = statics.diagnose(scene, plan, jm, current[0]) if (comm.rank == 0 and label == "jointed") else None
        words = comm.bcast(words)
        if words is None:
            raise
        raise NoEquilibrium(words) from err
