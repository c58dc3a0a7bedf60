#!/usr/bin/env python3
"""The validation of Salvat et al. (2005), Figs. 2-4, as a resumable sweep.

For each aspect ratio a and seed, runs `packbed generate` (which also analyses the bed) into
OUT/a<a>/seed<seed>/, skipping runs whose summary.json exists (so an interrupted sweep resumes
where it stopped). Then writes to OUT:
  fig4.md, fig4.csv   overall void fraction per a: seeds, mean, min, max, and the correlations
  fig4.svg            the same as a plot (gnuplot, when installed)
  profiles_a<a>.csv   mean radial void fraction and centre distribution over the seeds
  profiles_a<a>.svg   those with the de Klerk and Mueller correlations (gnuplot)
Np per a: the bed holds HEIGHT diameters at void fraction 0.4, Np = 1.5 (1 - 0.4) a^2 HEIGHT.

Usage: examples/validate.py [--packbed build/packbed] [--aspect-ratios 5,6,7.99,10,15,20,30]
                            [--seeds 1-10] [--height 25] [--band-clearance 2] [--out DIR]
"""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import time


def parse_seeds(text):
    seeds = []
    for part in text.split(","):
        if "-" in part:
            lo, hi = part.split("-")
            seeds.extend(range(int(lo), int(hi) + 1))
        else:
            seeds.append(int(part))
    return seeds


def particles_for(a, height):
    return round(1.5 * (1 - 0.4) * a * a * height)


def progress(message, verbose):
    if verbose:
        print(message, file=sys.stderr, flush=True)


def read_profile(path, column):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [float(r["x_from_wall_d"]) for r in rows], [float(r[column]) for r in rows]


