#!/usr/bin/env python3
"""How the cost grows with the model (docs/performance.md, "Scaling"): the thin-walled tube
refined along the axis (11, 22, 44, 88, 176 B4; 28 L9 ring) and around the
ring (12, 28, 60, 124 L9; 22 B4), elastic (bench/tube_28L9_elastic.toml, one
linear solve) and plastic (examples/bending_tube_28L9.toml, its first 5 of 15
increments: the plastic zone under the roller is formed, 2,300 plastic points
on the 20 L9 mesh). Per Newton iteration: assembly (per residual evaluation),
numeric factorization (per factorization), solves (triangular solves and PCG
per iteration); nnz(L) and the peak resident memory; then the least-squares
exponent of each against DOF and the DOF at which the peak memory reaches
24 GiB by extrapolation.

Usage: bench/scaling.py [--quick] [--reuse-runs]
  --quick: skips the two largest models; --reuse-runs: reads the runs left in
  /tmp/cufem_scaling by an earlier call instead of running them again.
A linear solve is a factorization and solve, or a PCG solve with an earlier
factor (solver::reuse); per-evaluation figures include failed attempts (the
88 and 176 B4 plastic models cut their first increment back twice: the
linear solve fails while the roller contacts engage, with or without reuse).
Writes bench/scaling.csv and docs/scaling.png (the plot needs matplotlib;
without it only the CSV and the table are written)."""
import csv, json, math, os, re, subprocess, sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
binary = os.path.join(root, "target/release/cufem")
quick = "--quick" in sys.argv
reuse_runs = "--reuse-runs" in sys.argv
subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=root, check=True)
elastic = open(os.path.join(root, "bench/tube_28L9_elastic.toml")).read()
plastic = open(os.path.join(root, "examples/bending_tube_28L9.toml")).read()
SEGMENTS = {11: (1, 4, 5, 1), 22: (2, 9, 9, 2), 44: (4, 18, 18, 4), 88: (8, 36, 36, 8), 176: (16, 72, 72, 16)}


def variant(kind, axis, ring):
    if kind == "elastic":
        text = elastic.replace("elements = 22 }", f"elements = {axis} }}")
    else:
        a, b, c, d = SEGMENTS[axis]
        text = (plastic.replace("to = 0.025, elements = 2 }", f"to = 0.025, elements = {a} }}")
                .replace("to = 0.125, elements = 9 }", f"to = 0.125, elements = {b} }}")
                .replace("to = 0.225, elements = 9 }", f"to = 0.225, elements = {c} }}")
                .replace("to = 0.25, elements = 2 }", f"to = 0.25, elements = {d} }}")
                .replace("increments = 15", "increments = 15\nmax_increments = 5"))
    return text.replace("around = 28", f"around = {ring}")


def run(kind, axis, ring):
    out = f"/tmp/cufem_scaling/{kind}_{axis}_{ring}"
    os.makedirs(out, exist_ok=True)
    model = os.path.join(out, "model.toml")
    text = variant(kind, axis, ring)
    if not (reuse_runs and os.path.exists(out + "/out/summary.json") and open(model).read() == text):
        open(model, "w").write(text)
        # the plastic runs stop at max_increments on purpose (exit code != 0)
        subprocess.run([binary, "run", model, "--out", out + "/out", "--force", "--threads", "1"],
                       capture_output=True, text=True)
    # nnz(L) from one setup and factorization (cufem bench)
    b = subprocess.run([binary, "bench", model, "--repeat", "1", "--threads", "1"], capture_output=True, text=True)
    nnz = int(re.search(r"nnz\(L\) (\d+)", b.stdout).group(1))
    s = json.load(open(out + "/out/summary.json"))
    t = s["timings"]
    evals = max(t["evaluations"], 1)
    solves = max(t["factorizations"] + t["reused_factorizations"], 1)
    return {
        "kind": kind, "axis_B4": axis, "ring_L9": ring, "dof": s["dof"], "nnz_L": nnz,
        "iterations": s["newton_iterations"], "evaluations": t["evaluations"],
        "factorizations": t["factorizations"], "reused": t["reused_factorizations"],
        "krylov_iterations": t["krylov_iterations"],
        "assembly_ms": 1e3 * (t["assembly_s"] + t["contact_s"]) / evals,
        "factorization_ms": 1e3 * t["factorization_s"] / max(t["factorizations"], 1),
        "solve_ms": 1e3 * t["solve_s"] / solves,
        "wall_per_evaluation_ms": 1e3 * (s["wall_time_s"] - t["setup_s"]) / evals,
        "peak_MiB": s["memory"]["peak_bytes"] / 2**20,
    }


