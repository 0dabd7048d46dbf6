#!/usr/bin/env python3
"""examples/channel_roller.toml (a channel twisted by a roller on one flange, issue 49) under
refinement of its section (wall counts, junction grading) and of its axis (every segment's
elements multiplied), and the mesh
`cufem run --adapt 0.02 --max-dof 60000` reaches: the roller's force (full structure, the roller's
displacement prescribed), the web's rotation measure u_x(top) - u_x(bottom) at y = 100, 175, 250
and 325 mm, the flange tip's u_z at mid-span, and the relative error estimate.

    python3 bench/channel_roller_refinement.py   # about three minutes; writes out/channel_roller_refinement/
    python3 bench/channel_roller_refinement.py --verify   # and the CalculiX twin of the axis x4 mesh (+7 min)
"""

import json
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "out" / "channel_roller_refinement"
CUFEM = ROOT / "target" / "release" / "cufem"
BASE = (ROOT / "examples" / "channel_roller.toml").read_text()


def variant(flange, web, junction=None, axis=1):
    counts = f"along_flange = {flange}, along_web = {web}, through = 1"
    if junction:
        counts += f", junction_element = {junction}"
    text = BASE.replace("along_flange = 2, along_web = 6, through = 1", counts)
    if axis != 1:
        text = re.sub(r"elements = (\d+)", lambda m: f"elements = {int(m.group(1)) * axis}", text)
    return text


def run(name, text, extra=()):
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / f"{name}.toml").write_text(text)
    subprocess.run([str(CUFEM), "run", str(OUT / f"{name}.toml"), "--out", str(OUT / name), "--quiet", "--force",
                    "--threads", "1", *extra], check=True, capture_output=True)
    return OUT / name


def row(label, folder):
    s = json.loads((folder / "summary.json").read_text())
    u = {p["name"]: p["u"] for p in s["probes"]}
    force = -next(c for c in s["contact"] if c["name"] == "load")["full_structure_force"][2]
    twist = " ".join(f"{1e6 * (u[f'wt_{y}'][0] - u[f'wb_{y}'][0]):8.2f}" for y in (100, 175, 250, 325))
    est = 100 * s["error_estimate"]["relative_energy_norm"]
    print(f"  {label:<44} {s['dof']:>7} DOF  estimate {est:5.2f} %  force {force:8.2f} N"
          f"  u_x(top) - u_x(bottom) [µm] {twist}  tip u_z {1e6 * u['tt_325'][2]:8.2f} µm", flush=True)


def main():
    print("examples/channel_roller.toml (CalculiX twin, verify --refine 1: roller force 1,363.9 N)")
    cases = [("2, 6 (the example)", variant(2, 6)), ("2, 6, junction 2 mm", variant(2, 6, 0.002)),
             ("4, 12", variant(4, 12)), ("4, 12, junction 1 mm", variant(4, 12, 0.001)),
             ("8, 24, junction 0.5 mm", variant(8, 24, 0.0005)),
             ("8, 6, junction 0.5 mm (the adapted section)", variant(8, 6, 0.0005)),
             ("2, 6, axis x2", variant(2, 6, None, 2)), ("2, 6, axis x4", variant(2, 6, None, 4)),
             ("2, 6, axis x8", variant(2, 6, None, 8)),
             ("4, 12, junction 1 mm, axis x2", variant(4, 12, 0.001, 2)),
             ("4, 12, junction 1 mm, axis x4", variant(4, 12, 0.001, 4)),
             ("8, 24, junction 0.5 mm, axis x2", variant(8, 24, 0.0005, 2))]
    for i, (label, text) in enumerate(cases):
        row(label, run(f"mesh{i}", text))
    adapted = run("adapt", BASE, ["--adapt", "0.02", "--max-dof", "60000"])
    row("--adapt 0.02 within 60,000 DOF", adapted)
    if "--verify" in sys.argv:
        twin()


def twin():
    """`cufem verify --refine 1` of the example with its axis x4: the web's rotation measure of
    both models (verify/table.txt's u_x rows) and the roller force."""
    (OUT / "axis_x4.toml").write_text(variant(2, 6, None, 4))
    folder = OUT / "verify_axis_x4"
    subprocess.run([str(CUFEM), "verify", str(OUT / "axis_x4.toml"), "--refine", "1", "--out", str(folder),
                    "--force", "--quiet"], check=True, capture_output=True)
    table = (folder / "verify" / "table.txt").read_text()
    u = {m.group(1): (float(m.group(2)), float(m.group(3)))
         for m in re.finditer(r"^(\w+)\s+u_x \[mm\]\s+(\S+)\s+(\S+)", table, re.M)}
    print("CalculiX twin of the example with its axis x4 (cufem verify --refine 1):")
    print("  " + next(line for line in table.splitlines() if line.startswith("DOF")))
    for y in (100, 175, 250, 325):
        c, d = (1e3 * (u[f"wt_{y}"][k] - u[f"wb_{y}"][k]) for k in (0, 1))
        print(f"  y = {y} mm: u_x(top) - u_x(bottom) cufem {c:8.2f} µm, 3D {d:8.2f} µm ({100 * (c / d - 1):+.2f} %)")
    print("  " + next(line for line in table.splitlines() if line.startswith("load")))


if __name__ == "__main__":
    main()
