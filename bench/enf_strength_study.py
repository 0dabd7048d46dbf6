#!/usr/bin/env python3
"""The end-notched flexure's peak against corrected beam theory, as the interface's
strength, the precrack, the viscosity and the increments change (issue 48's 3 %).

    python3 bench/enf_strength_study.py [CUFEM] [--cases NAME,...]

Each case is examples/enf.toml with some keys changed, run with `cufem run --threads 1`;
its curve (the load line's reaction against its deflection) is compared with the
closed form of tests/common/cbt.rs (Enf: Carlsson, Gillespie & Pipes with Wang &
Williams' 0.42χh, ported below) as the slow test `enf_curve_follows_corrected_beam_theory`
does: the whole-curve error max |P − P_CBT(δ)| / P_c, the peak against P_c and the
branch past 1.05 δ_c. Pure python3, no numpy. Results: bench/enf_strength_results.txt.
"""
import csv
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# AS4/PEEK and the specimen of examples/enf.toml
E11, E22, G13 = 122.7e9, 10.1e9, 5.5e9
B, H, L = 0.0254, 0.00156, 0.051
GIIC = 1719.0
_G = 1.18 * math.sqrt(E11 * E22) / G13
_R = _G / (1 + _G)
CHI = math.sqrt(E11 / (11 * G13) * (3 - 2 * _R * _R))
OFFSET = 0.42 * CHI * H


def compliance(a):
    """CBT compliance δ/P at crack a (both sides of the load line)."""
    A = a + OFFSET
    if A <= L:
        return (2 * L**3 + 3 * A**3) / (8 * E11 * B * H**3)
    return (8 * L**3 - 3 * (2 * L - A) ** 3) / (8 * E11 * B * H**3)


def branch_point(a):
    """(δ, P) on the propagation branch with the crack at a."""
    A = a + OFFSET
    x = A if A <= L else 2 * L - A
    p = math.sqrt(GIIC / (9 * x * x / (16 * E11 * B * B * H**3)))
    return p * compliance(a), p


def cbt_load(a0, d):
    dc, _ = branch_point(a0)
    if d <= dc:
        return d / compliance(a0)
    lo, hi = a0, 2 * L - OFFSET - 1e-9
    for _ in range(200):
        m = 0.5 * (lo + hi)
        if branch_point(m)[0] < d:
            lo = m
        else:
            hi = m
    return branch_point(0.5 * (lo + hi))[1]


# the precrack of examples/enf.toml at 77a6605 (a0 = 39.3125 mm) and a longer one (44.0625 mm, A0 = 0.886 L)
LONG = [
    ("crack = { from = 0.0, to = 0.0393 }", "crack = { from = 0.0, to = 0.0440625 }"),
    ("{ from = 0.0, to = 0.03825, elements = 10 }", "{ from = 0.0, to = 0.043, elements = 11 }"),
    ("{ from = 0.03825, to = 0.05325, elements = 40 }", "{ from = 0.043, to = 0.058, elements = 40 }"),
    ("{ from = 0.05325, to = 0.102, elements = 13 }", "{ from = 0.058, to = 0.102, elements = 12 }"),
    ("displacement = { z = -0.0042 }", "displacement = { z = -0.00415 }"),
    ("factor = 0.8333333333333334", "factor = 0.8675"),
]


def strength(n):
    return [("normal_strength = 80e6", f"normal_strength = {n}e6")]


def viscosity(v):
    return [("viscosity = 1e-5", f"viscosity = {v}")]


def increments(n):
    return [("name = \"propagation\"\nfactor = 1.0\nincrements = 140", f"name = \"propagation\"\nfactor = 1.0\nincrements = {n}")]


# name: (a0, edits)
CASES = {
    "shipped": (0.0440625, []),
    "short_n80": (0.0393125, []),
    "long_n80": (0.0440625, LONG),
    "long_n140": (0.0440625, LONG + strength(140)),
    "long_n140_i300": (0.0440625, LONG + strength(140) + increments(300)),
    "long_n140_i600": (0.0440625, LONG + strength(140) + increments(600)),
    "long_n140_v1e-4": (0.0440625, LONG + strength(140) + viscosity("1e-4") + increments(450)),
    "long_n140_v1e-4_i600": (0.0440625, LONG + strength(140) + viscosity("1e-4") + increments(600)),
}
for _n in (100, 120, 160, 200):
    CASES[f"long_n{_n}_v1e-4"] = (0.0440625, LONG + strength(_n) + viscosity("1e-4") + increments(450))
