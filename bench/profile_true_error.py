#!/usr/bin/env python3
"""True energy-norm errors of the thin-walled profiles of crates/cufem-cli/tests/adapt.rs
(`a_profile_s_loaded_wall_is_the_one_refined`) under a pressure on one wall (issue 49).

For a linear static problem loaded by a pressure p on a face, ||u - u_h||_E^2 = W - W_h with
W = p ∫ u_n dA the compliance (Galerkin orthogonality), so the true relative error against a fine
reference is sqrt((W_ref - W_h) / W_ref). ∫ u_n dA is integrated from probes on the loaded face:
3-point Gauss per interval of the finest mesh's lines across the wall, 4-point Gauss per B4 element
along the axis. Channel (web pressed): 2 x 2, 4 x 2, 2 x 4 L9 against 32 x 32; I-beam (top flange
pressed): the adaptive run's 16 x 2, the old path's 16 x 32 and the uniform 32 x 32 against 64 x 64.

    python3 bench/profile_true_error.py      # about a minute; writes out/profile_true_error/
"""

import json
import math
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "out" / "profile_true_error"
CUFEM = ROOT / "target" / "release" / "cufem"
MODEL = """[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3
[[bodies]]
name = "beam"
material = "steel"
section = {{ shape = "{shape}", element = "L9", origin = [0.0, -0.05], width = 0.05, height = 0.1, web_thickness = 0.003, flange_thickness = 0.003, along_flange = {flange}, along_web = {web}, through = 1 }}
axis = {{ element = "B4", from = 0.0, to = 0.4, elements = 4 }}
[[constraints]]
name = "ends"
body = "beam"
where = {{ y = [0.0, 0.0] }}
fix = ["x", "y", "z"]
[[constraints]]
name = "far"
body = "beam"
where = {{ y = 0.4 }}
fix = ["x", "y", "z"]
[[loads]]
name = "pressure"
body = "beam"
where = {wall}
pressure = 1e5
"""
G3 = [(-math.sqrt(0.6), 5 / 9), (0.0, 8 / 9), (math.sqrt(0.6), 5 / 9)]
_A, _B = math.sqrt(3 / 7 - 2 / 7 * math.sqrt(6 / 5)), math.sqrt(3 / 7 + 2 / 7 * math.sqrt(6 / 5))
_WA, _WB = (18 + math.sqrt(30)) / 36, (18 - math.sqrt(30)) / 36
G4 = [(-_B, _WB), (-_A, _WA), (_A, _WA), (_B, _WB)]


def gauss(intervals, rule):
    return [((a + b) / 2 + (b - a) / 2 * g, w * (b - a) / 2) for a, b in intervals for g, w in rule]


def face(across, point, component, sign):
    ys = gauss([(0.1 * i, 0.1 * (i + 1)) for i in range(4)], G4)
    pts = [(point(t, y), wt * wy) for y, wy in ys for t, wt in gauss(across, G3)]
    probes = "".join(f'[[probes]]\nname = "p{i}"\npoint = [{p[0]:.12g}, {p[1]:.12g}, {p[2]:.12g}]\n'
                     for i, (p, _) in enumerate(pts))
    return probes, [w for _, w in pts], component, sign


def compliance(name, text, probes):
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / f"{name}.toml").write_text(text + probes[0])
    subprocess.run([str(CUFEM), "run", str(OUT / f"{name}.toml"), "--out", str(OUT / name), "--quiet", "--force"],
                   check=True, capture_output=True)
    s = json.loads((OUT / name / "summary.json").read_text())
    _, w, c, sign = probes
    return 1e5 * sign * sum(wi * q["u"][c] for wi, q in zip(w, s["probes"])), s["dof"]


def study(shape, wall, probes, meshes, reference):
    ref, _ = compliance(f"{shape}_{reference[0]}x{reference[1]}",
                        MODEL.format(shape=shape, wall=wall, flange=reference[0], web=reference[1]), probes)
    print(f"{shape}, pressure on {wall}, against {reference[0]} x {reference[1]} L9")
    for f, w in meshes:
        c, dof = compliance(f"{shape}_{f}x{w}", MODEL.format(shape=shape, wall=wall, flange=f, web=w), probes)
        print(f"  {f:>2} x {w:<2} L9 {dof:>6} DOF  true relative error {100 * math.sqrt(max(ref - c, 0) / ref):6.2f} %")


def main():
    n = 32  # intervals of the finest mesh's lines in each part of the web / half-flange
    web = [(-0.05, -0.047)] + [(-0.047 + 0.094 * i / n, -0.047 + 0.094 * (i + 1) / n) for i in range(n)] + [(0.047, 0.05)]
    study("channel", '{ x = 0.0, region = "web" }', face(web, lambda z, y: (0.0, y, z), 0, 1.0),
          [(2, 2), (4, 2), (2, 4)], (32, 32))
    flange = ([(0.0235 * i / n, 0.0235 * (i + 1) / n) for i in range(n)] + [(0.0235, 0.0265)]
              + [(0.0265 + 0.0235 * i / n, 0.0265 + 0.0235 * (i + 1) / n) for i in range(n)])
    study("i_beam", '{ z = 0.05, region = "top_flange" }', face(flange, lambda x, y: (x, y, 0.05), 2, -1.0),
          [(2, 2), (16, 2), (16, 32), (32, 32)], (64, 64))


if __name__ == "__main__":
    main()
