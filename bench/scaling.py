#!/usr/bin/env python3
"""Wall time and peak memory of `packbed generate` against Np, for both solvers.

For each solver and Np, runs `packbed generate --solver SOLVER --aspect-ratio A --particles Np
--seed 1 --quiet` into OUT/<solver>/n<Np>/ (a = --aspect-ratio, except where --large gives
another a for an Np, e.g. 1000000:50), with a wall-time limit per run: a run that reaches it
is stopped and recorded as "> limit" (its time is then a lower bound), and a solver that hit
the limit is not run at larger Np. Finished runs are not redone, nor stopped ones unless the
limit is now longer (delete OUT to start over).
Peak memory is the run's own maximum resident set size (os.wait4). Writes OUT/scaling.csv, prints a
Markdown table and, where gnuplot exists, draws OUT/scaling.svg (log-log time and steps against
Np; the rows of --before, an earlier version's scaling.csv, dashed beside them).

Usage: bench/scaling.py [--packbed build/packbed] [--particles 1000,3000,...]
                        [--aspect-ratio 20] [--large 1000000:50] [--solvers paper,fire]
                        [--limit 600 | --limit paper:200,fire:1500]
                        [--threads CORES] [--out results/scaling]
                        [--before OLD/scaling.csv --before-label "(old build)"]
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys
import time


def run_one(args, solver, n, a, out):
    limit = args.limits[solver]
    summary = os.path.join(out, "summary.json")
    record = os.path.join(out, "scaling.json")
    if os.path.exists(record):
        with open(record) as f:
            old = json.load(f)
        if old["finished"] or old["wall_s"] >= limit:  # a stopped run reruns if given more time
            return old
    os.makedirs(out, exist_ok=True)
    cmd = [args.packbed, "generate", "--solver", solver, "--aspect-ratio", f"{a:g}",
           "--particles", str(n), "--seed", "1", "--threads", str(args.threads), "--quiet",
           "--force", "--out", out]
    start = time.monotonic()
    proc = subprocess.Popen(cmd)
    status, usage = None, None
    while True:  # os.wait4: the child's own peak memory (ru_maxrss, KiB)
        pid, raw, usage = os.wait4(proc.pid, os.WNOHANG)
        if pid:
            status = os.waitstatus_to_exitcode(raw)
            break
        if time.monotonic() - start > limit:
            proc.kill()
            _, _, usage = os.wait4(proc.pid, 0)
            break
        time.sleep(0.05)
    proc.returncode = status if status is not None else -9  # reaped here, not by Popen
    wall = time.monotonic() - start
    peak_mib = usage.ru_maxrss / 1024.0
    result = {"solver": solver, "particles": n, "aspect_ratio": a, "threads": args.threads,
              "wall_s": round(wall, 2), "peak_mib": round(peak_mib, 1),
              "finished": status == 0, "status": status}
    if status == 0:
        with open(summary) as f:
            s = json.load(f)
        result.update(seconds=s["seconds"], iterations=s["iterations"],
                      void_fraction=s["void_fraction"])
    with open(record, "w") as f:
        json.dump(result, f, indent=1)
    return result


def plot(args, rows):
    """Wall time and steps against Np, two panels; rows of --before drawn dashed."""
    if not shutil.which("gnuplot"):
        print("gnuplot not found: no plot", file=sys.stderr)
        return
    series = {}  # (label, finished) -> [(Np, wall, iterations)]
    for r in rows:
        series.setdefault((r["label"], r["finished"]), []).append(
            (r["particles"], r["wall_s"], r.get("iterations") or 0))
    colours = {"paper": "#9400d3", "fire": "#009e73"}
    lines = ["set terminal svg size 1200,500 font 'sans,12'",
             f"set output '{os.path.join(args.out, 'scaling.svg')}'",
             "set multiplot layout 1,2 title "
             f"'seed 1, {args.threads} threads, a = {args.aspect_ratio:g} (Np = 1e6: a = 50); "
             f"open marks: stopped at the limit'",
             "set logscale xy", "set grid", "set key top left", "set xrange [500:2e6]",
             "set xlabel 'spheres Np'",
             "$targets << EOD", "100000 60", "1000000 900", "EOD"]
    blocks = {}  # (label, finished) -> gnuplot data block name
    for k, (key, points) in enumerate(series.items()):
        blocks[key] = f"$s{k}"
        lines.append(f"{blocks[key]} << EOD")
        lines += [f"{n} {t} {it}" for n, t, it in sorted(points)]
        lines.append("EOD")

    def curves(column):
        out = []
        for (label, finished), name in blocks.items():
            solver = label.split()[0]
            dashed = " dt 2" if label != solver else ""
            style = "linespoints lw 2 pt 7" if finished else "points pt 6 ps 1.5"
            if column == 3 and not finished:
                continue  # a stopped run has no step count
            out.append(f"{name} using 1:{column} with {style}{dashed} lc rgb "
                       f"'{colours.get(solver, 'blue')}' title '{label}"
                       f"{'' if finished else ', stopped'}'")
        return out
    lines += ["set yrange [0.5:30000]", "set ylabel 'wall time of packbed generate (s)'",
              "plot $targets with points pt 3 ps 2 lc rgb 'black' title 'targets (fire)', "
              + ", ".join(curves(2))]
    lines += ["set yrange [3e3:1e7]", "set ylabel 'steps (iterations), all layers'",
              "plot " + ", ".join(curves(3)), "unset multiplot"]
    subprocess.run(["gnuplot"], input="\n".join(lines), text=True, check=True)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--packbed", default="build/packbed")
    p.add_argument("--particles", default="1000,3000,10000,30000,100000,1000000")
    p.add_argument("--aspect-ratio", type=float, default=20.0)
    p.add_argument("--large", default="1000000:50", help="Np:a pairs with their own a")
    p.add_argument("--solvers", default="paper,fire")
    p.add_argument("--limit", default="600",
                   help="seconds per run: one number, or SOLVER:SECONDS pairs (paper:200,fire:1500)")
    p.add_argument("--threads", type=int, default=os.cpu_count(),
                   help="--threads of every run (default: every core, as packbed's own default)")
    p.add_argument("--out", default="results/scaling")
    p.add_argument("--before", help="scaling.csv of an earlier version: drawn dashed beside")
    p.add_argument("--before-label", default="before",
                   help="what the plot's key adds to the earlier version's solver names")
    args = p.parse_args()
    try:
        if ":" in args.limit:
            args.limits = {k: float(v) for k, v in (i.split(":") for i in args.limit.split(","))}
        else:
            args.limits = {s: float(args.limit) for s in args.solvers.split(",")}
    except ValueError:
        sys.exit(f"scaling.py: --limit {args.limit!r}: a number or SOLVER:SECONDS pairs")
    if any(solver not in args.limits or args.limits[solver] <= 0
           for solver in args.solvers.split(",")) or args.threads < 1:
        sys.exit("scaling.py: every solver needs a --limit > 0, and --threads >= 1")
    own_a = {int(k): float(v) for k, v in
             (item.split(":") for item in args.large.split(",") if item)}
    rows = []
    print("| solver | Np | a | wall time (s) | iterations | void fraction | peak memory (MiB) |")
    print("|---|---|---|---|---|---|---|")
    for solver in args.solvers.split(","):
        for n in sorted(int(float(x)) for x in args.particles.split(",")):
            a = own_a.get(n, args.aspect_ratio)
            r = run_one(args, solver, n, a, os.path.join(args.out, solver, f"n{n}"))
            rows.append(dict(r, label=solver))
            wall = f"{r['wall_s']:.1f}" if r["finished"] else f"> {r['wall_s']:.0f} (stopped)"
            e = r.get("void_fraction")
            print(f"| {solver} | {n} | {a:g} | {wall} | {r.get('iterations', '-')} "
                  f"| {'-' if e is None else f'{e:.4f}'} | {r['peak_mib']:.0f} |", flush=True)
            if not r["finished"]:
                break  # larger beds take longer still
    with open(os.path.join(args.out, "scaling.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["solver", "particles", "aspect_ratio", "threads",
                                          "wall_s", "finished", "iterations", "void_fraction",
                                          "peak_mib"], extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    if args.before:
        with open(args.before) as f:
            for r in csv.DictReader(f):
                rows.append({"label": f"{r['solver']} {args.before_label}",
                             "particles": int(r["particles"]), "wall_s": float(r["wall_s"]),
                             "finished": r["finished"] == "True",
                             "iterations": int(r["iterations"]) if r["iterations"] else 0})
    plot(args, rows)


if __name__ == "__main__":
    main()
