#!/usr/bin/env python3
"""How the cost of a long elastoplastic member grows to a million unknowns
(docs/performance.md, "At scale"): bench/ibeam_1M.toml (a 5 m I-beam, 16 L9,
three rollers, elastoplastic) with its axis mesh scaled by f = 1/50 … 1
(every segment's element count times f, at least 1), run one after the
other through `cufem run --threads T`; per run the DOF, wall time, the
phases (setup, assembly, factorization, solves), increments, Newton
iterations, factorizations, nnz(L), the estimated and the measured peak
memory; then the least-squares exponent of each against DOF.

Usage: bench/long_member.py [--threads T] [--only F,F,...] [--reuse-runs]
  --only: the fractions to run (default 0.02,0.1,0.2,0.5,1);
  --reuse-runs: reads the runs left in /tmp/cufem_long by an earlier call.
Writes bench/long_member.csv and prints the table."""
import csv, json, math, os, re, subprocess, sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
binary = os.path.join(root, "target/release/cufem")
args = sys.argv[1:]
threads = args[args.index("--threads") + 1] if "--threads" in args else "2"
fractions = [float(f) for f in (args[args.index("--only") + 1].split(",") if "--only" in args else
                                  ["0.02", "0.1", "0.2", "0.5", "1"])]
reuse = "--reuse-runs" in args
work = "/tmp/cufem_long"
os.makedirs(work, exist_ok=True)
subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=root, check=True)
text = open(os.path.join(root, "bench/ibeam_1M.toml")).read()


def variant(f):
    """The model with every axis segment's element count times f."""
    def scaled(m):
        return f"elements = {max(1, round(int(m.group(1)) * f))} }}"
    axis = text[text.index("axis = {"):text.index("] }", text.index("axis = {"))]
    return text.replace(axis, re.sub(r"elements = (\d+) }", scaled, axis))


rows = []
for f in fractions:
    name = f"f{f:g}"
    out = os.path.join(work, name)
    if not reuse:
        path = os.path.join(work, f"{name}.toml")
        open(path, "w").write(variant(f))
        subprocess.run([binary, "run", path, "--out", out, "--threads", threads, "--quiet"], check=True)
    s = json.load(open(os.path.join(out, "summary.json")))
    t = s["timings"]
    rows.append({
        "fraction": f,
        "dof": s["dof"],
        "wall_s": s["wall_time_s"],
        "setup_s": t["setup_s"],
        "assembly_s": t["assembly_s"],
        "factorization_s": t["factorization_s"],
        "solve_s": t["solve_s"],
        "increments": s["increments"],
        "iterations": s["newton_iterations"],
        "cutbacks": s["cutbacks"],
        "factorizations": t["factorizations"],
        "evaluations": t["evaluations"],
        "estimate_MiB": s["memory"]["estimated_bytes"] / 2**20,
        "peak_MiB": s["memory"]["peak_bytes"] / 2**20,
    })

with open(os.path.join(root, "bench/long_member.csv"), "w", newline="") as fh:
    w = csv.DictWriter(fh, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)

print("| DOF | wall s | setup / assembly / factorization / solves s | increments / iterations / cutbacks | factorizations | evaluations | estimate / peak MiB |")
print("|---:|---:|---|---|---:|---:|---|")
for r in rows:
    print(f"| {r['dof']:,} | {r['wall_s']:.1f} | {r['setup_s']:.1f} / {r['assembly_s']:.1f} / {r['factorization_s']:.1f} / "
          f"{r['solve_s']:.1f} | {r['increments']} / {r['iterations']} / {r['cutbacks']} | {r['factorizations']} | "
          f"{r['evaluations']} | {r['estimate_MiB']:.0f} / {r['peak_MiB']:.0f} ({r['estimate_MiB'] / r['peak_MiB']:.2f}) |")


def exponent(key, per=None):
    pts = [(math.log(r["dof"]), math.log(r[key] / (r[per] if per else 1))) for r in rows if r[key] > 0]
    if len(pts) < 2:
        return float("nan")
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)


print()
print("exponents against DOF (least squares on log-log):")
for key, per in [("wall_s", None), ("assembly_s", "evaluations"), ("factorization_s", "factorizations"),
                 ("solve_s", "iterations"), ("peak_MiB", None), ("estimate_MiB", None)]:
    print(f"  {key}{' per ' + per if per else ''}: {exponent(key, per):.2f}")
