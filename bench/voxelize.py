"""Time voxel images: the binary and the exact image of one bed, in one run, through
the Python module (the computation alone) and the command line (with reading the bed and
writing the .npy file). Usage (Debian's Python, the module on the path):

    PYTHONPATH=build/python /usr/bin/python3 bench/voxelize.py BED_DIR [VOXEL_SIZE] [REPEATS] [module]

BED_DIR holds particles.csv and summary.json (e.g. `packbed generate -a 20 -n 100000 -s 1
--out BED_DIR`); VOXEL_SIZE in the bed's units (default 0.05: 20 voxels per diameter of 1);
`module`: the module's timings only (to compare two builds, one PYTHONPATH each, in one command).
"""

import os
import subprocess
import sys
import tempfile
import time

import packbed

bed_dir = sys.argv[1]
h = float(sys.argv[2]) if len(sys.argv) > 2 else 0.05
repeats = int(sys.argv[3]) if len(sys.argv) > 3 else 2
exe = os.environ.get("PACKBED", "build/packbed")
bed = packbed.read(os.path.join(bed_dir, "particles.csv"))
print(f"{len(bed)} spheres, voxel size {h}")
images = [("binary", "float64"), ("fraction", "float64"), ("fraction", "float32")]
best = {}
for _ in range(repeats):
    for kind, dtype in images:
        start = time.perf_counter()
        image = packbed.voxelize(bed, voxel_size=h, kind=kind, dtype=dtype)
        seconds = time.perf_counter() - start
        best[kind, dtype] = min(best.get((kind, dtype), seconds), seconds)
        shape = image.shape
        del image
print(f"image {shape[0]} x {shape[1]} x {shape[2]} = {shape[0] * shape[1] * shape[2]:.3g} voxels")
for kind, dtype in images:
    name = "binary" if kind == "binary" else f"exact {dtype}"
    print(f"module, {name}: {best[kind, dtype]:.2f} s (best of {repeats}), "
          f"{best[kind, dtype] / best['binary', 'float64']:.1f}x the binary")
if len(sys.argv) > 4 and sys.argv[4] == "module":
    sys.exit(0)
with tempfile.TemporaryDirectory() as folder:
    for kind, dtype in images:
        start = time.perf_counter()
        subprocess.run([exe, "voxelize", os.path.join(bed_dir, "particles.csv"), "--voxel-size",
                        str(h), "--kind", kind, "--dtype", dtype, "-q", "-o",
                        os.path.join(folder, "im.npy")], check=True)
        print(f"command line, {kind} {dtype}, with reading and writing .npy: "
              f"{time.perf_counter() - start:.2f} s")
        os.remove(os.path.join(folder, "im.npy"))
