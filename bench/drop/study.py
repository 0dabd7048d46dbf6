#!/usr/bin/env python3
"""Issue 48: convergence study of a drop weight on a cohesive [0/90]s beam.

Writes each case's model into bench/drop/cases/, runs it with the release
binary (one thread), and appends a row to the results table:

    python3 bench/drop/study.py [CASE ...]    # from the repository root; no CASE: all
    python3 bench/drop/study.py --list

Columns: Δt, steps, Newton iterations, cutbacks, peak contact force, absorbed
energy (the striker's loss, E0 − ½ m v² at the end), delaminated area (d = 1),
the law's dissipation and viscous work (summary.json), the ledger's
delamination (energy.csv), the largest |balance| and the largest growth of
the mechanical energy over one step (kinetic + elastic + striker + energy
held by the interfaces; nothing does work on the closed system once the
supports are fixed), both relative to the impact energy E0.
"""
import csv, json, os, subprocess, sys, time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
HERE = os.path.join(ROOT, "bench", "drop")
BIN = os.path.join(ROOT, "target", "release", "cufem")
DURATION = 6.0e-3


def model(axis=30, per_ply=1, steps=1200, forces="implicit", gamma=None, mass=0.1, speed=4.0, viscosity=1e-6):
    newmark = "" if gamma is None else "newmark = { gamma = %g, beta = %g }\n" % (gamma, 0.25 * (gamma + 0.5) ** 2)
    plies = ",\n".join('  { thickness = 0.0005, material = "cfrp", angle = %g, elements = %d }' % (a, per_ply) for a in (0, 90, 90, 0))
    return f'''title = "drop weight on a cohesive [0/90]s beam: {axis} B2, {per_ply} L4/ply, {steps} steps, {forces}"

[analysis]
type = "transient"
interface_forces = "{forces}"
{newmark}
[solver]
max_increments = 200000

[[materials]]
name = "cfrp"
density = 1540.0
orthotropic = {{ e1 = 156e9, e2 = 9.09e9, e3 = 9.09e9, g12 = 6.96e9, g13 = 6.96e9, g23 = 3.24e9, nu12 = 0.228, nu13 = 0.228, nu23 = 0.4 }}

[[materials]]
name = "epoxy_interface"
cohesive = {{ gic = 300.0, giic = 800.0, bk_exponent = 2.0, normal_strength = 10e6, shear_strength = 16.3e6, viscosity = {viscosity:g} }}

[[bodies]]
name = "beam"
section = {{ shape = "laminate", element = "L4", x = {{ from = 0.0, to = 0.01, elements = 1 }}, plies = [
{plies} ], interfaces = "cohesive", interface_material = "epoxy_interface" }}
axis = {{ element = "B2", segments = [{{ from = 0.0, to = 0.05, elements = {axis} }}] }}

[[constraints]]
name = "support_left"
body = "beam"
where = {{ y = 0.0, z = 0.0 }}
fix = ["z"]

[[constraints]]
name = "support_right"
body = "beam"
where = {{ y = 0.05, z = 0.0 }}
fix = ["z"]

{striker(mass, speed, DURATION, steps)}'''


def striker(mass, speed, duration, steps):
    """The striker (a rigid cylinder of r = 6 mm at mid-span) and the one
    load step of `steps` time steps over `duration`: the tables every drop
    model of bench/drop ends with (study.py, damage_study.py)."""
    return f'''[[indenters]]
name = "striker"
body = "beam"
shape = "cylinder"
surface = {{ z = 0.002, y = [0.015, 0.035] }}
axis = "x"
center = [0.005, 0.025, 0.00801]
radius = 0.006
mass = {mass:g}
velocity = [0.0, 0.0, {-speed:g}]

[[steps]]
name = "impact"
factor = 1.0
duration = {duration:g}
increments = {steps}
'''


CASES = {}
for s in (1200, 2400, 4800, 9600):
    CASES[f"imp_a30_p1_n{s}"] = dict(axis=30, per_ply=1, steps=s)
