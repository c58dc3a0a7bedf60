"""A small study with the Python module: the overall void fraction of the paper's beds against
the aspect ratio a = D/Dp, three seeds each, plotted with the correlation of Dixon (1988)
(docs/validation.md). Usage: void_fraction_study.py [PLOT.png]

Run with Debian's Python and the module on the path, e.g.
    PYTHONPATH=build/python /usr/bin/python3 examples/void_fraction_study.py study.png
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import packbed

ratios = [3, 4, 5, 6, 8, 10]
seeds = [1, 2, 3]
means, spreads = [], []
for a in ratios:
    # about 12 Dp of bed at every a (eq. 6 with e0 = 0.47)
    particles = int(round(0.53 * 1.5 * a * a * 12))
    e = [packbed.generate(aspect_ratio=a, particles=particles, seed=s).summary["void_fraction"]
         for s in seeds]
    means.append(np.mean(e))
    spreads.append(np.std(e))
    print(f"a = {a:>2}: {particles:>4} spheres, void fraction {np.mean(e):.4f} "
          f"(seeds {', '.join(f'{x:.4f}' for x in e)})")

# Dixon (1988), spheres: e = 0.4 + 0.05 / a + 0.412 / a^2
fine = np.linspace(min(ratios), max(ratios), 100)
plt.errorbar(ratios, means, yerr=spreads, fmt="o", capsize=3, label="packbed, 3 seeds each")
plt.plot(fine, 0.4 + 0.05 / fine + 0.412 / fine**2, label="Dixon (1988)")
plt.xlabel("aspect ratio a = D / Dp")
plt.ylabel("overall void fraction")
plt.legend()
plt.savefig(sys.argv[1] if len(sys.argv) > 1 else "void_fraction_study.png", dpi=100)
