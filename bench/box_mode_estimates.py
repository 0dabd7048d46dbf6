#!/usr/bin/env python3
"""The laminated torsion box's mode estimates against their true errors (issue 49).

bench/box_laminated_modes.toml ([±45]s T300 walls 1 mm, 100 × 50 mm, 1 m cantilever, assumed shear,
3 × 2 L9 along the walls, 8 B4) and the same box with its walls graded to a 0.25 mm element at each
junction and the flanges doubled, against a reference with 24 × 16 L9 along the walls, 0.25 mm junction
elements and 16 B4. For each mode of each mesh: the frequency, the estimated relative frequency error
(summary.json `modal.frequency_errors`), the true one (against the reference's mode of the same order:
the eight modes keep their order on the three meshes) and their ratio, the effectivity. The
reference's own error: its frequencies lie within 0.6 % of CalculiX's C3D20R twin
(docs/validation.md, rows verify.box_modes.mode.<k>.ccx_hz).

    python3 bench/box_mode_estimates.py      # about two minutes; writes out/box_mode_estimates/
"""

import json
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "out" / "box_mode_estimates"
CUFEM = ROOT / "target" / "release" / "cufem"
BASE = (ROOT / "bench" / "box_laminated_modes.toml").read_text()
COUNTS = "along_flange = 3, along_web = 2"
AXIS = "to = 1.0, elements = 8 }"


def variant(flange, web, axis, junction):
    assert COUNTS in BASE and AXIS in BASE
    counts = f"along_flange = {flange}, along_web = {web}"
    if junction:
        counts += f", junction_element = {junction}"
    return BASE.replace(COUNTS, counts).replace(AXIS, f"to = 1.0, elements = {axis} }}")


def solve(name, text):
    OUT.mkdir(parents=True, exist_ok=True)
    model = OUT / f"{name}.toml"
    model.write_text(text)
    out = OUT / name
    subprocess.run([str(CUFEM), "run", str(model), "--out", str(out), "--quiet", "--force"], check=True,
                   capture_output=True)
    s = json.loads((out / "summary.json").read_text())
    return s["dof"], s["modal"]["frequencies_hz"], s["modal"]["frequency_errors"]


def main():
    _, reference, _ = solve("reference", variant(24, 16, 16, 0.00025))
    for name, text in [("base 3 x 2 L9, 8 B4", variant(3, 2, 8, None)),
                       ("graded, flanges doubled: 6 x 2 L9, 8 B4", variant(6, 2, 8, 0.00025))]:
        dof, f, e = solve(name.split()[0] + name.split()[1].strip(","), text)
        print(f"{name} ({dof} DOF) against 24 x 16 L9, 16 B4")
        print(f"{'mode':>4} {'f (Hz)':>10} {'estimated %':>12} {'true %':>8} {'effectivity':>12}")
        for k, (fh, est, fr) in enumerate(zip(f, e, reference)):
            true = fh / fr - 1.0
            print(f"{k + 1:>4} {fh:>10.3f} {100 * est:>12.3f} {100 * true:>8.3f} {est / true:>12.2f}")


if __name__ == "__main__":
    main()