def fit(rows, key):
    """Least-squares slope and intercept of log(key) against log(DOF)."""
    xs = [math.log(r["dof"]) for r in rows]
    ys = [math.log(r[key]) for r in rows]
    n, mx, my = len(xs), sum(xs) / len(xs), sum(ys) / len(ys)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return slope, my - slope * mx


axes = [11, 22, 44, 88] + ([] if quick else [176])
rings = [12, 28, 60] + ([] if quick else [124])
families = []
for kind in ("elastic", "plastic"):
    families.append((kind, "axis", [run(kind, a, 28) for a in axes]))
    families.append((kind, "ring", [run(kind, 22, r) for r in rings]))
keys = ["assembly_ms", "factorization_ms", "solve_ms", "nnz_L", "peak_MiB"]
with open(os.path.join(root, "bench/scaling.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=["family"] + list(families[0][2][0].keys()))
    w.writeheader()
    for kind, fam, rows in families:
        for r in rows:
            w.writerow({"family": fam, **r})
print("per residual evaluation (assembly, wall), per factorization, per linear solve; ms")
print(f"{'family':<14} {'DOF':>8} {'nnz(L)':>11} {'its':>4} {'evals':>5} {'facts':>5} {'reused':>6} {'assembly':>9} "
      f"{'factor':>9} {'solve':>9} {'wall/ev':>9} {'peak MiB':>9}")
for kind, fam, rows in families:
    for r in rows:
        print(f"{kind + ' ' + fam:<14} {r['dof']:>8} {r['nnz_L']:>11} {r['iterations']:>4} {r['evaluations']:>5} "
              f"{r['factorizations']:>5} {r['reused']:>6} {r['assembly_ms']:>9.1f} {r['factorization_ms']:>9.1f} "
              f"{r['solve_ms']:>9.1f} {r['wall_per_evaluation_ms']:>9.1f} {r['peak_MiB']:>9.1f}")
print("\nexponents against DOF (least squares on log-log):")
for kind, fam, rows in families:
    parts = [f"{k} {fit(rows, k)[0]:.2f}" for k in keys]
    slope, icpt = fit(rows, "peak_MiB")
    limit = math.exp((math.log(24 * 1024) - icpt) / slope)
    print(f"  {kind} {fam}: " + ", ".join(parts) + f"; 24 GiB reached at ~{limit:,.0f} DOF")
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit("matplotlib not installed: CSV and table written, no plot")
fig, axs = plt.subplots(1, 2, figsize=(11, 4.5))
for ax, fam in zip(axs, ("axis", "ring")):
    for kind, f, rows in families:
        if f != fam:
            continue
        style = "-" if kind == "plastic" else "--"
        dof = [r["dof"] for r in rows]
        for key, colour in zip(["assembly_ms", "factorization_ms", "solve_ms", "peak_MiB"], "C0 C1 C2 C3".split()):
            ax.loglog(dof, [r[key] for r in rows], style, marker="o", color=colour,
                      label=f"{kind} {key.replace('_', ' ')} (slope {fit(rows, key)[0]:.2f})")
    ax.set_xlabel("DOF")
    ax.set_ylabel("ms (assembly per evaluation, factorization, solve) / MiB")
    ax.set_title({"axis": "axis refinement (28 L9 ring)", "ring": "ring refinement (22 B4)"}[fam])
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6)
fig.tight_layout()
fig.savefig(os.path.join(root, "docs/scaling.png"), dpi=120)
print("wrote bench/scaling.csv and docs/scaling.png")
