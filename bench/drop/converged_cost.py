#!/usr/bin/env python3
"""Issue 48: where the drop weight with ply damage spends its time.

Runs examples/laminate_drop_weight_damage.toml as shipped (its graded time
step, 1.25 µs while the laminate damages and 5 µs after, is the converged
one: docs/composites.md) with the release binary (CUFEM_BIN to override),
on THREADS threads (default 1, the machine's measure), and prints the wall
time, the Newton corrections and cutbacks, the phases of summary.json
`timings` (assembly, factorization, solves, with their counts and the time
of one), and the time steps and mean corrections per step in windows of
0.5 ms (history.csv `iterations`): the issue asks for the run in under a
minute.

    python3 bench/drop/converged_cost.py [THREADS]   # from the repository root
"""
import csv, json, os, subprocess, sys, tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.environ.get("CUFEM_BIN", os.path.join(ROOT, "target", "release", "cufem"))


def main():
    threads = sys.argv[1] if len(sys.argv) > 1 else "1"
    text = open(os.path.join(ROOT, "examples", "laminate_drop_weight_damage.toml")).read()
    with tempfile.TemporaryDirectory() as folder:
        model = os.path.join(folder, "model.toml")
        open(model, "w").write(text)
        out = os.path.join(folder, "out")
        subprocess.run([BIN, "run", model, "--out", out, "--quiet", "--threads", threads], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        s = json.load(open(os.path.join(out, "summary.json")))
        with open(os.path.join(out, "history.csv")) as f:
            rows = [(float(r["time"]), int(r["iterations"])) for r in csv.DictReader(f)]
    t = s["timings"]
    print(f"examples/laminate_drop_weight_damage.toml, {threads} thread(s): {s['equations']} equations")
    print(f"wall {s['wall_time_s']:.1f} s, {s['increments']} increments, {s['newton_iterations']} corrections, "
          f"{s['cutbacks']} cutbacks")
    print(f"assembly      {t['assembly_s']:7.1f} s  {t['evaluations']:6d} evaluations    "
          f"{1e3 * t['assembly_s'] / max(t['evaluations'], 1):6.2f} ms each")
    print(f"factorization {t['factorization_s']:7.1f} s  {t['factorizations']:6d} factorizations "
          f"{1e3 * t['factorization_s'] / max(t['factorizations'], 1):6.2f} ms each "
          f"({t['reused_factorizations']} reused, {t['fallbacks']} fallbacks)")
    print(f"solves        {t['solve_s']:7.1f} s  {t['krylov_iterations']:6d} PCG iterations")
    print("window_ms  steps  corrections_per_step")
    window = 0.5e-3
    for k in range(int(max(r[0] for r in rows) / window) + 1):
        w = [n for (time, n) in rows if k * window <= time < (k + 1) * window]
        if w:
            print(f"{1e3 * k * window:4.1f}-{1e3 * (k + 1) * window:3.1f} {len(w):6d} {sum(w) / len(w):10.2f}")


if __name__ == "__main__":
    main()
