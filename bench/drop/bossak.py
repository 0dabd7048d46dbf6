#!/usr/bin/env python3
"""Issue 48/50: examples/laminate_drop_weight_damage.toml with Bossak's α.

Runs the example as shipped (the trapezoidal rule) and with
`analysis.newmark = { alpha = A }` for each A given (default -0.02 -0.05),
one after the other with the release binary (CUFEM_BIN to override), two
threads, and prints per run: Newton corrections, factorizations, cutbacks,
wall time, the energy balance (the scheme's dissipation) as a share of the
striker's kinetic energy, the energy the striker keeps and the
delamination's dissipation:

    python3 bench/drop/bossak.py [A ...]      # from the repository root
"""
import json, os, subprocess, sys, tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.environ.get("CUFEM_BIN", os.path.join(ROOT, "target", "release", "cufem"))
EXAMPLE = os.path.join(ROOT, "examples", "laminate_drop_weight_damage.toml")
IMPACT = 0.5 * 0.1 * 4.0 ** 2  # the striker's ½ m v² (J): 0.1 kg at 4 m/s


def run(alpha, folder):
    text = open(EXAMPLE).read()
    anchor = 'ply_damage_forces = "implicit"\n'
    assert anchor in text and "0.1" in text
    if alpha is not None:
        text = text.replace(anchor, anchor + f"newmark = {{ alpha = {alpha} }}\n")
    model = os.path.join(folder, "model.toml")
    open(model, "w").write(text)
    out = os.path.join(folder, "out")
    subprocess.run([BIN, "run", model, "--out", out, "--quiet", "--threads", "2"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    s = json.load(open(os.path.join(out, "summary.json")))
    e = s["energy"]
    return (s["newton_iterations"], s["timings"]["factorizations"], s["cutbacks"], s["wall_time_s"],
            100 * e["balance"] / IMPACT, e["impactors"], e["delamination"])


def main():
    alphas = [float(a) for a in sys.argv[1:]] or [-0.02, -0.05]
    print("alpha      corrections factorizations cutbacks  wall_s balance_% striker_J delamination_J")
    for alpha in [None] + alphas:
        with tempfile.TemporaryDirectory() as folder:
            r = run(alpha, folder)
        name = "trapezoid" if alpha is None else f"{alpha:g}"
        print(f"{name:10} {r[0]:11d} {r[1]:14d} {r[2]:8d} {r[3]:7.1f} {r[4]:9.2f} {r[5]:9.4f} {r[6]:14.4f}")


if __name__ == "__main__":
    main()
