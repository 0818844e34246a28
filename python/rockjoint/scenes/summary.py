# SPDX-License-Identifier: MIT
"""The summary table of a scene's run (summary.txt, printed by `rockjoint run`): per stage, the
jointed model beside the intact one and the joints' share; the joints' state over all sets and per
set; the water (the coupling's iterations, the largest joint pressure, the joint points opened by
water) and the flow at every boundary with a condition; a slope's factor of safety beside the
intact rock's answer (safety_lines)."""
from __future__ import annotations


def summary_table(result) -> str:
    """The table of `result` (a runner.SceneResult): jointed beside intact, per stage: monitored
    displacements [mm], max ``|u|`` [mm], the joints, the water."""
    stages = [r.stage for r in result.rows if r.model == "jointed"]
    has_intact = any(r.model == "intact" for r in result.rows)
    w = max([len(s) for s in stages] + [5]) + 2
    q = max([len(f"  {n} (smeared): slipping points") + 2 for r in result.rows for n in r.per_set] + [28])
    lines = [f"{'stage':{w}}{'quantity':{q}}{'jointed':>14}{'intact':>14}{'joints share':>14}"]
    for stage in stages:
        j = result.row("jointed", stage)
        i = result.row("intact", stage) if has_intact else None
        quantities = [("max |u| [mm]", j.max_displacement, i and i.max_displacement)]
        for b, v in j.monitors.items():
            for k, axis in enumerate(["x", "y", "z"][:len(v) - 1] + ["n"]):
                quantities.append((f"mean u_{axis} {b} [mm]", v[k], i and i.monitors[b][k]))
        for name, a, b in quantities:
            share = f"{(a - b) * 1e3:14.5g}" if b is not None else f"{'':>14}"
            other = f"{b * 1e3:14.5g}" if b is not None else f"{'-':>14}"
            lines.append(f"{stage:{w}}{name:{q}}{a * 1e3:14.5g}{other}{share}")
        lines.append(f"{stage:{w}}{'joints: max closure [mm]':{q}}{j.max_closure * 1e3:14.5g}")
        lines.append(f"{stage:{w}}{'joints: max σ_n [MPa]':{q}}{j.max_normal_stress * 1e-6:14.5g}")
        lines.append(f"{stage:{w}}{'joints: slipping points':{q}}{j.slipping:14d}")
        lines.append(f"{stage:{w}}{'joints: largest slip [mm]':{q}}{j.max_slip * 1e3:14.5g}")
        for name, (closure, sn) in sorted(j.per_set.items()):  # every set, smeared ones too
            kind = f"{name} (smeared)" if name in j.smeared else name
            lines.append(f"{stage:{w}}{'  ' + kind + ': max closure [mm]':{q}}{closure * 1e3:14.5g}")
            lines.append(f"{stage:{w}}{'  ' + kind + ': max σ_n [MPa]':{q}}{sn * 1e-6:14.5g}")
            lines.append(f"{stage:{w}}{'  ' + kind + ': slipping points':{q}}{j.slipping_per_set.get(name, 0):14d}")
        if j.water.iterations:
            lines.append(f"{stage:{w}}{'water: coupled iterations':{q}}{j.water.iterations:14d}")
        if j.water.wet:
            lines.append(f"{stage:{w}}{'water: largest joint p [MPa]':{q}}{j.water.max_pressure * 1e-6:14.5g}")
            lines.append(f"{stage:{w}}{'water: joint points opened by it':{q}}{j.water.opened_by_water:14d}")
        for b, rate in (j.flow_rates or {}).items():   # L/min (per metre out of plane in 2D)
            other = i.flow_rates.get(b) if i is not None and i.flow_rates else None
            unit = "L/min/m" if result.gdim == 2 else "L/min"
            lines.append(f"{stage:{w}}{f'flow in at {b} [{unit}]':{q}}{rate * 6e4:14.5g}"
                         + (f"{other * 6e4:14.5g}" if other is not None else f"{'-':>14}"))
    if result.safety is not None:
        lines += safety_lines(result, w + q)
    return "\n".join(lines)


def safety_lines(result, width: int) -> list:
    """The factor-of-safety rows of the summary table (a slope's `factor_of_safety:`, slope_run.py):
    F, its bracket and tolerance, the trials and their time, the blocks that fail; beside it the
    intact rock, elastic."""
    s = result.safety
    f = s.found
    rows = []
    if f.bounded and f.reason:   # bounded, but not by the strength (SafetyFactor.reason)
        rows.append(("factor of safety F", "none: the failure does not depend on the strength"))
    elif f.bounded:
        rows += [("factor of safety F", f"{f.factor:.4g}"),
                 ("  bracket (stable, failed)", f"{f.stable:.4g} - {f.failed:.4g}"),
                 ("  tolerance", f"{100 * f.tolerance:.3g} %"),
                 ("  jointed rows above at F", f"{f.stable:.4g} (the largest stable trial)")]
    elif f.failed is None:
        rows.append(("factor of safety F", f"> {f.factor:g}: equilibrium at every F tried"))
    else:
        rows.append(("factor of safety F", f"< {f.factor:g}: no equilibrium at any F tried"))
    rows += [("  trial solves", f"{len(f.trials)}"), ("  search time [s]", f"{s.seconds:.3g}"),
             ("  moving blocks", ", ".join(s.moving) or "-")]
    lines = [f"{name:{width}}{value:>28}" for name, value in rows]
    # why F is not the strength's, or what stopped the first trial without equilibrium: words, below
    # the table (the failure names the joints, blocks and points where the search stopped)
    lines += [f"  {label}: {text}" for label, text in (("not a factor of safety", f.reason),
                                                        ("what failed at the unstable end", f.failure)) if text]
    rows = []
    intact = [r for r in result.rows if r.model == "intact"]
    if intact:
        rows += [("intact rock (elastic)", "never fails: no factor of safety"),
                 ("  intact max |u| [mm]", f"{intact[-1].max_displacement * 1e3:.5g}")]
    return lines + [f"{name:{width}}{value:>28}" for name, value in rows]
