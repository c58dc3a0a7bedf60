#!/usr/bin/env python3
"""The tube beds' converged CFD pressure gradients placed in the band of correlations
(docs/validation.md, "The tube beds in the band"): each bed's gradient and every correlation of
`packbed hydraulics` at that bed's void fraction, aspect ratio and velocity, all over Ergun's,
against a; the CFD with its uncertainty (the grid convergence index of its mesh series) as an
error bar.

Usage: bench/cfd_band.py PACKBED BEDS.csv OUT
    BEDS.csv: one row per bed, the columns a, void_fraction (the band's, as cfd-report reads
    it), velocity (m/s, the case's superficial velocity), pa_m (the converged gradient, Pa/m),
    gci (its relative uncertainty, 0.014 for 1.4 %; empty where the series has not converged:
    pa_m is then the finest mesh's, drawn as an open point) and bed (a label); the case's other
    defaults (d = 1 mm, water) are hydraulics' own. Writes OUT/cfd-band.csv (every value over
    Ergun's) and, where gnuplot exists, OUT/cfd-band.svg; OUT is created if missing.
"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys


def band(exe, a, e, u):
    """Every correlation of the band, Pa/m, by its label, and Ergun's."""
    out = subprocess.run([exe, "hydraulics", "--porosity", repr(e), "--aspect-ratio", repr(a),
                          "--velocity", repr(u), "--json"], check=True, text=True,
                         capture_output=True).stdout
    gradient = json.loads(out)["pressure_gradient"]
    return {c["label"]: c["Pa_m"] for c in gradient["band"]}, gradient["ergun_Pa_m"]


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    exe, beds_csv, out = sys.argv[1:]
    with open(beds_csv, newline="") as f:
        beds = list(csv.DictReader(f))
    os.makedirs(out, exist_ok=True)
    rows, labels = [], None
    for bed in beds:
        a, e, u = float(bed["a"]), float(bed["void_fraction"]), float(bed["velocity"])
        values, ergun = band(exe, a, e, u)
        labels = labels or list(values)
        cfd = float(bed["pa_m"]) / ergun
        converged = bed["gci"].strip() != ""
        bar = cfd * float(bed["gci"]) if converged else math.nan
        rows.append([a, cfd if converged else math.nan, bar, math.nan if converged else cfd] +
                    [values[k] / ergun for k in labels])
        print(f"a = {a:g} ({bed['bed']}): CFD {cfd:.3f} " +
              (f"+- {bar:.3f}" if converged else "(finest mesh, not converged)") +
              " of Ergun; " + ", ".join(f"{k} {values[k] / ergun:.3f}" for k in labels))
    path = os.path.join(out, "cfd-band.csv")
    with open(path, "w") as f:
        f.write(",".join(["a", "cfd", "cfd_gci", "cfd_finest"] + [f'"{k}"' for k in labels]) +
                "\n")
        for r in sorted(rows, key=lambda r: r[0]):
            # a value that does not apply (no bar, no open point) is an empty field: missing
            # to gnuplot, never a NaN in a file
            f.write(",".join("" if math.isnan(v) else f"{v:.6g}" for v in r) + "\n")
    if shutil.which("gnuplot") is None:
        print(f"written {path} (no gnuplot: no plot)")
        return
    curves = [f"'{path}' using 1:{5 + i} with linespoints title '{k}' noenhanced"
              for i, k in enumerate(labels)]
    curves.append(f"'{path}' using 1:2:3 with yerrorbars pt 7 ps 1.2 lc rgb 'black' "
                  "title 'CFD, converged (GCI)'")
    if any(not math.isnan(r[3]) for r in rows):  # the key shows the open point only if drawn
        curves.append(f"'{path}' using 1:4 with points pt 12 ps 2 lc rgb 'black' "
                      "title 'CFD, finest mesh, not converged'")
    script = f"""set terminal svg size 720,480 background '#ffffff'
set output '{out}/cfd-band.svg'
set datafile separator ','
set key top right
set logscale x
set xtics (5, 10, 20)
set xrange [4:25]
set yrange [0.8:1.7]
set xlabel 'aspect ratio a = D/d'
set ylabel "pressure gradient / Ergun's"
plot {", ".join(curves)}
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)
    print(f"written {path} and {out}/cfd-band.svg")


if __name__ == "__main__":
    main()
