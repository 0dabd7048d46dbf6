#!/usr/bin/env python3
"""Issue 50: what sets the Newton iterations of a time step under an impact.

The tube drop weight (examples/tube_drop_weight.toml) over its first 1.2 ms
(60 steps of 20 µs: the weight lands at step 5 and presses the tube while
plasticity spreads under it), run as shipped and with one thing changed at a
time, one thread each:

    python3 bench/drop/step_iterations.py     # from the repository root; about 4 min

* `kept`: the tube's contact nodes keep their mass (`contact_mass = "kept"`);
* `no_reuse`: every correction factorizes (`solver.reuse_factorization = false`);
* `displaced`: the weight replaced by the same roller moved at 1 m/s
  (`displacement`, no impactor unknown, no bordered system);
* `static`: that roller's motion in 60 static increments of the same size
  (no inertia: plasticity spreading under a monotonic load alone);
* `elastic`: the shipped run without plasticity (the contact and the
  vibration alone);
* `damped`: the shipped run with Bossak's `α = −0.3`, which damps the
  high frequencies the weight excites.

Prints, per run, the Newton iterations of steps 6–60 (the impact) and their
mean, and the plastic points at step 60. If the iterations came from an
inconsistent dynamic tangent (the impactor's border, the contact nodes' mass
redistribution, the reused factor), the first three variants would take
fewer; the last three split them between plasticity, contact and the
vibration.
"""
import os, re, subprocess, sys, tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.path.join(ROOT, "target", "release", "cufem")


def variants(text):
    base = text.replace("duration = 6e-3", "duration = 1.2e-3").replace("increments = 300", "increments = 60")
    assert base != text, "the example's step changed: update this script"
    kept = base.replace('type = "transient"', 'type = "transient"\ncontact_mass = "kept"', 1)
    no_reuse = base.replace("max_increments = 5000", "max_increments = 5000\nreuse_factorization = false", 1)
    displaced = base.replace("mass = 2.0\nvelocity = [0.0, 0.0, -1.0]", "displacement = [0.0, 0.0, -1.2e-3]", 1)
    static = displaced.replace('type = "transient"', 'type = "static"', 1).replace("duration = 1.2e-3\n", "", 1)
    start, end = base.index("[materials.plasticity]"), base.index("[[bodies]]")
    elastic = base[:start] + base[end:]
    damped = base.replace('type = "transient"', 'type = "transient"\nnewmark = { alpha = -0.3 }', 1)
    runs = [("kept", kept), ("no_reuse", no_reuse), ("displaced", displaced), ("static", static)]
    for name, t in runs + [("elastic", elastic), ("damped", damped)]:
        assert t != base and t.count('type = "') >= 1, f"{name}: the example changed: update this script"
    assert "duration" not in static, "static: the step's duration is left"
    return [("shipped", base)] + runs + [("elastic", elastic), ("damped", damped)]


def run(text, folder):
    path = os.path.join(folder, "model.toml")
    with open(path, "w") as f:
        f.write(text)
    done = subprocess.run([BIN, "run", path, "--threads", "1", "--out", os.path.join(folder, "out"), "--force"],
                          capture_output=True, text=True, check=True)
    out = done.stdout + done.stderr  # the progress lines go to stderr
    rows = re.findall(r"^increment\s+(\d+)\s.*?(\d+) iterations.*?plastic points (\d+)", out, re.M)
    return [(int(k), int(n), int(p)) for k, n, p in rows]


def main():
    text = open(os.path.join(ROOT, "examples", "tube_drop_weight.toml")).read()
    print("run        iterations, steps 6-60 (mean)   plastic points at the end")
    for name, t in variants(text):
        with tempfile.TemporaryDirectory() as d:
            rows = run(t, d)
        impact = [n for k, n, _ in rows if k >= 6]
        print(f"{name:10} {sum(impact):5d} ({sum(impact) / max(len(impact), 1):.2f} a step)      {rows[-1][2]}")


if __name__ == "__main__":
    sys.exit(main())