# the same with the interface nodes twice as close where the crack runs (0.0625 mm)
FINE = [(new, new.replace("elements = 40", "elements = 80")) for _, new in LONG if "elements = 40" in new]
for _n in (80, 140, 200):
    CASES[f"long_fine_n{_n}_v1e-4"] = (0.0440625, LONG + FINE + strength(_n) + viscosity("1e-4") + increments(450))
# a ten times softer interface (5 E3/t instead of the default 50 E3/t)
SOFT = [("normal_strength = 140e6,", "normal_strength = 140e6, penalty = 3.24e13,")]
CASES["long_n140_k10_i450"] = (0.0440625, LONG + strength(140) + SOFT + increments(450))
CASES["long_n140_k10_i600"] = (0.0440625, LONG + strength(140) + SOFT + increments(600))
CASES["long_n140_k10_v1e-4"] = (0.0440625, LONG + strength(140) + SOFT + viscosity("1e-4") + increments(450))
# three times softer than the default penalty (3.24e14 Pa/m): between the early drop and the branch's lift
SOFT3 = [("normal_strength = 140e6,", "normal_strength = 140e6, penalty = 1.08e14,")]
CASES["long_n140_k3_i450"] = (0.0440625, LONG + strength(140) + SOFT3 + increments(450))
CASES["long_n140_k3_i600"] = (0.0440625, LONG + strength(140) + SOFT3 + increments(600))


def columns(path):
    rows = list(csv.DictReader(open(path)))
    return {k: [float(r[k]) if r[k] else 0.0 for r in rows] for k in rows[0]}


# The cases edit examples/enf.toml as it was before it took the case long_n140_k3_i450 (the
# precrack a0 = 39.3 mm, normal_strength = 80e6, the default penalty, 140 increments): that
# file at commit 77a6605; `shipped` is the example as it is now.
BASE_COMMIT = "77a6605"


def run_case(cufem, name, a0, edits, scratch):
    if name == "shipped":
        text = (ROOT / "examples" / "enf.toml").read_text()
    else:
        text = subprocess.run(["git", "show", f"{BASE_COMMIT}:examples/enf.toml"], cwd=ROOT, check=True,
                              capture_output=True, text=True).stdout
    for old, new in edits:
        assert text.count(old) == 1, f"{name}: {old!r} not once in examples/enf.toml at {BASE_COMMIT}"
        text = text.replace(old, new)
    model = scratch / f"{name}.toml"
    model.write_text(text)
    out = scratch / name
    start = time.time()
    subprocess.run([cufem, "run", str(model), "--out", str(out), "--quiet", "--threads", "1"], check=True,
                   stdout=subprocess.DEVNULL)
    secs = time.time() - start
    probes, load = columns(out / "history_probes.csv"), columns(out / "history_load.csv")
    points = [(-u, -p) for u, p in zip(probes["load_line.u_z"], load["r_z"])]
    dc, pc = branch_point(a0)
    errors = [((p - cbt_load(a0, d)) / pc, d) for d, p in points]
    worst = max(errors, key=lambda e: abs(e[0]))
    branch = max((abs(e) for e, d in errors if d >= 1.05 * dc), default=float("nan"))
    peak = max(p for _, p in points)
    return (f"| {name} | {1e3 * a0:.2f} | {(a0 + OFFSET) / L:.3f} | {100 * (peak / pc - 1):+.2f} % | "
            f"{100 * worst[0]:+.2f} % at {1e3 * worst[1]:.3f} mm | {100 * branch:.2f} % | {len(points)} | {secs:.0f} s |")


def main():
    args = sys.argv[1:]
    cases = list(CASES)
    if "--cases" in args:
        i = args.index("--cases")
        cases = args[i + 1].split(",")
        del args[i:i + 2]
    cufem = args[0] if args else str(ROOT / "target" / "release" / "cufem")
    print("| case | a0 (mm) | A0/L | peak − P_c | whole-curve error | branch past 1.05 δ_c | increments | time |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        for name in cases:
            a0, edits = CASES[name]
            print(run_case(cufem, name, a0, edits, Path(tmp)), flush=True)


if __name__ == "__main__":
    main()
