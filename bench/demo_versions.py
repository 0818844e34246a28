#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""bench/results/demo_versions.md: the lab, tunnel, blocky and user-model demos on DOLFINx 0.11
beside 0.9, number for number.

Runs on the host (Debian 12 or 13); each demo runs in each version's userland through
scripts/run.sh (build both first: `bash scripts/build.sh` and
`ROCKJOINT_DOLFINX=0.9 bash scripts/build.sh`):

    python3 bench/demo_versions.py

Every line a demo prints is split into words; lines whose words agree except for numbers are
paired, and each number of 0.11 is set against the same number of 0.9 (relative difference
|a - b| / max(|a|, |b|); numbers below 1e-12 on both sides are zeros at round-off and not compared). The report lists the lines that carry numbers, the largest difference
per demo, and the run times. Nothing here is a number of its own: it only compares the two runs.
"""
from __future__ import annotations

import argparse
import os
import re
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VERSIONS = ("0.11", "0.9")
DEMOS = ("demo_lab_closure_test", "demo_tunnel", "demo_blocky_rock_mass", "demo_user_model")
#: numbers below this on both versions are zeros at round-off (a demo's self-checks print such
#: differences); their relative difference means nothing
ROUND_OFF = 1e-12
PATH = re.compile(r"\S*/\S*")
NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")


def run(demo: str, version: str, output: str) -> tuple[list[str], float]:
    """The demo's printed lines (stdout and logging) and its wall time in that version's userland."""
    env = dict(os.environ, ROCKJOINT_DOLFINX=version)
    t0 = time.perf_counter()
    r = subprocess.run(["bash", os.path.join(ROOT, "scripts", "run.sh"), "python3",
                        os.path.join("demos", f"{demo}.py"), "--output", output],
                       cwd=ROOT, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if r.returncode != 0:
        raise SystemExit(f"{demo} on DOLFINx {version} failed ({r.returncode}):\n{r.stderr[-3000:]}")
    # paths (the output folder names the version) are not results
    lines = [PATH.sub("<path>", ln.rstrip()) for ln in (r.stdout + r.stderr).splitlines()]
    lines = [ln for ln in lines if NUMBER.search(ln)]
    # progress lines (timings, Newton residual logs) are not results
    return [ln for ln in lines if not re.search(r"\d s(\b|$)|elapsed|\|\|r\|\||^wrote |wall time", ln)], wall


def shape(line: str) -> str:
    return NUMBER.sub("#", line)


def compare(a: list[str], b: list[str]) -> tuple[list[tuple[str, str, float]], float]:
    """Pairs of lines with the same shape, in order, and their largest relative difference."""
    rows, worst = [], 0.0
    rest = list(b)
    for la in a:
        match = next((lb for lb in rest if shape(lb) == shape(la)), None)
        if match is None:
            rows.append((la, "(no such line)", float("nan")))
            continue
        rest.remove(match)
        diff = 0.0
        for x, y in zip(map(float, NUMBER.findall(la)), map(float, NUMBER.findall(match))):
            scale = max(abs(x), abs(y))
            if scale < ROUND_OFF:   # both zero to round-off (e.g. a difference of two solutions)
                continue
            diff = max(diff, abs(x - y) / scale)
        worst = max(worst, diff)
        rows.append((la, match, diff))
    return rows, worst


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", default=os.path.join(ROOT, "bench", "results", "demo_versions.md"))
    ap.add_argument("--demos", nargs="*", default=list(DEMOS))
    args = ap.parse_args()
    out = ["# The demos on DOLFINx 0.11 beside 0.9", "",
           f"Written by `python3 bench/demo_versions.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}"
           " (each demo at its defaults in each version's userland; the meshes come from gmsh 4.15 "
           "and 4.13, so they differ slightly). Lines with numbers that differ are shown with both "
           "values; rel. diff = |a - b| / max(|a|, |b|) over the line's numbers.", "",
           "| demo | wall 0.11 [s] | wall 0.9 [s] | numeric lines | identical | largest rel. diff |",
           "|---|---:|---:|---:|---:|---:|"]
    details = []
    # The demos write under the repository (the only folder the userlands see).
    with tempfile.TemporaryDirectory(dir=os.path.join(ROOT, ".scratch") if os.path.isdir(
            os.path.join(ROOT, ".scratch")) else ROOT) as tmp:
        for demo in args.demos:
            res = {}
            for v in VERSIONS:
                print(f"== {demo} on DOLFINx {v}", flush=True)
                res[v] = run(demo, v, os.path.join(tmp, f"{demo}_{v}"))
            rows, worst = compare(res["0.11"][0], res["0.9"][0])
            same = sum(1 for _, _, d in rows if d == 0.0)
            out.append(f"| {demo} | {res['0.11'][1]:.0f} | {res['0.9'][1]:.0f} | {len(rows)} | {same} | "
                       f"{worst:.2g} |")
            details += ["", f"## {demo}", "", "Lines that differ (0.11, then 0.9):", ""]
            differing = [(a, b, d) for a, b, d in rows if d != 0.0]
            details += [f"    {a}\n    {b}\n    (rel. diff {d:.2g})" for a, b, d in differing] or ["    none"]
    text = "\n".join(out + details) + "\n"
    with open(args.output, "w", encoding="utf-8") as fh:
        fh.write(text)
    print(text)


if __name__ == "__main__":
    main()