for s in (2400, 4800):
    CASES[f"imp_a60_p1_n{s}"] = dict(axis=60, per_ply=1, steps=s)
    CASES[f"imp_a30_p2_n{s}"] = dict(axis=30, per_ply=2, steps=s)
    CASES[f"imp_a60_p2_n{s}"] = dict(axis=60, per_ply=2, steps=s)
CASES["imp_a120_p2_n2400"] = dict(axis=120, per_ply=2, steps=2400)
CASES["imp_a120_p1_n2400"] = dict(axis=120, per_ply=1, steps=2400)
CASES["imp_a30_p4_n2400"] = dict(axis=30, per_ply=4, steps=2400)
for s in (1200, 2400, 4800):
    CASES[f"nmk_a30_p1_n{s}"] = dict(axis=30, per_ply=1, steps=s, forces="newmark")
    CASES[f"dg06_a30_p1_n{s}"] = dict(axis=30, per_ply=1, steps=s, forces="discrete_gradient", gamma=0.6)
    CASES[f"imp_a30_p1_n{s}_v1e-7"] = dict(axis=30, per_ply=1, steps=s, viscosity=1e-7)

TIMEOUT = 2400  # s of wall time per case (the machine is shared)
WINDOW = 1.0e-4  # s: the window of the averaged force (a 10 kHz load cell)

HEAD = "case,dt_us,steps,newton,cutbacks,status,peak_N,t_peak_ms,peak_avg_N,absorbed_J,dissipated_J,contact_end_ms,delam_mm2,law_J,viscous_J,ledger_J,max_abs_balance_pct,max_step_growth_pct,wall_s"


def measure(out, wall):
    s = json.load(open(os.path.join(out, "summary.json")))
    d = s["delamination"]
    e = list(csv.DictReader(open(os.path.join(out, "energy.csv"))))
    h = list(csv.DictReader(open(os.path.join(out, "history_striker.csv"))))
    E0 = float(e[0]["impactors_J"])
    f = [float(r["f_n"]) for r in h]
    ip = max(range(len(f)), key=lambda k: f[k])
    tpeak = float(e[ip + 1]["time_s"]) if ip + 1 < len(e) else float("nan")
    # the contact force averaged over WINDOW: the striker's impulse over the window / WINDOW
    # (f_n at the end of each step is that step's impulse / Δt under "implicit")
    times = [float(r["time_s"]) for r in e]
    imp = [0.0]
    for k in range(len(f)):
        imp.append(imp[-1] + f[k] * (times[k + 1] - times[k]))
    avg, j = [], 0
    for i in range(len(times)):
        while times[i] - times[j] > WINDOW * (1 + 1e-9):
            j += 1
        if times[i] - times[j] >= WINDOW * (1 - 1e-9):
            avg.append((imp[i] - imp[j]) / (times[i] - times[j]))
    held = lambda r: float(r["interfaces_J"]) - float(r["delamination_J"])
    mech = [float(r["kinetic_J"]) + float(r["elastic_J"]) + float(r["impactors_J"]) + held(r) for r in e]
    grow = max(mech[k + 1] - mech[k] for k in range(len(mech) - 1))
    bal = max(abs(float(r["balance_J"])) for r in e)
    return dict(steps=s["increments"], newton=s["newton_iterations"], cutbacks=s["cutbacks"], status=s["status"],
                peak_N=f[ip], t_peak_ms=tpeak * 1e3, peak_avg_N=max(avg), absorbed_J=E0 - float(e[-1]["impactors_J"]), dissipated_J=E0 - mech[-1], contact_end_ms=1e3 * max([times[k + 1] for k in range(len(f)) if f[k] > 0] or [0.0]),
                delam_mm2=d["area_m2"] * 1e6, law_J=d["dissipated_j"], viscous_J=d["viscous_j"],
                ledger_J=float(e[-1]["delamination_J"]), max_abs_balance_pct=100 * bal / E0,
                max_step_growth_pct=100 * grow / E0, wall_s=wall)


