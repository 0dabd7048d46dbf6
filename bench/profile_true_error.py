#!/usr/bin/env python3
"""True energy-norm errors of the thin-walled profiles of crates/cufem-cli/tests/adapt.rs
(`a_profile_s_loaded_wall_is_the_one_refined`) under a pressure on one wall (issue 49): the
uniform meshes, and each cycle of `cufem run --adapt` (its `adapted.toml` under growing DOF
budgets).

For a linear static problem loaded by a pressure p on a face, ||u - u_h||_E^2 = W - W_h with
W = p ∫ u_n dA the compliance (Galerkin orthogonality), so the true relative error against a fine
reference is sqrt((W_ref - W_h) / W_ref). ∫ u_n dA is integrated from probes on the loaded face:
3-point Gauss per interval of 16 across each half-flange (or the web between the junctions) and
over the junction, 4-point Gauss per interval of 32 along the axis. The reference is converged in
the section and along the axis: 32 x 32 L9 with a 0.375 mm element at each junction and 64 B4;
the script prints its own convergence (16 and 32 B4 of the same section, and 32 x 32 against
16 x 16), from which the reference's remaining error is a few hundredths of a percent of W —
errors below about 3 % are not resolved by it.

    python3 bench/profile_true_error.py      # about two minutes; writes out/profile_true_error/
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
section = {{ shape = "{shape}", element = "L9", origin = [0.0, -0.05], width = 0.05, height = 0.1, web_thickness = 0.003, flange_thickness = 0.003, along_flange = {flange}, along_web = {web}, through = 1{junction} }}
axis = {{ element = "B4", from = 0.0, to = 0.4, elements = {axis} }}
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
CASES = {
    "channel": ('{ x = 0.0, region = "web" }', 0, 1.0),
    "i_beam": ('{ z = 0.05, region = "top_flange" }', 2, -1.0),
}


def gauss(intervals, rule):
    return [((a + b) / 2 + (b - a) / 2 * g, w * (b - a) / 2) for a, b in intervals for g, w in rule]


def face(shape):
    """Probes (text) and weights of the loaded face's quadrature."""
    n = 16
    if shape == "channel":
        across = ([(-0.05, -0.047)] + [(-0.047 + 0.094 * i / n, -0.047 + 0.094 * (i + 1) / n) for i in range(n)]
                  + [(0.047, 0.05)])
        point = lambda t, y: (0.0, y, t)  # noqa: E731
    else:
        across = ([(0.0235 * i / n, 0.0235 * (i + 1) / n) for i in range(n)] + [(0.0235, 0.0265)]
                  + [(0.0265 + 0.0235 * i / n, 0.0265 + 0.0235 * (i + 1) / n) for i in range(n)])
        point = lambda t, y: (t, y, 0.05)  # noqa: E731
    ys = gauss([(0.4 * i / 32, 0.4 * (i + 1) / 32) for i in range(32)], G4)
    pts = [(point(t, y), wt * wy) for y, wy in ys for t, wt in gauss(across, G3)]
    text = "".join(f'[[probes]]\nname = "p{i}"\npoint = [{p[0]:.12g}, {p[1]:.12g}, {p[2]:.12g}]\n'
                   for i, (p, _) in enumerate(pts))
    return text, [w for _, w in pts]


def model(shape, flange, web, junction=None, axis=4):
    j = f", junction_element = {junction}" if junction else ""
    return MODEL.format(shape=shape, wall=CASES[shape][0], flange=flange, web=web, junction=j, axis=axis)


def run(name, text, extra=()):
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / f"{name}.toml").write_text(text)
    subprocess.run([str(CUFEM), "run", str(OUT / f"{name}.toml"), "--out", str(OUT / name), "--quiet", "--force",
                    *extra], check=True, capture_output=True)
    return OUT / name


def compliance(shape, name, text, probes):
    """p ∫ u_n dA over the loaded face, the DOF and the relative estimate."""
    s = json.loads((run(name, text + probes[0]) / "summary.json").read_text())
    _, component, sign = CASES[shape]
    w = sum(wi * q["u"][component] for wi, q in zip(probes[1], s["probes"]))
    return 1e5 * sign * w, s["dof"], s["error_estimate"]["relative_energy_norm"]


def adapted(shape, budget):
    """The mesh of `cufem run --adapt 0.01` from 2 x 2 L9 within `budget` DOF."""
    folder = run(f"{shape}_adapt_{budget}", model(shape, 2, 2), ["--adapt", "0.01", "--max-dof", str(budget)])
    return (folder / "adapted.toml").read_text()


def study(shape, budgets):
    probes = face(shape)
    refs = {}
    for f, a in [(16, 16), (16, 32), (32, 16), (32, 32), (32, 64)]:
        refs[(f, a)] = compliance(shape, f"{shape}_ref_{f}_{a}", model(shape, f, f, 0.000375, a), probes)[0]
    ref = refs[(32, 64)]
    print(f"{shape}, pressure on {CASES[shape][0]}; reference 32 x 32 L9, 0.375 mm junction elements, 64 B4:"
          f" W = {ref:.8e}")
    print(f"  its convergence: 32 -> 64 B4 {100 * (ref / refs[(32, 32)] - 1):+.3f} %,"
          f" 16 -> 32 B4 {100 * (refs[(16, 32)] / refs[(16, 16)] - 1):+.3f} % (16 x 16),"
          f" 16 x 16 -> 32 x 32 {100 * (refs[(32, 16)] / refs[(16, 16)] - 1):+.3f} % (16 B4)")
    meshes = [(f"uniform {n} x {n} L9, 4 B4", model(shape, n, n)) for n in (2, 4, 8, 16, 32)]
    meshes += [(f"--adapt within {b:,} DOF", adapted(shape, b)) for b in budgets]
    for i, (label, text) in enumerate(meshes):
        w, dof, est = compliance(shape, f"{shape}_{i}", text, probes)
        true = 100 * math.sqrt(max(ref - w, 0) / ref)
        print(f"  {label:<28} {dof:>6} DOF  estimate {100 * est:6.2f} %  true {true:6.2f} %")


def main():
    study("channel", [3000, 5000, 6400, 14000, 25000])
    study("i_beam", [4400, 8300, 25000])


if __name__ == "__main__":
    main()
