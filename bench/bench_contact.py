#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Benchmark: the boundary-element closure curve of a joint (rockjoint.contact).
Targets, 15 loads (0.1-30 MPa): periodic 512 x 512 in <= 1 s and 1024 x 1024 in <= 3 s;
non-periodic (zero-padded kernel, real scans) 1024 x 1024 in <= 10 s (issues 21, 43).

Run:  bash scripts/run.sh python3 bench/bench_contact.py [--repeat 3] [--sizes 256 512 1024]
Writes bench/results/contact.md (what a user sees) and bench/results/contact_efficiency.md (the
solver against its own limit) and prints both. The joint is the granite-like synthetic mated pair
of the accuracy ladder (H 0.8, rms 1 mm, matedness 2.5 mm, h 0.25 mm, E 50 GPa, ν 0.25). Each time
is the whole closure_curve call (solver set-up, FFT plans, 15 warm-started loads): *first* is the
first call of the process, which also pays FFTW's planning (stated on its own: FFTW_MEASURE from
1024² transform points, once per size and process); *best* is the minimum of --repeat later calls.
Then one more call with profile=True gives, per load, the wall time, its phases and the CG
iterations; efficiency = iterations × the solver's transform pair (the shortest of 5 u = K p calls
after the curve, same plans and arrays) / wall time. Transforms from 512² (padded transform size)
up run on every core (ROCKJOINT_FFT_THREADS sets the number). The machine's load average is
recorded before and after each case: the transforms are threaded, so other processes on the
cores slow them more than the machine's share would suggest.
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
TARGETS = {(512, True): 1.0, (1024, True): 3.0, (1024, False): 10.0}
#: the phases of ContactProfile, as the efficiency report names them
PHASES = (("transforms", "transforms"), ("direct_sums", "direct sums"),
          ("grid_passes", "grid passes"), ("contact_set", "contact set"))
COMMAND = "bash scripts/run.sh python3 bench/bench_contact.py"


def timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


def wall_and_cpu(fn):
    """(wall, CPU seconds of every thread of the process) of fn()."""
    c0, t0 = time.process_time(), time.perf_counter()
    fn()
    return time.perf_counter() - t0, time.process_time() - c0


def load_average():
    return "/".join(f"{x:.1f}" for x in os.getloadavg())


def kernel_name(periodic):
    return "periodic" if periodic else "non-periodic"


def measure(aperture, e_star, stresses, periodic, repeat):
    """The case's user-facing times and one profiled curve."""
    run = lambda profile: contact.closure_curve(aperture, e_star, stresses, periodic=periodic,  # noqa: E731
                                                profile=profile)
    before = load_average()
    first, first_curve = timed(lambda: run(True))
    best, cpu = min(wall_and_cpu(lambda: run(False)) for _ in range(repeat))
    wall, curve = timed(lambda: run(True))
    prof = curve.profile
    total = {name: sum(getattr(p, name) for p in prof) for name in
             ("wall", "start", "final_state", "transform_pairs", "carried_updates") + tuple(n for n, _ in PHASES)}
    return dict(periodic=periodic, first=first, planning=first_curve.planning_seconds, best=best, cpu=cpu, curve=curve,
                pair=curve.transform_pair, total=total, call=wall, load=f"{before} → {load_average()}")


def user_report(rows, args):
    lines = [
        "# Boundary-element closure curve: cost", "",
        f"Produced by `bench/bench_contact.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
        f"{platform.machine()}, {os.cpu_count()} CPUs (transform threads: "
        f"{os.environ.get('ROCKJOINT_FFT_THREADS', os.cpu_count())}), rockjoint {rockjoint.__version__}.", "",
        f"Reproduce: `{COMMAND}`", "",
        "Joint: synthetic mated granite-like pair (H 0.8, rms 1 mm, matedness 2.5 mm, h 0.25 mm), "
        "E* = E/(2(1-ν²)) with E 50 GPa, ν 0.25; 15 loads 0.1-30 MPa (geometric), warm-started; "
        "Polonsky-Keer tolerance 1e-8 on Σ|Δp|/Σp. Time = the whole `contact.closure_curve` call; "
        "*first* is the first call of the process (what a one-curve run pays), FFTW's planning inside it "
        f"stated on its own; *best* is the minimum of {args.repeat} later calls, *CPU* the seconds its threads ran "
        "(at most the transform threads × best: less means the process waited for a core). Load average (1/5/15 min) "
        "before → after the case: the machine is shared, and other processes on its cores slow the "
        "threaded transforms.", "",
        "| grid | kernel | first [s] | planning in first [s] | best [s] | CPU of best [s] | target [s] | met | CG its (total, max/load) "
        "| A/A0 at 30 MPa | Δ at 1 / 10 / 30 MPa [mm] | max p·g / (σ Δmax) | load average |",
        "|---|---|---:|---:|---:|---:|---:|---|---|---:|---|---:|---|"]
    for r in rows:
        c = r["curve"]
        target = TARGETS.get((r["n"], r["periodic"]))
        d = np.interp([1e6, 10e6, 30e6], c.stress, c.closure) * 1e3
        cmp = float(np.max(c.complementarity / (c.stress * c.closure[-1])))
        lines.append(f"| {r['n']}² | {kernel_name(r['periodic'])} | {r['first']:.3f} | {r['planning']:.3f} | "
                     f"{r['best']:.3f} | {r['cpu']:.3f} | {target if target else '-'} | "
                     f"{('yes' if r['best'] <= target else 'no') if target else '-'} | "
                     f"{int(c.iterations.sum())}, {int(c.iterations.max())} | {c.contact_area_ratio[-1]:.4f} | "
                     f"{d[0]:.4f} / {d[1]:.4f} / {d[2]:.4f} | {cmp:.1e} | {r['load']} |")
    lines += ["", "The non-periodic kernel (real scans) transforms a zero-padded 2n × 2n grid (pruned: the "
              "zero rows are not transformed, docs/contact.md). Δ at 1 and 10 MPa is interpolated linearly "
              "between loads. Where the time goes: bench/results/contact_efficiency.md (same command)."]
    return "\n".join(lines) + "\n"


