#!/usr/bin/env python3
"""Issues 48/50: a transient example with Bossak's α.

Runs examples/NAME.toml (default laminate_drop_weight_damage) as shipped
(the trapezoidal rule) and with `analysis.newmark = { alpha = A }` for each
A given (default -0.02 -0.05), one after the other with the release binary
(CUFEM_BIN to override), two threads, and prints per run: Newton
corrections, factorizations, cutbacks, wall time, the energy balance (the
scheme's dissipation) as a share of the impactors' initial kinetic energy,
the energy the impactors keep, and the delamination's and the plastic
dissipation where the model has them:

    python3 bench/drop/bossak.py [--example NAME] [A ...]   # from the repository root
"""
import csv, json, os, subprocess, sys, tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.environ.get("CUFEM_BIN", os.path.join(ROOT, "target", "release", "cufem"))


def run(example, alpha, folder):
    text = open(os.path.join(ROOT, "examples", example + ".toml")).read()
    anchor = 'type = "transient"\n'
    assert anchor in text and "\nnewmark" not in text
    if alpha is not None:
        text = text.replace(anchor, anchor + f"newmark = {{ alpha = {alpha} }}\n")
    model = os.path.join(folder, "model.toml")
    open(model, "w").write(text)
    out = os.path.join(folder, "out")
    subprocess.run([BIN, "run", model, "--out", out, "--quiet", "--threads", "2"], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    s = json.load(open(os.path.join(out, "summary.json")))
    e = s["energy"]
    with open(os.path.join(out, "energy.csv")) as f:
        impact = float(next(csv.DictReader(f))["impactors_J"])
    return (s["newton_iterations"], s["timings"]["factorizations"], s["cutbacks"], s["wall_time_s"],
            100 * e["balance"] / impact, e["impactors"], e.get("delamination", 0.0), e["plastic"])


def main():
    args = sys.argv[1:]
    example = "laminate_drop_weight_damage"
    if args[:1] == ["--example"]:
        example, args = args[1], args[2:]
    alphas = [float(a) for a in args] or [-0.02, -0.05]
    print(f"examples/{example}.toml")
    print("alpha      corrections factorizations cutbacks  wall_s balance_% impactors_J delamination_J plastic_J")
    for alpha in [None] + alphas:
        with tempfile.TemporaryDirectory() as folder:
            r = run(example, alpha, folder)
        name = "trapezoid" if alpha is None else f"{alpha:g}"
        print(f"{name:10} {r[0]:11d} {r[1]:14d} {r[2]:8d} {r[3]:7.1f} {r[4]:9.2f} {r[5]:11.4f} {r[6]:14.4f} {r[7]:9.4f}")


if __name__ == "__main__":
    main()
