#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""FFTW's planning effort for the contact reference's transforms: the evidence for
contact/half_space.hpp's detail::measure_plans (below 1024² transform points a size is planned
by FFTW_ESTIMATE until it has been planned 8 times in the process, then by FFTW_MEASURE; larger
sizes by FFTW_MEASURE at once).

For each grid, in fresh processes (as a scene run pays it), the wall time of 10 successive
closure curves (2 at 1024²) of the granite-like joint of bench_contact.py (H 0.8, rms 1 mm, matedness 2.5 mm) at
h = 0.5 mm (15 loads 0.1-30 MPa) with the rule ("auto"), with FFTW_MEASURE for every plan and
with FFTW_ESTIMATE for every plan (ROCKJOINT_FFT_PLANNING), minimum over --repeat processes.

Run:  bash scripts/run.sh python3 bench/bench_fft_planning.py [--repeat 2] [--sizes 128 256 ...]
Writes bench/results/fft_planning.md (and prints it).
"""
from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import time

import numpy as np

MODES = ("auto", "measure", "estimate")
_CURVES = """
import sys, time, rockjoint
from rockjoint import contact, topography as topo
n, periodic, count = int(sys.argv[1]), sys.argv[2] == "periodic", int(sys.argv[3])
walls = topo.mated_pair(topo.SelfAffineSpec(0.8, 1e-3), (n, n), 0.5e-3, 2.5e-3, seed=1)
aperture = topo.composite_topography(*walls).aperture
e_star = rockjoint.composite_modulus(50e9, 0.25)
stresses = [0.1e6 * 300.0 ** (k / 14) for k in range(15)]
for _ in range(count):
    t0 = time.perf_counter()
    contact.closure_curve(aperture, e_star, stresses, periodic=periodic)
    print(time.perf_counter() - t0)
"""


def curves(n: int, kernel: str, mode: str) -> list:
    env = dict(os.environ, ROCKJOINT_FFT_PLANNING=mode)
    count = 10 if n < 1024 else 2
    out = subprocess.run([sys.executable, "-c", _CURVES, str(n), kernel, str(count)], env=env, capture_output=True,
                         text=True, check=True)
    return [float(x) for x in out.stdout.split()]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[128, 200, 240, 256, 300, 512, 1024])
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--output", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "results",
                                                     "fft_planning.md"))
    args = ap.parse_args()
    rows = []
    cases = [(n, "periodic") for n in args.sizes] + [(n, "non-periodic") for n in args.sizes if n in (256, 512)]
    for n, kernel in cases:
        times = {}
        for mode in MODES:
            runs = [curves(n, kernel, mode) for _ in range(args.repeat if n < 1024 else 1)]
            times[mode] = [min(r[k] for r in runs) for k in range(len(runs[0]))]
        rows.append((n, kernel, times))
        print(f"{n}² {kernel}: " + "; ".join(f"{m} " + " / ".join(f"{t:.3f}" for t in times[m]) for m in MODES),
              flush=True)
    lines = ["# FFTW's planning effort for the contact reference's transforms", "",
             __doc__.split("Run:")[0].strip(), "",
             f"Reproduce: `bash scripts/run.sh python3 bench/bench_fft_planning.py --repeat {args.repeat}`. Produced "
             f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {platform.machine()}, {os.cpu_count()} CPUs "
             f"(transforms threaded from 512² transform points; 1024² one process per mode).", "",
             "Wall seconds per closure curve in one process: the 1st (what a scene run pays), the 2nd, the "
             "median of the later ones, and the sum of all (the cumulative cost of a process that solves "
             "that many curves of the size).", "",
             "| grid | kernel | curves | 1st: auto / measure / estimate | 2nd: auto / measure / estimate | "
             "later, median: auto / measure / estimate | sum: auto / measure / estimate |",
             "|---|---|---:|---|---|---|---|"]
    for n, kernel, t in rows:
        def cell(f):
            return " / ".join("-" if not np.isfinite(f(t[m])) else f"{f(t[m]):.3f}" for m in MODES)
        lines.append(f"| {n}² | {kernel} | {len(t['auto'])} | {cell(lambda x: x[0])} | {cell(lambda x: x[1])} | "
                     f"{cell(lambda x: float(np.median(x[2:])) if len(x) > 2 else float('nan'))} | {cell(sum)} |")
    text = "\n".join(lines) + "\n"
    with open(args.output, "w", encoding="utf-8") as fh:
        fh.write(text)
    print(text)


if __name__ == "__main__":
    main()