def gnuplot(script):
    if shutil.which("gnuplot") is None:
        return False
    subprocess.run(["gnuplot"], input=script, text=True, check=True)
    return True


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--packbed", default="build/packbed")
    p.add_argument("--aspect-ratios", default="5,6,7.99,10,15,20,30")
    p.add_argument("--seeds", default="1-10")
    p.add_argument("--height", type=float, default=25.0, help="bed height in diameters")
    p.add_argument("--band-clearance", type=float, default=2.0, help="in diameters")
    p.add_argument("--profiles-at", default="7.99", help="aspect ratio of the Fig. 2-3 profiles")
    p.add_argument("--solver", default="paper", choices=["paper", "fire"],
                   help="paper (default here): the article's own schedule, as docs/validation.md")
    p.add_argument("--out", default="results/validation")
    p.add_argument("--verbose", action="store_true", help="progress even when not on a terminal")
    args = p.parse_args()
    verbose = args.verbose or sys.stderr.isatty()
    ratios = [float(a) for a in args.aspect_ratios.split(",")]
    seeds = parse_seeds(args.seeds)
    os.makedirs(args.out, exist_ok=True)

    # The runs, resumable: a finished run is one whose summary.json exists.
    todo = [(a, s) for a in ratios for s in seeds]
    for k, (a, seed) in enumerate(todo, 1):
        run = os.path.join(args.out, f"a{a:g}", f"seed{seed}")
        if os.path.exists(os.path.join(run, "summary.json")):
            progress(f"[{k}/{len(todo)}] a = {a:g}, seed {seed}: done before", verbose)
            continue
        start = time.time()
        subprocess.run([args.packbed, "generate", "--solver", args.solver, "--aspect-ratio", f"{a:g}",
                        "--particles", str(particles_for(a, args.height)), "--seed", str(seed),
                        "--band-clearance", f"{args.band_clearance:g}", "--quiet",
                        "--out", run], check=True)
        with open(os.path.join(run, "summary.json")) as f:
            e = json.load(f)["void_fraction"]
        progress(f"[{k}/{len(todo)}] a = {a:g}, seed {seed}: e = {e:.4f}, "
                 f"{time.time() - start:.0f} s", verbose)

    # Fig. 4: overall void fraction against a, with the correlations.
    names = None
    rows = []
    for a in ratios:
        values = []
        for seed in seeds:
            with open(os.path.join(args.out, f"a{a:g}", f"seed{seed}", "summary.json")) as f:
                values.append(json.load(f)["void_fraction"])
        corr = json.loads(subprocess.run([args.packbed, "correlations", "--aspect-ratio",
                                          f"{a:g}", "--json"], check=True, text=True,
                                         capture_output=True).stdout)["mean_void_fraction"]
        names = list(corr)
        rows.append([a, particles_for(a, args.height), len(values), sum(values) / len(values),
                     min(values), max(values)] + [corr[n]["value"] for n in names])
    header = ["a", "Np", "seeds", "mean", "min", "max"] + names
    with open(os.path.join(args.out, "fig4.csv"), "w") as f:
        f.write(",".join(header) + "\n")
        for r in rows:
            f.write(",".join(f"{v:g}" if isinstance(v, float) else str(v) for v in r) + "\n")
    with open(os.path.join(args.out, "fig4.md"), "w") as f:
        f.write("| " + " | ".join(header) + " |\n|" + "---|" * len(header) + "\n")
        for r in rows:
            f.write("| " + " | ".join([f"{r[0]:g}", str(r[1]), str(r[2])] +
                                      [f"{v:.4f}" for v in r[3:]]) + " |\n")
    # The correlations as curves: on a fine grid of a across the plotted range.
    lo, hi = min(ratios) - 1, max(ratios) + 1
    grid = [lo + 0.25 * k for k in range(int((hi - lo) / 0.25) + 1)]
    with open(os.path.join(args.out, "fig4_correlations.csv"), "w") as f:
        f.write("a," + ",".join(names) + "\n")
        for a in grid:
            corr = json.loads(subprocess.run(
                [args.packbed, "correlations", "--aspect-ratio", f"{a:g}", "--json"], check=True,
                text=True, capture_output=True).stdout)["mean_void_fraction"]
            f.write(f"{a:g}," + ",".join(f"{corr[n]['value']:.6g}" for n in names) + "\n")
    columns = ", ".join(f"'{args.out}/fig4_correlations.csv' using 1:{2 + i} with lines "
                        f"title '{n}'" for i, n in enumerate(names))
    gnuplot(f"""set terminal svg size 720,480 background '#ffffff'
set output '{args.out}/fig4.svg'
set datafile separator ','
set key top right
set xrange [{lo:g}:{hi:g}]
set xlabel 'aspect ratio a = D/d'
set ylabel 'overall void fraction'
plot '{args.out}/fig4.csv' using 1:4:5:6 with yerrorbars pt 7 lc rgb 'black' title 'packbed (mean, min-max)', {columns}
""")

    # Figs. 2-3: mean radial profiles at one aspect ratio, with the correlations.
    a = float(args.profiles_at)
    if a in ratios:
        x, sums_void, sums_centre = None, None, None
        for seed in seeds:
            run = os.path.join(args.out, f"a{a:g}", f"seed{seed}")
            x, v = read_profile(os.path.join(run, "radial_void_fraction.csv"), "void_fraction")
            _, c = read_profile(os.path.join(run, "radial_centre_distribution.csv"),
                                 "relative_density")
            sums_void = v if sums_void is None else [s + t for s, t in zip(sums_void, v)]
            sums_centre = c if sums_centre is None else [s + t for s, t in zip(sums_centre, c)]
        corr = json.loads(subprocess.run([args.packbed, "correlations", "--aspect-ratio",
                                          f"{a:g}", "--json", "--profile-to", f"{a / 2:g}"],
                                         check=True, text=True, capture_output=True).stdout)
        profiles = os.path.join(args.out, f"profiles_a{a:g}.csv")
        with open(profiles, "w") as f:
            f.write("x_from_wall_d,void_fraction,centre_relative_density\n")
            for i in range(len(x)):
                f.write(f"{x[i]:.6g},{sums_void[i] / len(seeds):.6g},"
                        f"{sums_centre[i] / len(seeds):.6g}\n")
        corr_file = os.path.join(args.out, f"correlations_a{a:g}.csv")
        radial = corr["radial_void_fraction"]
        with open(corr_file, "w") as f:
            f.write("x_from_wall_d," + ",".join(radial) + "\n")
            grid = next(iter(radial.values()))["x_from_wall_d"]
            for i, z in enumerate(grid):
                f.write(f"{z:.6g}," + ",".join(f"{radial[n]['void_fraction'][i]:.6g}"
                                                for n in radial) + "\n")
        # How far the mean profile lies from each correlation: RMS over the shells, and the
        # first minimum of each curve.
        mean_void = [v / len(seeds) for v in sums_void]
        with open(os.path.join(args.out, f"profiles_a{a:g}.md"), "w") as f:
            f.write("| profile | RMS difference to packbed (x <= a/2) | first minimum | at x |\n"
                    "|---|---|---|---|\n")
            near = [i for i in range(len(x)) if x[i] < 1.0]
            i_min = min(near, key=lambda i: mean_void[i])
            f.write(f"| packbed (mean of {len(seeds)} beds) | - | {mean_void[i_min]:.3f} "
                    f"| {x[i_min]:.2f} |\n")
            for n in radial:
                values = [radial[n]["void_fraction"][min(round(xi / 0.01), len(grid) - 1)]
                          for xi in x]
                rms = math.sqrt(sum((v - m) ** 2 for v, m in zip(values, mean_void)) / len(x))
                j = min((j for j in range(len(grid)) if grid[j] < 1.0),
                        key=lambda j: radial[n]["void_fraction"][j])
                f.write(f"| {n} | {rms:.3f} | {radial[n]['void_fraction'][j]:.3f} "
                        f"| {grid[j]:.2f} |\n")
        lines = ", ".join(f"'{corr_file}' using 1:{2 + i} with lines title '{n}'"
                          for i, n in enumerate(radial))
        gnuplot(f"""set terminal svg size 900,420 background '#ffffff'
set output '{args.out}/profiles_a{a:g}.svg'
set datafile separator ','
set multiplot layout 1,2
set xlabel 'distance from the wall (R - r)/d'
set xrange [0:{a / 2:g}]
set ylabel 'radial void fraction'
set title 'a = {a:g}: radial void fraction, mean of {len(seeds)} beds'
plot '{profiles}' using 1:2 with lines lw 2 lc rgb 'black' title 'packbed', {lines}
set ylabel 'centre density / mean'
set title 'radial distribution of sphere centres'
plot '{profiles}' using 1:3 with lines lw 2 lc rgb 'black' title 'packbed'
unset multiplot
""")
    print(f"validation written to {args.out}/ (fig4.md, fig4.csv, fig4.svg, profiles_a*.csv/svg)")


if __name__ == "__main__":
    main()
