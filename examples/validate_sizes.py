#!/usr/bin/env python3
"""Binary beds against the binary-mixture packing models (docs/validation.md).

Packs spheres of diameters 1 and RATIO (by volume fractions X_L of the large ones) in a tube of
diameter D (in units of the small diameter) with `packbed generate --sizes discrete:...`, each
bed holding about the same solid volume, and prints the measured overall void fraction next to
two published models of binary packings, fed with the measured void fractions of the two
mono-sized beds (X_L = 0 and 1) of the same sweep:

- Yu & Standish (1987), Powder Technol. 52, 233-241, as implemented in MFIX
  (model/calc_p_star.f, CALC_EP_STAR, YU_STANDISH): for the fine component i and coarse j,
  r = d_fine / d_coarse; if r <= 0.741, P_ij = phi_i + phi_i (1 - phi_i)(1 - 2.35 r + 1.35 r^2),
  X_ij = (1 - r^2) / (2 - phi_i) (j coarser) or 1 - (1 - r^2) / (2 - phi_i) (j finer);
  P_i = phi_i / (1 - sum_j (1 - phi_i / P_ij) X_j / X_ij); phi = min_i P_i.
- the linear packing model with Yu, Zou & Standish's (1996) interaction functions, Ind. Eng.
  Chem. Res. 35, 3730-3741: V = max(V_L X_L + V_L (1 - a) X_S, (V_S - (V_S - 1) b) X_L + V_S X_S),
  V = 1 / phi, a(r) = (1 - r)^3.3 + 2.8 r (1 - r)^2.7, b(r) = (1 - r)^2 + 0.4 r (1 - r)^3.7.

Both are for unbounded (bulk) beds; ours are in a tube, so the comparison is of how much the
mixture densifies against its two mono-sized beds, not of absolute values.

Usage: examples/validate_sizes.py [--packbed build/packbed] [--ratio 2] [--tube 20]
                                  [--fractions 0,0.25,0.5,0.75,1] [--solid 2300] [--seed 1]
                                  [--out results/validate-sizes]
"""
import argparse
import json
import math
import os
import subprocess


def yu_standish(phi, d, x):
    """phi, d, x: per component (packing fraction alone, diameter, volume fraction)."""
    n = len(phi)
    totals = []
    for i in range(n):
        s = 0.0
        for j in range(n):
            if j == i or x[j] == 0.0:
                continue
            r = min(d[i], d[j]) / max(d[i], d[j])
            if r > 0.741:
                continue
            p_ij = phi[i] + phi[i] * (1 - phi[i]) * (1 - 2.35 * r + 1.35 * r * r)
            x_ij = (1 - r * r) / (2 - phi[i]) if d[j] > d[i] else 1 - (1 - r * r) / (2 - phi[i])
            s += (1 - phi[i] / p_ij) * x[j] / x_ij
        totals.append(phi[i] / (1 - s) if x[i] > 0.0 else 1.0)
    return min(totals)


def linear_model(phi_small, phi_large, ratio, x_large):
    r = 1.0 / ratio
    a = (1 - r) ** 3.3 + 2.8 * r * (1 - r) ** 2.7
    b = (1 - r) ** 2.0 + 0.4 * r * (1 - r) ** 3.7
    v_s, v_l = 1 / phi_small, 1 / phi_large
    x_s = 1 - x_large
    v = max(v_l * x_large + v_l * (1 - a) * x_s, (v_s - (v_s - 1) * b) * x_large + v_s * x_s)
    return 1 / v


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--packbed", default="build/packbed")
    p.add_argument("--ratio", type=float, default=2.0)
    p.add_argument("--tube", type=float, default=20.0, help="tube diameter, small diameters")
    p.add_argument("--fractions", default="0,0.25,0.5,0.75,1")
    p.add_argument("--solid", type=float, default=2300.0, help="solid volume, small d^3")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--out", default="results/validate-sizes")
    o = p.parse_args()
    rows = []
    for text in o.fractions.split(","):
        x_large = float(text)
        spec = f"discrete:1:{1 - x_large:g},{o.ratio:g}:{x_large:g}"
        # Spheres for the solid volume: volume per sphere by number, 1 / sum(F_k / v_k).
        v_small, v_large = math.pi / 6, math.pi / 6 * o.ratio ** 3
        per_sphere = 1 / ((1 - x_large) / v_small + x_large / v_large)
        n = round(o.solid / per_sphere)
        out = os.path.join(o.out, f"xl{x_large:g}")
        if not os.path.exists(os.path.join(out, "summary.json")):
            subprocess.run([o.packbed, "generate", "-q", "--sizes", spec, "--container",
                            f"cylinder:{o.tube:g}", "--particles", str(n), "--seed",
                            str(o.seed), "--force", "--out", out], check=True)
        s = json.load(open(os.path.join(out, "summary.json")))
        rows.append((x_large, n, s["void_fraction"], s["iterations"], s["seconds"]))
    e = {x: v for x, _, v, _, _ in rows}
    phi_s, phi_l = 1 - e[0.0], 1 - e[1.0]
    print(f"| X_L | spheres | e (packbed) | e Yu & Standish 1987 | e linear model 1996 | "
          f"steps | s |")
    print("|---|---|---|---|---|---|---|")
    for x_large, n, void, steps, seconds in rows:
        ys = 1 - yu_standish([phi_s, phi_l], [1.0, o.ratio], [1 - x_large, x_large])
        lm = 1 - linear_model(phi_s, phi_l, o.ratio, x_large)
        print(f"| {x_large:g} | {n} | {void:.4f} | {ys:.4f} | {lm:.4f} | {steps} | "
              f"{seconds:.1f} |")


if __name__ == "__main__":
    main()
