#!/usr/bin/env python3
"""The layering check: no include goes up a floor (ARCHITECTURE.md, "Floors").

Every quoted #include of src/, include/packbed/, apps/ and python/ is checked. A file's floor is
its folder's (src/base, src/geometry, ...); a public header's is the folder of the source file
that implements it (include/packbed/x.hpp: src/*/x.cpp; pipeline.hpp: src/pipeline/), or the
ground floor for a header with no source file (error, limits, packing, registry, vec3), except
those HEADER_ONLY names (shape.hpp: what a container answers, and particle_shape.hpp: what a
particle answers, on the containers' floor). An
include of a higher floor is a finding.
Exit status 0 when clean, 1 with one line per finding.

Usage: scripts/check-layers.py [REPO]
"""
import pathlib
import re
import sys

FLOORS = {  # bottom to top; the folders of one floor may include each other
    "base": 0,
    "geometry": 1,
    "generate": 2, "analyze": 2, "export": 2, "particles": 2,
    "io": 3,
    "pipeline": 4,
    "apps": 5, "python": 5,
}


HEADER_ONLY = {"shape": "geometry", "particle_shape": "geometry", "pellet_shape": "particles"}  # public headers with no source file above the ground floor


def main():
    repo = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    implemented = {"pipeline": "pipeline", **HEADER_ONLY}  # header stem -> floor
    for source in (repo / "src").rglob("*.cpp"):
        implemented[source.stem] = floor_of(source.relative_to(repo))

    def header_floor(name, including):
        if name.startswith("packbed/"):
            return implemented.get(pathlib.Path(name).stem, "base")
        if "/" in name:
            return name.split("/")[0]
        return floor_of(including.parent.relative_to(repo) / name)

    findings = []
    files = [p for d in ("src", "include/packbed", "apps", "python")
             for p in (repo / d).rglob("*") if p.suffix in (".cpp", ".hpp")]
    for path in sorted(files):
        rel = path.relative_to(repo)
        own = implemented.get(path.stem, "base") if rel.parts[0] == "include" else floor_of(rel)
        for number, line in enumerate(path.read_text().splitlines(), 1):
            m = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
            if not m:
                continue
            target = header_floor(m.group(1), path)
            if target not in FLOORS or FLOORS[target] <= FLOORS[own]:
                continue
            findings.append(f"{rel}:{number}: {own} includes {m.group(1)} ({target}), a floor "
                            f"above it")
    for f in findings:
        print(f)
    return 1 if findings else 0


def floor_of(rel):
    parts = pathlib.Path(rel).parts
    if parts[0] == "src":
        return parts[1] if len(parts) > 2 else "base"
    return parts[0]  # apps, python


if __name__ == "__main__":
    sys.exit(main())
