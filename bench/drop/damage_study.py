#!/usr/bin/env python3
"""Issue 48: the drop weight of examples/laminate_drop_weight.toml with ply damage.

Writes each case's model into bench/drop/cases/, runs it with the release
binary (one thread, the log kept beside it), and appends a row to
bench/drop/damage_results.csv:

    python3 bench/drop/damage_study.py [CASE ...]   # from the repository root
    python3 bench/drop/damage_study.py --list

Columns as bench/drop/study.py's (the same `measure`), and the ply damage's:
the energy each mode dissipated (summary.json), the points whose strength the
crack band lowered, the scheme's dissipation and the ledger's rest (energy.csv).
"""
import csv, json, os, subprocess, sys, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study  # noqa: E402

ROOT, HERE = study.ROOT, study.HERE
BIN = os.environ.get("CUFEM_BIN", study.BIN)

T300 = dict(xt=1520e6, xc=1590e6, yt=45e6, yc=252e6, s12=105e6, s23=126e6)
G = dict(ft=12.5e3, fc=12.5e3, mt=1.0e3, mc=1.0e3)


def model(axis=60, per_ply=1, wide=1, steps=2400, duration=6e-3, mass=0.1, speed=4.0, viscosity=1e-6,
          toughness=G, strengths=T300, element="L4", forces="implicit", supports="lines", span=(0.0, 0.05), solver="", newmark="",
          graded=None):
    plies = ",\n".join('  { thickness = 0.0005, material = "cfrp", angle = %g, elements = %d }' % (a, per_ply)
                       for a in (0, 90, 90, 0))
    supports_text = support_text(supports, span)
    s = ", ".join("%s = %g" % kv for kv in strengths.items())
    g = toughness
    return f'''title = "drop weight with ply damage: {axis} B2, {per_ply} {element}/ply, {wide} across, {steps} steps"

[analysis]
type = "transient"
interface_forces = "implicit"
ply_damage_forces = "{forces}"
{newmark}

[solver]
max_increments = 200000
{solver}

[[materials]]
name = "cfrp"
density = 1540.0
strengths = {{ {s} }}
damage = {{ fibre_tension = {g["ft"]:g}, fibre_compression = {g["fc"]:g}, matrix_tension = {g["mt"]:g}, matrix_compression = {g["mc"]:g}, viscosity = {viscosity:g} }}
orthotropic = {{ e1 = 156e9, e2 = 9.09e9, e3 = 9.09e9, g12 = 6.96e9, g13 = 6.96e9, g23 = 3.24e9, nu12 = 0.228, nu13 = 0.228, nu23 = 0.4 }}

[[materials]]
name = "epoxy_interface"
cohesive = {{ gic = 300.0, giic = 800.0, bk_exponent = 2.0, normal_strength = 10e6, shear_strength = 16.3e6, viscosity = 1e-06 }}

[[bodies]]
name = "beam"
section = {{ shape = "laminate", element = "{element}", x = {{ from = 0.0, to = 0.01, elements = {wide} }}, plies = [
{plies} ], interfaces = "cohesive", interface_material = "epoxy_interface" }}
axis = {{ element = "B2", segments = [{{ from = 0.0, to = 0.05, elements = {axis} }}] }}

{supports_text}{graded_steps(study.striker(mass, speed, duration, steps), duration, graded)}'''


def graded_steps(text, duration, graded):
    """The striker's one step split in two where `graded = (t1, n1, n2)`:
    `n1` time steps over the first `t1` s (while the plies and the
    interfaces damage), `n2` over the rest."""
    if graded is None:
        return text
    t1, n1, n2 = graded
    head = text[:text.index("[[steps]]")]
    return head + f'''[[steps]]
name = "impact"
factor = 1.0
duration = {t1:g}
increments = {n1}

[[steps]]
name = "rebound"
factor = 1.0
duration = {duration - t1:g}
increments = {n2}
'''


def support_text(supports, span):
    if supports == "lines":
        return "".join(f'''[[constraints]]
name = "support_{n}"
body = "beam"
where = {{ y = {y:g}, z = 0.0 }}
fix = ["z"]

''' for n, y in zip(("left", "right"), span))
    # fixed rigid rollers (r = 5 mm) under the bottom face
    return "".join(f'''[[indenters]]
name = "support_{n}"
body = "beam"
shape = "cylinder"
surface = {{ z = 0.0, y = [{y - 0.004:g}, {y + 0.004:g}] }}
axis = "x"
center = [0.005, {y:g}, -0.005]
radius = 0.005
displacement = [0.0, 0.0, 0.0]

''' for n, y in zip(("left", "right"), span))


