#!/usr/bin/env python3
"""Are the fire solver's beds statistically the paper's?

For each aspect ratio a and seed, runs `packbed generate --solver paper` and `--solver fire`
on the same bed (Np = 1.5 (1 - 0.4) a^2 HEIGHT, as examples/validate.py, band 2 Dp clear of
the ends) into OUT/<solver>/a<a>/seed<seed>/, skipping runs whose summary.json exists; paper
runs already made by examples/validate.py are reused from --paper-runs. Prints, per a, the
mean overall void fraction of each solver, their difference, the RMS difference of the mean
radial void-fraction profiles (x from the wall 0 to a/2, 0.02 Dp shells), the same RMS between
two halves of the paper's seeds (the noise floor) and the mean wall time and iterations.
Targets: |mean difference| <= 0.003 and profile RMS <= 0.01.

With --reference fire the reference runs are the fire solver's (into OUT/fire-reference/) and
the compared ones take --fire-args, e.g. the LAMMPS engine (its targets: within 0.005 and 0.015):
    bench/solver_equivalence.py --reference fire --fire-args "--engine lammps --ranks 2" \
        --label lammps

Usage: bench/solver_equivalence.py [--packbed build/packbed] [--aspect-ratios 5,10]
                                   [--seeds 1-10] [--out results/equivalence]
                                   [--paper-runs results/validation]
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys


def parse_seeds(text):
    seeds = []
    for part in text.split(","):
        lo, _, hi = part.partition("-")
        seeds.extend(range(int(lo), int(hi or lo) + 1))
    return seeds


def particles_for(a, height):
    return round(1.5 * (1 - 0.4) * a * a * height)


def profile(run):
    with open(os.path.join(run, "radial_void_fraction.csv")) as f:
        return [float(r["void_fraction"]) for r in csv.DictReader(f)]


def mean_profile(runs):
    profiles = [profile(r) for r in runs]
    return [sum(p[i] for p in profiles) / len(profiles) for i in range(len(profiles[0]))]


def rms(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)) / len(a))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--packbed", default="build/packbed")
    p.add_argument("--aspect-ratios", default="5,10")
    p.add_argument("--seeds", default="1-10")
    p.add_argument("--height", type=float, default=25.0)
    p.add_argument("--out", default="results/equivalence")
    p.add_argument("--paper-runs", default="results/validation")
    p.add_argument("--fire-args", default="",
                   help="extra options of the fire runs (a schedule other than the default)")
    p.add_argument("--label", default="fire",
                   help="folder of the fire runs under OUT (one per --fire-args)")
    p.add_argument("--existing-paper-runs-only", action="store_true",
                   help="compare with the paper runs already made (seeds without one are left "
                        "out of the paper's mean), do not start new ones")
    p.add_argument("--reference", choices=["paper", "fire"], default="paper",
                   help="the solver the runs of --fire-args are compared with")
    p.add_argument("--threads", default="2")
    args = p.parse_args()
    seeds = parse_seeds(args.seeds)
    verbose = sys.stderr.isatty()

    ref, label = args.reference, args.label
    print(f"| a | Np | seeds {ref}/{label} | {ref}: mean e | {label}: mean e | difference "
          f"| profile RMS | {ref} halves RMS | {ref}: s, iterations | {label}: s, iterations |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for a in [float(x) for x in args.aspect_ratios.split(",")]:
        runs = {"paper": [], "fire": []}
        for solver in runs:
            for seed in seeds:
                folder = args.label if solver == "fire" else (
                    "paper" if args.reference == "paper" else "fire-reference")
                run = os.path.join(args.out, folder, f"a{a:g}", f"seed{seed}")
                reused = os.path.join(args.paper_runs, f"a{a:g}", f"seed{seed}")
                if (solver == "paper" and args.reference == "paper"
                        and os.path.exists(os.path.join(reused, "summary.json"))):
                    with open(os.path.join(reused, "summary.json")) as f:
                        s = json.load(f)
                    # Reuse only the same bed: same Np, same band, the paper's solver.
                    if (s["particles"] == particles_for(a, args.height)
                            and s["parameters"]["band_clearance"] == 2
                            and s["parameters"].get("solver", "paper") == "paper"):
                        run = reused
                if not os.path.exists(os.path.join(run, "summary.json")):
                    if solver == "paper" and args.reference == "paper" and args.existing_paper_runs_only:
                        continue
                    if verbose:
                        print(f"a = {a:g}, seed {seed}, {solver} ...", file=sys.stderr, flush=True)
                    subprocess.run([args.packbed, "generate",
                                    "--solver", solver if solver == "fire" else args.reference,
                                    "--aspect-ratio", f"{a:g}",
                                    "--particles", str(particles_for(a, args.height)),
                                    "--seed", str(seed), "--band-clearance", "2", "--quiet",
                                    "--threads", args.threads, "--out", run]
                                   + (args.fire_args.split() if solver == "fire" else []),
                                   check=True)
                runs[solver].append(run)

        def summaries(solver):
            out = []
            for run in runs[solver]:
                with open(os.path.join(run, "summary.json")) as f:
                    out.append(json.load(f))
            return out

        paper, fire = summaries("paper"), summaries("fire")
        e_paper = sum(s["void_fraction"] for s in paper) / len(paper)
        e_fire = sum(s["void_fraction"] for s in fire) / len(fire)
        half = len(runs["paper"]) // 2
        noise = rms(mean_profile(runs["paper"][:half]), mean_profile(runs["paper"][half:])) \
            if half > 0 else float("nan")
        diff = rms(mean_profile(runs["paper"]), mean_profile(runs["fire"]))

        def cost(s):
            return (f"{sum(x['seconds'] for x in s) / len(s):.1f}, "
                    f"{sum(x['iterations'] for x in s) / len(s):.3g}")

        print(f"| {a:g} | {particles_for(a, args.height)} | {len(runs['paper'])}/{len(seeds)} "
              f"| {e_paper:.4f} "
              f"| {e_fire:.4f} | {e_fire - e_paper:+.4f} | {diff:.4f} | {noise:.4f} "
              f"| {cost(paper)} | {cost(fire)} |", flush=True)


if __name__ == "__main__":
    main()
