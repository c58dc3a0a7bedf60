#!/usr/bin/env python3
"""Radial void fraction and orientation profiles of pellet beds in a tube, over seeds
(docs/validation.md, "Pellets: radial profiles").

Each SPEC is SHAPE/A/N/SEED[/MU], e.g. cylinder:1,1/5/165/1 or ring:1,0.5,1/4/75/2/0.3 (MU the
friction at the pellets and the walls). A bed is generated into OUT (one thread) unless its
particles.csv is there already, then analysed (`--shell-width 0.1`). Printed, for the beds of
each shape, a and friction together: e against the distance from the wall (the mean over the
seeds and its range), and the pellets' orientation in bands of centroid distance: <cos^2 theta>
(theta from the tube's axis; 1/3 at random) and <cos^2 psi> (psi from the wall's normal, the
radius; 1/3 at random), counted over every pellet of every seed in the band; and the wall
layer (the pellets that touch the wall, within 0.01 D, with their centroid 1 d_v clear of the
floor and the top, from particles.csv): how many pellets point an end at the wall (cos^2 psi > 0.9), lie with their side
on it (cos^2 psi < 0.1) or neither, and the side-on ones' axes against the horizontal in 15-degree
bins (their axes lie near the wall's plane, the z-theta plane).

Usage: bench/pellet_profiles.py PACKBED OUT SPEC [SPEC ...]
"""
import csv
import json
import math
import os
import subprocess
import sys
from collections import defaultdict

BANDS = [(0.0, 0.5), (0.5, 0.7), (0.7, 1.0), (1.0, 1.5), (1.5, 2.0), (2.0, 99.0)]


def run(cmd):
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def bed(exe, out, spec):
    parts = spec.split("/")
    shape, a, n, seed = parts[:4]
    mu = parts[4] if len(parts) > 4 else None
    name = f"{shape.split(':')[0]}_a{a}_n{n}_s{seed}" + (f"_mu{mu}" if mu else "")
    path = os.path.join(out, name)
    if not os.path.exists(os.path.join(path, "particles.csv")):
        cmd = [exe, "generate", "--shape", shape, "-a", a, "-n", n, "-s", seed, "--threads", "1",
               "-q", "-o", path, "--force"]
        if mu:
            cmd += ["--friction", mu, "--wall-friction", mu]
        run(cmd)
    analysis = path + "-analysis"
    if not os.path.exists(os.path.join(analysis, "orientation_profile.csv")):
        run([exe, "analyze", os.path.join(path, "particles.csv"), "--shell-width", "0.1", "-q",
             "-o", analysis, "--force"])
    return (shape, a, mu), analysis, path


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def wall_layer(path, shape):
    """(cos^2 psi, axis angle from the horizontal in degrees) of each pellet of the bed at
    `path` that touches the tube's wall (its rims' farthest point within 0.01 D of it; a
    cylinder or a ring, D and L the first and last numbers of `shape`) with its centroid in the
    band 1 d_v clear of the floor and of the highest centroid."""
    numbers = [float(v) for v in shape.split(":")[1].split(",")]
    half_d, half_l = 0.5 * numbers[0], 0.5 * numbers[-1]
    summary = json.load(open(os.path.join(path, "summary.json")))
    radius = summary["container"]["radius"]
    rows = read(os.path.join(path, "particles.csv"))
    dv = 2.0 * float(rows[0]["r"])
    top = max(float(r["z"]) for r in rows)
    out = []
    for r in rows:
        x, y, z = float(r["x"]), float(r["y"]), float(r["z"])
        if not (dv <= z <= top - dv):
            continue
        w, qx, qy, qz = (float(r[k]) for k in ("qw", "qx", "qy", "qz"))
        # The body axes turned by the quaternion: the columns of its matrix.
        e1 = (1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy + w * qz), 2 * (qx * qz - w * qy))
        e2 = (2 * (qx * qy - w * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz + w * qx))
        axis = (2 * (qx * qz + w * qy), 2 * (qy * qz - w * qx), 1 - 2 * (qx * qx + qy * qy))
        farthest = 0.0
        for k in range(720):
            c, s_ = math.cos(math.pi * k / 360), math.sin(math.pi * k / 360)
            for sign in (-1.0, 1.0):
                px = x + half_d * (c * e1[0] + s_ * e2[0]) + sign * half_l * axis[0]
                py = y + half_d * (c * e1[1] + s_ * e2[1]) + sign * half_l * axis[1]
                farthest = max(farthest, math.hypot(px, py))
        rho = math.hypot(x, y)
        if radius - farthest > 0.01 * numbers[0] or rho == 0.0:
            continue
        towards = (axis[0] * x + axis[1] * y) / rho
        out.append((towards * towards, math.degrees(math.asin(min(1.0, abs(axis[2]))))))
    return out


def main():
    exe, out, specs = os.path.realpath(sys.argv[1]), sys.argv[2], sys.argv[3:]
    os.makedirs(out, exist_ok=True)
    groups = defaultdict(list)
    for spec in specs:
        key, analysis, path = bed(exe, out, spec)
        groups[key].append((analysis, path))
    for (shape, a, mu), pairs in groups.items():
        beds = [analysis for analysis, _ in pairs]
        print(f"\n{shape}, a = {a}, friction {mu or 0}: {len(beds)} beds")
        summaries = [json.load(open(os.path.join(b, "summary.json"))) for b in beds]
        e = [s["void_fraction"] for s in summaries]
        print(f"e in the band: mean {sum(e) / len(e):.4f} ({min(e):.4f}-{max(e):.4f})")
        radial = [read(os.path.join(b, "radial_void_fraction.csv")) for b in beds]
        print("| x from the wall (d_v) | e, mean | range |")
        print("|---|---|---|")
        for k in range(len(radial[0])):
            values = [float(r[k]["void_fraction"]) for r in radial]
            x = float(radial[0][k]["x_from_wall_d"])
            print(f"| {x:.2f} | {sum(values) / len(values):.4f} | {min(values):.4f}-"
                  f"{max(values):.4f} |")
        print("| centroid from the wall (d_v) | pellets | <cos^2 theta> | <cos^2 psi> |")
        print("|---|---|---|---|")
        for low, high in BANDS:
            n = cos2 = cos2_wall = 0.0
            for b in beds:
                for row in read(os.path.join(b, "orientation_profile.csv")):
                    x = float(row["x_from_wall_d"])
                    if low <= x < high and int(row["pellets"]) > 0:
                        k = int(row["pellets"])
                        n += k
                        cos2 += k * float(row["mean_cos2"])
                        cos2_wall += k * float(row["mean_cos2_wall"])
            if n:
                label = f"{low:.1f}-{high:.1f}" if high < 99 else f"{low:.1f} and more"
                print(f"| {label} | {int(n)} | {cos2 / n:.3f} | {cos2_wall / n:.3f} |")
        layer = [p for _, path in pairs for p in wall_layer(path, shape)]
        end_on = sum(1 for c, _ in layer if c > 0.9)
        side_on = [angle for c, angle in layer if c < 0.1]
        print(f"wall layer: {len(layer)} pellets, {end_on} with an end at the wall, "
              f"{len(side_on)} with their side on it, {len(layer) - end_on - len(side_on)} neither")
        bins = [0] * 6
        for angle in side_on:
            bins[min(5, int(angle // 15))] += 1
        print("side on the wall, axis from the horizontal: " +
              ", ".join(f"{15 * k}-{15 * k + 15} deg: {n}" for k, n in enumerate(bins)))


if __name__ == "__main__":
    main()