CASES = {}
# 1.5 ms probes: why Newton cuts back
CASES["p15_base"] = dict(steps=600, duration=1.5e-3)
CASES["p15_rollers"] = dict(steps=600, duration=1.5e-3, supports="rollers", span=(0.005, 0.045))
CASES["p15_wide4"] = dict(steps=600, duration=1.5e-3, wide=4)
CASES["p15_tough"] = dict(steps=600, duration=1.5e-3, toughness=dict(ft=100e3, fc=100e3, mt=10e3, mc=40e3))
CASES["p15_fib"] = dict(steps=600, duration=1.5e-3, toughness=dict(ft=91.6e3, fc=79.9e3, mt=1e3, mc=1e3))
CASES["p15_fib_m"] = dict(steps=600, duration=1.5e-3, toughness=dict(ft=91.6e3, fc=79.9e3, mt=1.2e3, mc=3e3))
CASES["p15_m12"] = dict(steps=600, duration=1.5e-3, toughness=dict(ft=100e3, fc=100e3, mt=1.2e3, mc=40e3))
TOUGH = dict(ft=100e3, fc=100e3, mt=10e3, mc=40e3)
# the example's toughnesses: the least round values whose longest band 2 E G/X² exceeds this mesh's bands
SHIP = dict(ft=100e3, fc=100e3, mt=1.2e3, mc=40e3)
for a, s in ((30, 2400), (60, 2400), (60, 4800), (120, 2400), (30, 4800), (120, 4800), (60, 9600)):
    CASES[f"ship_a{a}_n{s}"] = dict(axis=a, steps=s, toughness=SHIP)
    # on fixed rollers (r = 5 mm) 40 mm apart instead of the line supports
    CASES[f"roll_a{a}_n{s}"] = dict(axis=a, steps=s, toughness=SHIP, supports="rollers", span=(0.005, 0.045))
# the example's graded step: 1.25 us over the first 2 ms (the damage grows until about 1.9 ms), then
# 5 us; halved (0.625 / 2.5 us) and with the axis refined (120 B2)
for a, (n1, n2) in ((60, (1600, 800)), (60, (3200, 1600)), (120, (1600, 800))):
    CASES[f"roll_a{a}_g{n1}_{n2}"] = dict(axis=a, toughness=SHIP, supports="rollers", span=(0.005, 0.045),
                                          graded=(2e-3, n1, n2))
# the graded example with other linear solves (each a setting of [solver]): a new double factor at
# every correction, double factors with the reuse, Newton's tolerances at 1e-8 with and without the
# reuse, and the halved steps without the reuse
for tag, solver in (("noreuse", "reuse_factorization = false"), ("double", 'factor_precision = "double"'),
                    ("tol8", "residual_tolerance = 1e-8\ndisplacement_tolerance = 1e-8"),
                    ("tol8_noreuse", "residual_tolerance = 1e-8\ndisplacement_tolerance = 1e-8\nreuse_factorization = false")):
    CASES[f"roll_a60_g1600_800_{tag}"] = dict(axis=60, toughness=SHIP, supports="rollers", span=(0.005, 0.045),
                                              graded=(2e-3, 1600, 800), solver=solver)
CASES["roll_a120_g1600_800_noreuse"] = dict(axis=120, toughness=SHIP, supports="rollers", span=(0.005, 0.045),
                                            graded=(2e-3, 1600, 800), solver="reuse_factorization = false")
for tag, solver in (("", ""), ("_noreuse", "reuse_factorization = false")):
    # two L4 per ply through the thickness: does the spread across the solves narrow?
    CASES[f"roll_a60_p2_g1600_800{tag}"] = dict(axis=60, per_ply=2, toughness=SHIP, supports="rollers",
                                                 span=(0.005, 0.045), graded=(2e-3, 1600, 800), solver=solver)
CASES["roll_a60_g3200_1600_noreuse"] = dict(axis=60, toughness=SHIP, supports="rollers", span=(0.005, 0.045),
                                            graded=(2e-3, 3200, 1600), solver="reuse_factorization = false")
