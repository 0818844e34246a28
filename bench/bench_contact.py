#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Benchmark: the boundary-element closure curve of a joint (rockjoint.contact).
Targets, 15 loads (0.1-30 MPa): periodic 512 x 512 in <= 1 s and 1024 x 1024 in <= 5 s;
non-periodic (zero-padded kernel, real scans) 1024 x 1024 in <= 10 s (issue 21).

Run:  bash scripts/run.sh python3 bench/bench_contact.py [--repeat 3]
Prints a table and writes bench/results/contact.md. The joint is the granite-like synthetic
mated pair of the accuracy ladder (H 0.8, rms 1 mm, matedness 2.5 mm, h 0.25 mm, E 50 GPa,
ν 0.25). Each time is the whole closure_curve call (solver set-up, FFT plans, 15 warm-started
loads); the first call in a process also pays FFTW's planning (FFTW_MEASURE) and is reported
on its own; "best" is the minimum of --repeat further calls. Transforms from 512² (padded
transform size) up run on every core of the machine (ROCKJOINT_FFT_THREADS sets the number).
"""
import argparse
import os
import platform
import time

import numpy as np

import rockjoint
from rockjoint import contact
from rockjoint import topography as topo

#: (grid, periodic) -> target [s]
TARGETS = {(512, True): 1.0, (1024, True): 5.0, (1024, False): 10.0}


def timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[256, 512, 1024])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--output", default=os.path.join(os.path.dirname(__file__), "results",
                                                     "contact.md"))
    args = ap.parse_args()
    e_star = rockjoint.composite_modulus(50e9, 0.25)
    stresses = np.geomspace(0.1e6, 30e6, 15)
    rows = []
    for n in args.sizes:
        upper, lower = topo.mated_pair(topo.SelfAffineSpec(0.8, 1e-3), (n, n), 0.25e-3, 2.5e-3,
                                       seed=1)
        aperture = topo.composite_topography(upper, lower).aperture
        for periodic in (True, False):
            run = lambda: contact.closure_curve(aperture, e_star, stresses, periodic=periodic)  # noqa: E731
            first, curve = timed(run)
            best = min(timed(run)[0] for _ in range(args.repeat))
            rows.append(dict(n=n, periodic=periodic, first=first, best=best,
                             its=int(curve.iterations.sum()), max_its=int(curve.iterations.max()),
                             area=curve.contact_area_ratio[-1], closure=curve.closure,
                             cmp=float(np.max(curve.complementarity / (stresses * curve.closure[-1])))))
            r = rows[-1]
            print(f"{n}² {'periodic' if periodic else 'non-periodic'}: first {first:.3f} s, "
                  f"best {best:.3f} s, {r['its']} CG iterations", flush=True)
    lines = [
        "# Boundary-element closure curve: cost", "",
        f"Produced by `bench/bench_contact.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
        f"{platform.machine()}, {os.cpu_count()} CPUs (transform threads: "
        f"{os.environ.get('ROCKJOINT_FFT_THREADS', os.cpu_count())}), load average "
        f"{', '.join(f'{x:.2f}' for x in os.getloadavg())} at the end.", "",
        "Reproduce: `bash scripts/run.sh python3 bench/bench_contact.py`", "",
        "Joint: synthetic mated granite-like pair (H 0.8, rms 1 mm, matedness 2.5 mm, h 0.25 mm), "
        "E* = E/(2(1-ν²)) with E 50 GPa, ν 0.25; 15 loads 0.1-30 MPa (geometric), warm-started; "
        "Polonsky-Keer tolerance 1e-8 on Σ|Δp|/Σp. Time = the whole `contact.closure_curve` call; "
        "*first* includes FFTW's planning (FFTW_MEASURE, once per size and process), *best* is the "
        f"minimum of {args.repeat} further calls.", "",
        "| grid | kernel | first [s] | best [s] | target [s] | met | CG its (total, max/load) | A/A0 at 30 MPa | Δ at 1 / 10 / 30 MPa [mm] | max p·g / (σ Δmax) |",
        "|---|---|---:|---:|---:|---|---|---:|---|---:|"]
    for r in rows:
        target = TARGETS.get((r["n"], r["periodic"]))
        d = np.interp([1e6, 10e6, 30e6], stresses, r["closure"]) * 1e3
        lines.append(f"| {r['n']}² | {'periodic' if r['periodic'] else 'non-periodic (2n² padded)'} | "
                     f"{r['first']:.3f} | {r['best']:.3f} | {target if target else '-'} | "
                     f"{('yes' if r['best'] <= target else 'no') if target else '-'} | "
                     f"{r['its']}, {r['max_its']} | {r['area']:.4f} | "
                     f"{d[0]:.4f} / {d[1]:.4f} / {d[2]:.4f} | {r['cmp']:.1e} |")
    lines += ["", "The non-periodic kernel (real scans) transforms a zero-padded 2n × 2n grid (pruned: "
              "the zero rows are not transformed, docs/contact.md). Δ at 1 and 10 MPa is "
              "interpolated linearly between loads."]
    text = "\n".join(lines) + "\n"
    os.makedirs(os.path.dirname(args.output), exist_ok=True)
    with open(args.output, "w") as fh:
        fh.write(text)
    print(text)


if __name__ == "__main__":
    main()