def efficiency_report(rows):
    lines = [
        "# Boundary-element closure curve: the solver against its own limit", "",
        f"Produced by `{COMMAND}` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
        f"{platform.machine()}, {os.cpu_count()} CPUs (transform threads: "
        f"{os.environ.get('ROCKJOINT_FFT_THREADS', os.cpu_count())}); the joint and loads of "
        "bench/results/contact.md, one closure curve per case with `profile=True` after the timed ones.", "",
        "Each CG iteration needs at least one transform pair (u = K p or K t: forward + inverse FFT with the "
        "kernel product). *pair* is the shortest of 5 u = K p calls after the curve (same plans, arrays "
        "and threads); efficiency = CG iterations × pair / wall time of the load (target ≥ 0.7). "
        "*pairs* counts the transform pairs the solver made (the final u included; an iteration whose "
        "contact set grew or shrank by more than a few points needs both K t and a new u = K p, the "
        "others carry u, *carried*). The phases (percent of the wall time) are consecutive laps of one "
        "clock: transforms (every pair, at the speed it ran inside the solve), direct sums (K t on a small "
        "contact set), grid passes (the interpenetration scan, the carried update of u), contact set (the "
        "CG algebra on its list), other (warm start, final gap, contact set and spots).", "",
        "## Whole curve", "",
        "| grid | kernel | CG its | pairs (carried) | pair [ms] | wall [s] | its × pair [s] | efficiency "
        "| pairs × pair / wall | transforms | direct sums | grid passes | contact set | other | load average |",
        "|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    for r in rows:
        t, its = r["total"], int(r["curve"].iterations.sum())
        share = [100 * t[name] / t["wall"] for name, _ in PHASES]
        lines.append(f"| {r['n']}² | {kernel_name(r['periodic'])} | {its} | {t['transform_pairs']} "
                     f"({t['carried_updates']}) | {1e3 * r['pair']:.2f} | {t['wall']:.3f} | {its * r['pair']:.3f} | "
                     f"{its * r['pair'] / t['wall']:.2f} | {t['transform_pairs'] * r['pair'] / t['wall']:.2f} | "
                     + " | ".join(f"{x:.0f} %" for x in share) + f" | {100 - sum(share):.0f} % | {r['load']} |")
    lines += ["", "## Per load", "",
              "| grid | kernel | σ [MPa] | CG its | pairs (carried) | wall [ms] | its × pair [ms] | efficiency "
              "| transforms | direct sums | grid passes | contact set | other |",
              "|---|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        c = r["curve"]
        for s, its, p in zip(c.stress, c.iterations, c.profile):
            share = [100 * getattr(p, name) / p.wall for name, _ in PHASES]
            lines.append(f"| {r['n']}² | {kernel_name(r['periodic'])} | {s * 1e-6:.3g} | {its} | "
                         f"{p.transform_pairs} ({p.carried_updates}) | {1e3 * p.wall:.1f} | "
                         f"{1e3 * its * r['pair']:.1f} | {its * r['pair'] / p.wall:.2f} | "
                         + " | ".join(f"{x:.0f} %" for x in share) + f" | {100 - sum(share):.0f} % |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[256, 512, 1024])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--output", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "results"),
                    help="folder of contact.md and contact_efficiency.md")
    args = ap.parse_args()
    e_star = rockjoint.composite_modulus(50e9, 0.25)
    stresses = np.geomspace(0.1e6, 30e6, 15)
    rows = []
    for n in args.sizes:
        upper, lower = topo.mated_pair(topo.SelfAffineSpec(0.8, 1e-3), (n, n), 0.25e-3, 2.5e-3, seed=1)
        aperture = topo.composite_topography(upper, lower).aperture
        for periodic in (True, False):
            rows.append(dict(n=n, **measure(aperture, e_star, stresses, periodic, args.repeat)))
            r, its = rows[-1], int(rows[-1]["curve"].iterations.sum())
            print(f"{n}² {kernel_name(periodic)}: first {r['first']:.3f} s (planning {r['planning']:.3f} s), "
                  f"best {r['best']:.3f} s, {its} CG iterations, efficiency "
                  f"{its * r['pair'] / r['total']['wall']:.2f}, load {r['load']}", flush=True)
    os.makedirs(args.output, exist_ok=True)
    for name, text in (("contact.md", user_report(rows, args)), ("contact_efficiency.md", efficiency_report(rows))):
        with open(os.path.join(args.output, name), "w", encoding="utf-8") as fh:
            fh.write(text)
        print(text)


if __name__ == "__main__":
    main()
