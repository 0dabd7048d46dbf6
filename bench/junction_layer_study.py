#!/usr/bin/env python3
"""Why the assumed shear's mode estimates overstate the error of thin-walled profiles (issue 49).

The thin steel box of tests/modal_adapt.rs (100 × 50 mm, walls 1 mm, 0.4 m cantilever, 3 × 2 L9 along
the walls, 4 B4, `formulation = "assumed_shear"`), written once as the `box` profile and then as
`shape = "quads"` over the same grid lines (which reproduces the profile's frequencies and estimates), then
with each wall graded: a first element of 2 mm or 0.5 mm next to each junction. For each: DOF, the lowest
five frequencies and their estimated relative errors (summary.json `modal.frequency_errors`), and the share
of mode 1's estimate in the wall elements next to the junctions (mode_1.vtu `error`).

    python3 bench/junction_layer_study.py      # about a minute; writes out/junction_layer/

Compare with the true errors of tests/modal_adapt.rs (rows modal_adapt.assumed_shear.mode<k>.true of
docs/validation.md: mode 1 0.579 % on the uniform 3 × 2 mesh, against 24 × 16 L9 × 8 B4).
"""

import base64
import json
import re
import struct
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "out" / "junction_layer"
CUFEM = ROOT / "target" / "release" / "cufem"

MODEL = """[analysis]
type = "modal"
modes = 8
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3
density = 7800.0
[[bodies]]
name = "box"
material = "steel"
formulation = "assumed_shear"
SECTION
axis = { element = "B4", from = 0.0, to = 0.4, elements = 4 }
[[constraints]]
name = "root"
body = "box"
where = { y = 0.0 }
fix = ["x", "y", "z"]
"""
PROFILE = ('section = { shape = "box", element = "L9", width = 0.1, height = 0.05, web_thickness = 0.001, '
           'flange_thickness = 0.001, along_flange = 3, along_web = 2 }')


def quads(xl, zl):
    """The box's walls over the grid lines xl (inner x lines) and zl (inner z lines)."""
    xs, zs = [0.0] + xl + [0.1], [0.0] + zl + [0.05]
    index, points, cells = {}, [], []

    def node(i, j):
        if (i, j) not in index:
            index[(i, j)] = len(points)
            points.append([xs[i], zs[j]])
        return index[(i, j)]
    for i in range(len(xs) - 1):
        for j in range(len(zs) - 1):
            if i in (0, len(xs) - 2) or j in (0, len(zs) - 2):
                cells.append([node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)])
    return f'section = {{ shape = "quads", element = "L9", points = {points}, quads = {cells} }}'


def vtu_arrays(path):
    arrays = {}
    for m in re.finditer(r'<DataArray([^>]*)>([^<]*)</DataArray>', path.read_text()):
        attrs = m.group(1)
        if 'type="Float64"' not in attrs:
            continue
        name = re.search(r'Name="([^"]*)"', attrs)
        raw = base64.b64decode(m.group(2).strip())
        n = struct.unpack('<Q', raw[:8])[0]
        arrays[name.group(1) if name else "Points"] = struct.unpack(f'<{n // 8}d', raw[8:8 + n])
    return arrays


def next_to_junctions(path, per=36):
    """Share of mode 1's η² in the wall elements that touch a junction element (t × t at a corner)."""
    a = vtu_arrays(path)
    pts, err = a["Points"], a["error"]
    shares, boxes = [], []
    for e in range(len(err) // per):
        xs = [pts[3 * (e * per + i)] for i in range(per)]
        zs = [pts[3 * (e * per + i) + 2] for i in range(per)]
        boxes.append((min(xs), max(xs), min(zs), max(zs)))
        shares.append(err[e * per] ** 2)
    total = sum(shares)
    corner = lambda b: (b[1] - b[0]) < 1.5e-3 and (b[3] - b[2]) < 1.5e-3
    touch = lambda b, c: b[0] <= c[1] + 1e-9 and c[0] <= b[1] + 1e-9 and b[2] <= c[3] + 1e-9 and c[2] <= b[3] + 1e-9
    corners = [b for b in boxes if corner(b)]
    near = sum(s for b, s in zip(boxes, shares) if not corner(b) and any(touch(b, c) for c in corners))
    return near / total


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    cases = [
        ("profile 3 x 2", PROFILE),
        ("quads 3 x 2 (same lines)", quads([0.001, 0.033666667, 0.066333333, 0.099], [0.001, 0.025, 0.049])),
        ("graded, 2 mm off junctions", quads([0.001, 0.003, 0.0335, 0.0665, 0.097, 0.099],
                                             [0.001, 0.003, 0.025, 0.047, 0.049])),
        ("graded, 0.5 mm off junctions", quads([0.001, 0.0015, 0.0335, 0.0665, 0.0985, 0.099],
                                               [0.001, 0.0015, 0.025, 0.0485, 0.049])),
        ("profile 6 x 4 (doubled)", PROFILE.replace("along_flange = 3, along_web = 2", "along_flange = 6, along_web = 4")),
    ]
    print(f"{'mesh':<30} {'DOF':>6}  f1..f5 (Hz) | estimated error (%) | mode 1's eta^2 next to junctions")
    for k, (name, section) in enumerate(cases):
        model = OUT / f"case{k}.toml"
        model.write_text(MODEL.replace("SECTION", section))
        out = OUT / f"case{k}"
        subprocess.run([str(CUFEM), "run", str(model), "--out", str(out), "--quiet", "--force"], check=True, capture_output=True)
        s = json.loads((out / "summary.json").read_text())
        f = " ".join(f"{v:.2f}" for v in s["modal"]["frequencies_hz"][:5])
        e = " ".join(f"{100 * v:.2f}" for v in s["modal"]["frequency_errors"][:5])
        print(f"{name:<30} {s['dof']:>6}  {f} | {e} | {next_to_junctions(out / 'mode_1.vtu'):.3f}")


if __name__ == "__main__":
    main()
