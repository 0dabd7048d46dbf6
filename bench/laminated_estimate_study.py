#!/usr/bin/env python3
"""Why the mode estimates of the laminated box's walls were 3-8x their true error (issue 49).

The laminated torsion box of bench/box_laminated_modes.toml ([+45/-45]s T300/5208 walls 1 mm, one L9
per ply, `formulation = "assumed_shear"`) shortened to 0.4 m with 4 B4, on the meshes `--adapt` goes
through (uniform 3 x 2 L9 along the walls; walls graded to a 0.25 mm element at each junction; graded
with the flanges doubled; uniform 6 x 4), against the same box with 24 x 16 L9, a 0.0625 mm element
at each junction and 8 B4 (140,400 DOF; 12 x 8 with the same grading lies 0.06-0.14 % above it).
Prints each mode's estimated relative frequency error (summary.json `modal.frequency_errors`), the
true one (f_h / f_ref - 1, modes matched by order: modes 5-6 of the uniform 3 x 2 mesh are a pair
1 % apart that MAC matching in tests/mode_error.rs leaves unmatched) and their ratio.

    python3 bench/laminated_estimate_study.py          # a few minutes; writes out/laminated_estimate/

bench/laminated_estimate_results.txt holds its output before and after the area-weighted section fit
of post::spr, and the per-component and per-location split of the estimate that found the cause.
"""

import json
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "out" / "laminated_estimate"
CUFEM = ROOT / "target" / "release" / "cufem"


def model(flange, web, axis, junction=None):
    text = (ROOT / "bench" / "box_laminated_modes.toml").read_text()
    j = f", junction_element = {junction}" if junction else ""
    text = text.replace("along_flange = 3, along_web = 2", f"along_flange = {flange}, along_web = {web}{j}")
    return text.replace("to = 1.0, elements = 8 }", f"to = 0.4, elements = {axis} }}")


def run(name, text):
    path = OUT / f"{name}.toml"
    path.write_text(text)
    out = OUT / name
    subprocess.run([str(CUFEM), "run", str(path), "--out", str(out), "--quiet", "--force"], check=True,
                   capture_output=True)
    return json.loads((out / "summary.json").read_text())


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    ref = run("reference", model(24, 16, 8, 0.0000625))
    fr = ref["modal"]["frequencies_hz"]
    print(f"reference {ref['dof']} DOF: " + " ".join(f"{f:.2f}" for f in fr))
    cases = [("uniform_3x2", model(3, 2, 4)), ("graded_3x2", model(3, 2, 4, 0.00025)),
             ("graded_6x2", model(6, 2, 4, 0.00025)), ("uniform_6x4", model(6, 4, 4))]
    for name, text in cases:
        s = run(name, text)
        f, e = s["modal"]["frequencies_hz"], s["modal"]["frequency_errors"]
        rows = [(100 * est, 100 * (fh / fref - 1)) for fh, est, fref in zip(f, e, fr)]
        eff = [a / b for a, b in rows]
        print(f"{name:<12} {s['dof']:>6} DOF  estimate % " + " ".join(f"{a:.2f}" for a, _ in rows))
        print(f"{'':<24} true %     " + " ".join(f"{b:.2f}" for _, b in rows))
        print(f"{'':<24} effectivity {min(eff):.2f}-{max(eff):.2f}")


if __name__ == "__main__":
    main()
