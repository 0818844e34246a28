#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""bench/results/fem.md: the FE benchmark on DOLFINx 0.11 beside 0.9, from their two reports.

Each report is a run of bench/bench_fem.py in its own userland (scripts/host.sh):

    rm -rf .scratch/fem_meshes
    bash scripts/run.sh python3 bench/bench_fem.py --scaling-sizes --mesh-dir .scratch/fem_meshes \\
        --output bench/results/fem_dolfinx0.11.md
    ROCKJOINT_DOLFINX=0.9 bash scripts/run.sh python3 bench/bench_fem.py --scaling-sizes \\
        --mesh-dir .scratch/fem_meshes --output bench/results/fem_dolfinx0.9.md
    python3 bench/fem_versions.py

The second run reads the meshes and partitions the first one made (--mesh-dir): both versions
solve the same systems, and only DOLFINx, PETSc and their build differ.

This script only reads the two reports' ratio tables and writes them side by side (no number of
its own); the full tables, settings and residual histories stay in the two reports. The 1M-dof
run (bench/results/fem_1m.md, its command inside) is copied below them the same way.
"""
from __future__ import annotations

import argparse
import os
import re

HERE = os.path.dirname(os.path.abspath(__file__))
RESULTS = os.path.join(HERE, "results")
VERSIONS = ("0.11", "0.9")


def ratio_rows(path: str) -> tuple[str, dict]:
    """(title, {(case, ranks): row}) of a bench_fem.py report's ratio table."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    title = text.splitlines()[0].lstrip("# ").strip()
    section = text.split("## Jointed analysis / one intact linear solve", 1)[1].split("\n## ", 1)[0]
    lines = [ln for ln in section.splitlines() if ln.startswith("|")]
    header = [c.strip() for c in lines[0].strip("|").split("|")]
    rows = {}
    for ln in lines[2:]:
        cells = dict(zip(header, (c.strip() for c in ln.strip("|").split("|"))))
        rows[(cells["case"], int(cells["ranks"]))] = cells
    if not rows:
        raise ValueError(f"{path}: no ratio table found")
    return title, rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", default=os.path.join(RESULTS, "fem.md"))
    args = ap.parse_args()
    reports = {v: ratio_rows(os.path.join(RESULTS, f"fem_dolfinx{v}.md")) for v in VERSIONS}
    keys = sorted(set.intersection(*(set(r) for _, r in reports.values())))
    out = ["# A jointed analysis at the cost of an intact linear solve: DOLFINx 0.11 beside 0.9", "",
           "Written by `python3 bench/fem_versions.py` from the two runs of `bench/bench_fem.py` "
           "(same cases, same settings, each in its own Debian userland on the same machine, one "
           "after the other; with `--mesh-dir` as in the script's docstring, the second run reads the "
           "first one's meshes and partitions, so both solve the same systems; each report says "
           "where its meshes came from):", ""]
    out += [f"- {reports[v][0]}: [`fem_dolfinx{v}.md`](fem_dolfinx{v}.md)" for v in VERSIONS]
    out += ["", "Ratio = jointed analysis / one intact linear solve on the same mesh (min of the runs; "
            "target <= 2); CPU ratio is the headline on a shared machine (see the reports).", "",
            "| case | ranks | dofs (jointed) 0.11 / 0.9 | " + " | ".join(
                f"intact LS [s] {v} | jointed [s] {v} | ratio wall {v} | ratio CPU {v} | Newton its {v} | "
                f"error vs closed form {v}" for v in VERSIONS) + " |",
            "|---|---:|---:|" + "---:|---:|---|---:|---:|---|" * len(VERSIONS)]
    for case, ranks in keys:
        dofs = " / ".join(reports[v][1][(case, ranks)]["dofs (jointed / intact)"].split("/")[0].strip()
                          for v in VERSIONS)
        row = f"| {case} | {ranks} | {dofs} |"
        for v in VERSIONS:
            c = reports[v][1][(case, ranks)]
            row += (f" {c['intact LS [s]']} | {c['jointed [s]']} | {c['ratio (wall)']} | {c['ratio (CPU)']} | "
                    f"{c['Newton its']} | {c['error vs closed form (jointed / intact)']} |")
        out.append(row)
    cpu = {v: [float(re.sub(r"[^0-9.]", "", reports[v][1][k]["ratio (CPU)"])) for k in keys] for v in VERSIONS}
    worse = [(k, a, b) for k, a, b in zip(keys, cpu["0.11"], cpu["0.9"]) if a > b]
    out += ["", "CPU ratio on 0.11 against 0.9: " + ", ".join(
        f"{case} {ranks} rank(s) {a:.2f} vs {b:.2f}" for (case, ranks), a, b in zip(keys, cpu["0.11"], cpu["0.9"]))
        + (". No case is worse on 0.11." if not worse else
           ". Worse on 0.11: " + ", ".join(f"{c} {r} rank(s)" for (c, r), _, _ in worse) + "."), ""]
    big = os.path.join(RESULTS, "fem_1m.md")
    if os.path.exists(big):
        title, rows = ratio_rows(big)
        out += [f"## At 1 M dofs: {title}", "",
                "From [`fem_1m.md`](fem_1m.md) (its command, definitions and residual histories there; "
                "target <= 1.3; where the time goes and what would reach the target: docs/fem.md, "
                "\"At 1M dofs\").", "",
                "| case | ranks | dofs (jointed / intact) | runs | intact LS [s] | jointed [s] | ratio wall | "
                "ratio CPU | Newton its | Krylov its per Newton it (intact) |",
                "|---|---:|---|---:|---:|---:|---|---:|---:|---|"]
        for (case, ranks), c in sorted(rows.items()):
            out.append(f"| {case} | {ranks} | {c['dofs (jointed / intact)']} | {c['runs']} | {c['intact LS [s]']} | "
                       f"{c['jointed [s]']} | {c['ratio (wall)']} | {c['ratio (CPU)']} | {c['Newton its']} | "
                       f"{c['Krylov its per Newton it (intact)']} |")
        out.append("")
    with open(args.output, "w", encoding="utf-8") as f:
        f.write("\n".join(out))
    print("\n".join(out))


if __name__ == "__main__":
    main()
