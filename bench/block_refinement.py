#!/usr/bin/env python3
"""The "Refinement of the block" table of docs/cross-check.md: the block example (B-bar,
projected fields) on refined section and axis meshes, against the CalculiX
solution of tests/data/block_calculix_top.csv along the top line,
x in [0.21, 0.29] m. Usage: bench/block_refinement.py [ROWS]  (ROWS: how many
meshes of the list, default all; the finest take 2-3 min each)."""
import csv, json, os, subprocess, sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
meshes = [(6, 6, 1), (9, 9, 2), (12, 12, 2), (12, 12, 3), (12, 12, 4), (18, 18, 3)]  # x elements per segment, z, B4
rows = int(sys.argv[1]) if len(sys.argv) > 1 else len(meshes)
base = open(os.path.join(root, "examples/block_indentation.toml")).read()
ref = [[float(v) for v in l.split(",")] for l in open(os.path.join(root, "tests/data/block_calculix_top.csv"))
       if not l.startswith("#") and not l[0].isalpha()]
peak = [max(abs(r[k]) for r in ref) for k in (0, 1, 2)]
binary = os.path.join(root, "target/release/cufem")
subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=root, check=True)
previous = None
print("mesh, DOF, time s, force vs 3D %, centre s_zz MPa, centre peeq, s_zz vs 3D %, peeq vs 3D %, change s_zz/peeq %, largest reversal %")
for nx, nz, nb in meshes[:rows]:
    text = (base.replace("elements = 6, ratio", f"elements = {nx}, ratio")
                .replace("{ from = 0.2, to = 0.3, elements = 6 }", f"{{ from = 0.2, to = 0.3, elements = {nx} }}")
                .replace("to = 0.3, elements = 6, ratio = 0.3 }", f"to = 0.3, elements = {nz}, ratio = 0.3 }}")
                .replace("to = 0.1, elements = 1 }", f"to = 0.1, elements = {nb} }}"))
    out = f"/tmp/block_refinement_{nx}_{nz}_{nb}"
    os.makedirs(out, exist_ok=True)
    model = os.path.join(out, "model.toml")
    open(model, "w").write(text)
    subprocess.run([binary, "run", model, "--out", out + "/out", "--quiet", "--force"], check=True, stdout=subprocess.DEVNULL)
    s = json.load(open(out + "/out/summary.json"))
    line = [[float(r["x"]), float(r["s_zz"]), float(r["peeq"])] for r in csv.DictReader(open(out + "/out/line_top.csv"))]
    inside = [i for i, r in enumerate(ref) if 0.21 - 1e-9 <= r[0] <= 0.29 + 1e-9]
    diff = [max(abs(line[i][k] - ref[i][k]) for i in inside) / peak[k] for k in (1, 2)]
    under = [p for p in line if 0.21 - 1e-9 <= p[0] <= 0.25 + 1e-9]
    reversal = max([0.0] + [a[1] - b[1] for a, b in zip(under, under[1:])]) / peak[1]
    change = "" if previous is None else "%.1f / %.1f" % tuple(
        100 * max(abs(line[i][k] - previous[i][k]) for i in inside) / peak[k] for k in (1, 2))
    force = s["contact"][0]["force"][2]
    print(f"{3 * nx} x {nz}, {nb} B4, {s['dof']}, {s['wall_time_s']:.1f}, {100 * (force / -1.4102e6 - 1):+.2f}, "
          f"{line[100][1] / 1e6:.1f}, {line[100][2]:.4f}, {100 * diff[0]:.1f}, {100 * diff[1]:.1f}, {change}, {100 * reversal:.1f}")
    previous = line
