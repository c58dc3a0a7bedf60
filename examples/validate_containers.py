#!/usr/bin/env python3
"""The containers' validation of docs/validation.md ("Containers").

Runs `packbed generate` (FIRE, mono-sized, frictionless) in a periodic cell (three seeds), a wide
cylinder, a box and an annulus, all about 30 Dp tall, and prints:
- the bulk void fraction (the band 5 Dp clear of the floor and of the top) and the mean
  coordination of the non-rattlers (contact gap <= 1e-3 Dp, rattlers: fewer than 4 contacts),
  to compare with random close packing of frictionless spheres (solid fraction about 0.639,
  isostatic coordination 6);
- each wall's profile: the first minimum of e(x) (x the distance from the wall in Dp), and the
  mean e more than 4 Dp from every wall (the core).

Usage: python3 examples/validate_containers.py [--packbed build/packbed] [--out DIR]
Standard library only; about 5 minutes on 2 cores.
"""
import argparse
import csv
import json
import os
import subprocess
import sys

CASES = [
    # name, --container, particles, seed
    ("periodic s1", "periodic:12,12", 6000, 1),
    ("periodic s2", "periodic:12,12", 6000, 2),
    ("periodic s3", "periodic:12,12", 6000, 3),
    ("cylinder a=16", "cylinder:16", 7000, 1),
    ("box 16 x 16", "box:16,16", 8000, 1),
    ("annulus 16, 4", "annulus:16,4", 6000, 1),
]


def profile(path):
    """(x from the wall in Dp, e) rows of a radial_void_fraction table."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return [(float(r["x_from_wall_d"]), float(r["void_fraction"])) for r in rows]


def first_minimum(rows):
    inside = [r for r in rows if 0.3 <= r[0] <= 0.8]
    return min(inside, key=lambda r: r[1]) if inside else (float("nan"), float("nan"))


def core(rows, beyond=4.0):
    values = [e for x, e in rows if x > beyond]
    return sum(values) / len(values) if values else float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--packbed", default="build/packbed")
    parser.add_argument("--out", default="validate-containers")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    print("| bed | e (5 Dp clear) | Z non-rattlers | rattlers | wall | first minimum x, e | core e |")
    print("|---|---|---|---|---|---|---|")
    for name, spec, n, seed in CASES:
        out = os.path.join(args.out, name.replace(" ", "_").replace(",", "").replace("=", ""))
        subprocess.run([args.packbed, "generate", "--container", spec, "--particles", str(n),
                        "--seed", str(seed), "--band-clearance", "5", "--quiet", "--force",
                        "--out", out], check=True)
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
        a = s["analysis"]
        c = a["coordination"]
        walls = [w["name"] for w in a.get("walls", [])] or (
            [] if spec.startswith("periodic") else ["wall"])
        cells = []
        for w in walls:
            table = "radial_void_fraction.csv" if w == "wall" else f"radial_void_fraction_{w}.csv"
            rows = profile(os.path.join(out, table))
            x, e = first_minimum(rows)
            centre = core(rows)
            cells.append((w, f"{x:.2f}, {e:.3f}", "-" if centre != centre else f"{centre:.3f}"))
        if not cells:
            cells = [("none", "-", "-")]
        for k, (w, minimum, centre) in enumerate(cells):
            head = (f"| {name} | {a['void_fraction']:.4f} | {c['mean_without_rattlers']:.3f} | "
                    f"{c['rattlers'] / c['spheres']:.1%} |") if k == 0 else "| | | | |"
            print(f"{head} {w} | {minimum} | {centre} |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