# the example's PCG stopped at most at 1e-4, 1e-6 or 1e-10 (solver.krylov_tolerance), and Newton's
# tolerances at 1e-9: which of them leave the default's path, and where
for tag, solver in (("k4", "krylov_tolerance = 1e-4"), ("k6", "krylov_tolerance = 1e-6"),
                    ("k10", "krylov_tolerance = 1e-10"),
                    ("tol9", "residual_tolerance = 1e-9\ndisplacement_tolerance = 1e-9")):
    CASES[f"roll_a60_g1600_800_{tag}"] = dict(axis=60, toughness=SHIP, supports="rollers", span=(0.005, 0.045),
                                              graded=(2e-3, 1600, 800), solver=solver)
# a step control by the damage instead of the graded steps: from 1.25 us, steps up to 5 us
CASES["roll_a60_sc10"] = dict(steps=4800, toughness=SHIP, supports="rollers", span=(0.005, 0.045),
                              solver="max_increment = 8.333333333333333e-4\nstep_control = { damage = 0.1 }")
CASES["full_tough_a60_n2400"] = dict(steps=2400, toughness=TOUGH)
CASES["p15_visc1e-5"] = dict(steps=600, duration=1.5e-3, viscosity=1e-5)
CASES["p15_n1200"] = dict(steps=1200, duration=1.5e-3)
CASES["p15_ls"] = dict(steps=600, duration=1.5e-3, solver="line_search = true")
CASES["p15_ls_rollers"] = dict(steps=600, duration=1.5e-3, solver="line_search = true", supports="rollers", span=(0.005, 0.045))

# Newmark's numerical damping (gamma > 1/2, beta = (gamma + 1/2)^2/4) against the step-to-step chatter of
# closed cracks and touching delaminated faces
G52 = 'newmark = { beta = 0.2601, gamma = 0.52 }'
CASES["p15_g52"] = dict(steps=600, duration=1.5e-3, newmark=G52)
CASES["p15_g52_rollers"] = dict(steps=600, duration=1.5e-3, newmark=G52, supports="rollers", span=(0.005, 0.045))

HEAD = study.HEAD + ",FT_J,FC_J,MT_J,MC_J,reduced,scheme_J,rest_J"


def run(name, timeout=3000):
    p = CASES[name]
    os.makedirs(os.path.join(HERE, "cases"), exist_ok=True)
    path = os.path.join(HERE, "cases", name + ".toml")
    open(path, "w").write(model(**p))
    out = os.path.join(HERE, "cases", "out_" + name)
    t0 = time.time()
    log = open(os.path.join(HERE, "cases", name + ".log"), "w")
    try:
        subprocess.run([BIN, "run", path, "--out", out, "--threads", "1", "--force"], stdout=log, stderr=subprocess.STDOUT,
                       timeout=timeout)
    except subprocess.TimeoutExpired:
        return "%s,,,,,stopped after %d s" % (name, timeout)
    wall = time.time() - t0
    if not os.path.exists(os.path.join(out, "summary.json")):
        return "%s,,,,,failed" % name
    study.DURATION = p.get("duration", 6e-3)
    m = study.measure(out, wall)
    # the first (finest) step of a graded run
    g = p.get("graded")
    m["dt_us"] = g[0] / g[1] * 1e6 if g else p.get("duration", 6e-3) / p["steps"] * 1e6
    s = json.load(open(os.path.join(out, "summary.json")))
    dmg = s["damage"]
    for k, key in zip(("FT_J", "FC_J", "MT_J", "MC_J"), dmg["modes"]):
        m[k] = dmg["dissipated_j"][key]
    m["reduced"] = dmg["strength_reduced_points"]
    e = list(csv.DictReader(open(os.path.join(out, "energy.csv"))))
    m["scheme_J"] = float(e[-1].get("damage_scheme_J", "nan"))
    m["rest_J"] = float(e[-1].get("plastic_J", "nan"))
    fmt = lambda v: ("%.6g" % v) if isinstance(v, float) else str(v).replace(",", ";")
    return name + "," + ",".join(fmt(m[c]) for c in HEAD.split(",")[1:])


if __name__ == "__main__":
    if "--list" in sys.argv:
        print("\n".join(CASES))
        sys.exit(0)
    table = os.path.join(HERE, "damage_results.csv")
    if not os.path.exists(table):
        open(table, "w").write(HEAD + "\n")
    for n in sys.argv[1:] or list(CASES):
        row = run(n)
        print(row, flush=True)
        open(table, "a").write(row + "\n")