def run(name):
    p = CASES[name]
    os.makedirs(os.path.join(HERE, "cases"), exist_ok=True)
    path = os.path.join(HERE, "cases", name + ".toml")
    open(path, "w").write(model(**p))
    out = os.path.join(HERE, "cases", "out_" + name)
    t0 = time.time()
    try:
        r = subprocess.run([BIN, "run", path, "--out", out, "--quiet", "--threads", "1", "--force"], capture_output=True, text=True,
                           timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        return "%s,,,,,stopped after %d s (wall; the machine shared)" % (name, TIMEOUT)
    wall = time.time() - t0
    if not os.path.exists(os.path.join(out, "summary.json")):
        return "%s,,,,,failed: %s" % (name, (r.stderr or r.stdout).strip().splitlines()[-1][:120].replace(",", ";"))
    m = measure(out, wall)
    dt = DURATION / p["steps"] * 1e6
    cols = HEAD.split(",")[1:]
    m["dt_us"] = dt
    fmt = lambda v: ("%.6g" % v) if isinstance(v, float) else str(v).replace(",", ";")
    return name + "," + ",".join(fmt(m[c]) for c in cols)


if __name__ == "__main__":
    if "--remeasure" in sys.argv:
        # rewrite the table from the output folders kept in cases/
        rows = [HEAD]
        for n in CASES:
            out = os.path.join(HERE, "cases", "out_" + n)
            if os.path.exists(os.path.join(out, "summary.json")):
                old = [l for l in open(os.path.join(HERE, "results.csv")) if l.startswith(n + ",")]
                wall = float(old[-1].strip().split(",")[-1]) if old else float("nan")
                m = measure(out, wall)
                m["dt_us"] = DURATION / CASES[n]["steps"] * 1e6
                rows.append(n + "," + ",".join(("%.6g" % m[c]) if isinstance(m[c], float) else str(m[c]) for c in HEAD.split(",")[1:]))
        open(os.path.join(HERE, "results.csv"), "w").write("\n".join(rows) + "\n")
        print("\n".join(rows))
        sys.exit(0)
    if "--table" in sys.argv:
        # the results table as text (bench/drop/results.txt)
        rows = list(csv.DictReader(open(os.path.join(HERE, "results.csv"))))
        cols = ["case", "dt_us", "steps", "newton", "cutbacks", "status", "peak_N", "peak_avg_N", "absorbed_J", "dissipated_J", "contact_end_ms", "delam_mm2",
                "law_J", "viscous_J", "ledger_J", "max_abs_balance_pct", "max_step_growth_pct"]
        short = ["case", "dt_us", "steps", "newton", "cut", "status", "peak_N", "avg_N", "absorb_J", "dissip_J", "end_ms", "delam_mm2",
                 "law_J", "visc_J", "ledger_J", "|bal|%E0", "grow%E0"]
        def cell(r, c):
            v = r.get(c) or ""
            try:
                x = float(v)
                return v if c in ("steps", "newton", "cutbacks") else ("%.4g" % x)
            except ValueError:
                return v
        w = [max(len(s), *(len(cell(r, c)) for r in rows)) for s, c in zip(short, cols)]
        print("  ".join(s.ljust(n) for s, n in zip(short, w)))
        for r in rows:
            print("  ".join(cell(r, c).ljust(n) for c, n in zip(cols, w)))
        sys.exit(0)
    if "--list" in sys.argv:
        print("\n".join(CASES))
        sys.exit(0)
    names = sys.argv[1:] or list(CASES)
    table = os.path.join(HERE, "results.csv")
    if not os.path.exists(table):
        open(table, "w").write(HEAD + "\n")
    for n in names:
        row = run(n)
        print(row, flush=True)
        open(table, "a").write(row + "\n")
