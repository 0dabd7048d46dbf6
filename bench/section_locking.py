#!/usr/bin/env python3
"""Issue 50: are thin walls of a CUF section too stiff because the fully integrated L9/L16 section
elements lock?  Linear, small-strain models; each mesh run with the section's full Gauss rule
((p+1)x(p+1)) and a reduced one (p x p), chosen by the experimental environment variable
CUFEM_SECTION_RULE of branch wt-lock (src/values/mod.rs, SectionValues::new).

  python3 bench/section_locking.py channel   # bench/channel_twist.toml made linear: tip twist and u_z
  python3 bench/section_locking.py strip     # a 100 x 3 mm strip: torsion and plate bending across
Runs go to out/lock/ (needs target/release/cufem built on wt-lock)."""
import json, os, re, subprocess, sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CUFEM = os.path.join(ROOT, "target", "release", "cufem")
OUT = os.path.join(ROOT, "out", "lock")
ORDER = {"L9": 2, "L16": 3}


def run(name, text, rule):
    os.makedirs(OUT, exist_ok=True)
    path = os.path.join(OUT, name + ".toml")
    open(path, "w").write(text)
    out = os.path.join(OUT, name)
    env = dict(os.environ)
    if rule is not None:
        env["CUFEM_SECTION_RULE"] = str(rule)
    p = subprocess.run([CUFEM, "run", path, "--threads", "1", "--out", out, "--force", "--quiet"],
                       capture_output=True, text=True, env=env)
    if p.returncode != 0:
        print(name, "failed:", p.stderr[-400:])
        return None
    d = json.load(open(os.path.join(out, "summary.json")))
    return d["dof"], {q["name"]: q["u"] for q in d["probes"]}


def channel_model(el, af, aw, th, n, ratio):
    text = open(os.path.join(ROOT, "bench", "channel_twist.toml")).read()
    text = text.replace('geometry = "nonlinear"', 'geometry = "linear"')
    text = re.sub(r"increments = 20", "increments = 1", text)
    text = re.sub(r"max_increment = 0.05", "max_increment = 1.0", text)
    text = re.sub(r'element = "L\d+", origin', f'element = "{el}", origin', text)
    text = re.sub(r"along_flange = \d+, along_web = \d+, through = \d+",
                  f"along_flange = {af}, along_web = {aw}, through = {th}", text)
    text = re.sub(r"axis = \{[^}]*\}",
                  f'axis = {{ element = "B4", from = 0.0, to = 1.0, elements = {n}, ratio = {float(ratio)} }}', text)
    return text


def channel_measures(u):
    top, bot, web = u["top_flange_tip"], u["bottom_flange_tip"], u["web_middle"]
    twist = (top[0] - bot[0]) / 0.097          # chord rotation between the flange tips (small)
    return {"twist": twist, "uz_web": web[2], "ux_top": top[0], "uz_top": top[2]}


def channel():
    ref_mesh = ("L16", 8, 16, 2, 48, 10)
    meshes = [("L9", 2, 4, 1, 24, 10), ("L9", 4, 8, 1, 24, 10), ("L9", 8, 16, 1, 24, 10),
              ("L9", 2, 4, 2, 24, 10), ("L16", 2, 4, 1, 24, 10), ("L16", 4, 8, 1, 24, 10),
              ("L9", 2, 4, 1, 12, 1), ("L16", 2, 4, 1, 12, 1)]
    dof, u = run("ch_ref", channel_model(*ref_mesh), None)
    ref = channel_measures(u)
    print(f"reference {ref_mesh}: {dof} DOF, {ref}")
    print("mesh | DOF | aspect | rule | twist err % | u_z web err % | u_x top err % | u_z top err %")
    for m in meshes:
        el, af, aw, th, n, ratio = m
        aspect = (0.1 - 0.003) / aw / (0.003 / th)
        for rule in (ORDER[el] + 1, ORDER[el]):
            name = "ch_" + "_".join(map(str, m)) + f"_g{rule}"
            r = run(name, channel_model(*m), rule)
            if r is None:
                continue
            v = channel_measures(r[1])
            e = {k: 100 * (v[k] - ref[k]) / abs(ref[k]) for k in ref}
            print(f"{el} {af}/{aw} thr{th} {n}B4 r{ratio} | {r[0]} | {aspect:.1f} | {rule}x{rule} | "
                  f"{e['twist']:+.2f} | {e['uz_web']:+.2f} | {e['ux_top']:+.2f} | {e['uz_top']:+.2f}", flush=True)


def nl_model(el, af, aw, th, n, ratio):
    text = channel_model(el, af, aw, th, n, ratio)
    text = text.replace('geometry = "linear"', 'geometry = "nonlinear"')
    text = re.sub(r"increments = 1\n", "increments = 20\n", text)
    return re.sub(r"max_increment = 1.0", "max_increment = 0.05", text)


def nl_history(name):
    import csv
    rows = list(csv.DictReader(open(os.path.join(OUT, name, "history_probes.csv"))))
    return {round(float(r["lambda"]), 6): (float(r["top_flange_tip.u_x"]), float(r["top_flange_tip.u_z"])) for r in rows}


def nonlinear():
    """The error along the load path: if it grows with the twist, the stiffness is a large-rotation
    effect, not small-strain locking (which would show from the first increment)."""
    ref_mesh = ("L16", 6, 12, 1, 36, 10)
    meshes = [("L9", 2, 4, 1, 12, 1), ("L16", 2, 4, 1, 12, 1), ("L9", 2, 4, 1, 48, 1), ("L9", 4, 8, 1, 12, 1),
              ("L9", 2, 4, 1, 12, 10)]
    r = run("nl_ref", nl_model(*ref_mesh), None)
    print(f"nonlinear reference {ref_mesh}: {r[0]} DOF", flush=True)
    ref = nl_history("nl_ref")
    peak = [max(abs(v[i]) for v in ref.values()) for i in (0, 1)]
    for m in meshes:
        name = "nl_" + "_".join(map(str, m))
        r = run(name, nl_model(*m), None)
        h = nl_history(name)
        line = []
        for lam in sorted(ref):
            if lam in h and lam in (0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0):
                line.append(f"lam {lam}: ux {100 * (h[lam][0] - ref[lam][0]) / abs(ref[lam][0]):+.1f}% "
                            f"({100 * (h[lam][0] - ref[lam][0]) / peak[0]:+.1f}% of peak)")
        print(f"{m} {r[0]} DOF |", " | ".join(line), flush=True)


STRIP = """title = "strip"
[analysis]
geometry = "linear"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3
[[bodies]]
name = "strip"
material = "steel"
section = {{ shape = "rectangle", element = "{el}", x = {{ from = 0.0, to = 0.1, elements = {nx} }}, z = {{ from = 0.0, to = 0.003, elements = {nz} }} }}
axis = {{ element = "B4", from = 0.0, to = {length}, elements = {ny} }}
"""


def strip():
    """A 100 x 3 mm strip. Torsion: clamped at y = 0, a couple T = 0.05 F at y = 1 (opposite z
    forces on the two halves of the end face): Saint-Venant (Timoshenko & Goodier, thin rectangle)
    J = b t^3/3 (1 - 0.630 t/b), twist = T L/(G J), stiffened a little by the clamp's restrained
    warping. Plate bending across the wall: the long edge x = 0 clamped, a line load q along z on
    the edge x = b, a 0.3 m strip with free ends: cylindrical bending w = q b^3/(3 D), D = E t^3/(12 (1 - nu^2)),
    read at mid-length. Each against the refined CUF run (L16, 16 x 2) too."""
    e, nu, b, t = 200e9, 0.3, 0.1, 0.003
    g = e / (2 * (1 + nu))
    f = 10.0
    j = b * t**3 / 3 * (1 - 0.630 * t / b)
    theory_twist = f * 0.05 * 1.0 / (g * j)
    torsion = """[[constraints]]
name = "root"
body = "strip"
where = { y = 0.0 }
fix = ["x", "y", "z"]
[[loads]]
name = "left"
body = "strip"
where = { y = 1.0, x = [0.0, 0.05] }
total_force = [0.0, 0.0, -10.0]
[[loads]]
name = "right"
body = "strip"
where = { y = 1.0, x = [0.05, 0.1] }
total_force = [0.0, 0.0, 10.0]
[[probes]]
name = "a"
point = [0.0, 1.0, 0.0015]
[[probes]]
name = "b"
point = [0.1, 1.0, 0.0015]
"""
    q, length = 100.0, 0.3
    dplate = e * t**3 / (12 * (1 - nu**2))
    theory_w = q * b**3 / (3 * dplate)
    bending = f"""[[constraints]]
name = "edge"
body = "strip"
where = {{ x = 0.0 }}
fix = ["x", "y", "z"]
[[loads]]
name = "line"
body = "strip"
where = {{ x = 0.1 }}
total_force = [0.0, 0.0, {-q * length}]
[[probes]]
name = "a"
point = [0.1, {length / 2}, 0.0015]
"""
    def twist(el, nx, nz, rule):
        name = f"strip_t_{el}_{nx}_{nz}_g{rule}"
        r = run(name, STRIP.format(el=el, nx=nx, nz=nz, length=1.0, ny=16) + torsion, rule)
        return r and (r[0], (r[1]["b"][2] - r[1]["a"][2]) / 0.1)
    def bend(el, nx, nz, rule):
        name = f"strip_b_{el}_{nx}_{nz}_g{rule}"
        r = run(name, STRIP.format(el=el, nx=nx, nz=nz, length=length, ny=6) + bending, rule)
        return r and (r[0], r[1]["a"][2])
    ref_t = twist("L16", 16, 2, None)[1]
    ref_b = bend("L16", 16, 2, None)[1]
    print(f"torsion: theory (free warping) {theory_twist:.6g} rad, refined CUF L16 16x2 {ref_t:.6g} "
          f"({100 * (ref_t - theory_twist) / theory_twist:+.2f} %)")
    print(f"plate bending: theory {theory_w:.6g} m, refined CUF {-ref_b:.6g} ({100 * (-ref_b - theory_w) / theory_w:+.2f} %)")
    print("element | along x | aspect | rule | torsion err % vs ref | bending err % vs ref")
    for el in ("L9", "L16"):
        for nx in (1, 2, 4, 8):
            for rule in (ORDER[el] + 1, ORDER[el]):
                rt, rb = twist(el, nx, 1, rule), bend(el, nx, 1, rule)
                et = 100 * (rt[1] - ref_t) / abs(ref_t) if rt else float("nan")
                eb = 100 * (rb[1] - ref_b) / abs(ref_b) if rb else float("nan")
                print(f"{el} | {nx} | {b / nx / t:.1f} | {rule}x{rule} | {et:+.2f} | {eb:+.2f}", flush=True)


def strip_large_twist():
    """The strip's torsion with nonlinear geometry: the couple raised until the tip turns past 100
    degrees (Wagner's stiffening: the fibres become helices). Each mesh against the refined CUF run
    (L16 16 x 2, 32 B4) at every 4th increment: does the coarse wall's error grow with the twist?"""
    torsion = """[analysis]
geometry = "nonlinear"
[solver]
increments = 20
max_increment = 0.05
[[constraints]]
name = "root"
body = "strip"
where = { y = 0.0 }
fix = ["x", "y", "z"]
[[loads]]
name = "left"
body = "strip"
where = { y = 1.0, x = [0.0, 0.05] }
total_force = [0.0, 0.0, -6000.0]
[[loads]]
name = "right"
body = "strip"
where = { y = 1.0, x = [0.05, 0.1] }
total_force = [0.0, 0.0, 6000.0]
[[probes]]
name = "a"
point = [0.0, 1.0, 0.0015]
[[probes]]
name = "b"
point = [0.1, 1.0, 0.0015]
"""
    import csv, math

    def go(el, nx, nz, ny):
        name = f"strip_nl_{el}_{nx}_{nz}_{ny}"
        text = STRIP.format(el=el, nx=nx, nz=nz, length=1.0, ny=ny).replace('[analysis]\ngeometry = "linear"\n', "") + torsion
        r = run(name, text, None)
        rows = list(csv.DictReader(open(os.path.join(OUT, name, "history_probes.csv"))))
        out = {}
        for row in rows:
            dx = 0.1 + float(row["b.u_x"]) - float(row["a.u_x"])
            dz = float(row["b.u_z"]) - float(row["a.u_z"])
            out[round(float(row["lambda"]), 6)] = math.degrees(math.atan2(dz, dx))
        return r[0], out

    dof, ref = go("L16", 16, 2, 32)
    lams = [0.05, 0.2, 0.4, 0.6, 0.8, 1.0]
    print("reference L16 16x2 32 B4:", dof, "DOF; twist (deg) at lambda", {l: round(ref[l], 1) for l in lams}, flush=True)
    for el, nx, ny in (("L9", 2, 16), ("L9", 4, 16), ("L9", 8, 16), ("L16", 2, 16), ("L16", 4, 16), ("L9", 4, 32)):
        dof, h = go(el, nx, 1, ny)
        print(f"{el} {nx} along x (aspect {0.1 / nx / 0.003:.1f}), {ny} B4, {dof} DOF | twist err %: " +
              " ".join(f"{l}: {100 * (h[l] - ref[l]) / ref[l]:+.2f}" for l in lams), flush=True)


def channel_loads():
    """The linear channel under loads that work the walls' own bending across their thickness (the
    state the twisted channel reaches past 90 degrees, where the dead load pulls across the flanges):
    "sideways": the tip load along x on the top flange's end face (weak-axis bending and twist);
    "pry": the flanges' tips pulled apart along z (the section opens: plate bending of flanges and
    web at the corners). Error of the top flange tip's displacement along the load against the
    refined CUF run (L16 8/16, 2 through, 48 B4 graded)."""
    loads = {"sideways": ('total_force = [0.0, 0.0, -8e3]', 'total_force = [8e3, 0.0, 0.0]'),
             "pry": ('total_force = [0.0, 0.0, -8e3]', 'total_force = [0.0, 0.0, 100.0]\n[[loads]]\nname = "tip2"\n'
                     'body = "channel"\nwhere = { y = 1.0, region = "bottom_flange" }\ntotal_force = [0.0, 0.0, -100.0]')}
    meshes = [("L9", 2, 4, 1, 24, 10), ("L9", 4, 8, 1, 24, 10), ("L16", 2, 4, 1, 24, 10), ("L16", 4, 8, 1, 24, 10)]
    for key, (old, new) in loads.items():
        comp = 0 if key == "sideways" else 2
        _, u = run(f"cl_{key}_ref", channel_model("L16", 8, 16, 2, 48, 10).replace(old, new), None)
        ref = u["top_flange_tip"][comp]
        print(f"{key}: reference top tip u = {ref:.6g} m", flush=True)
        for m in meshes:
            _, u = run(f"cl_{key}_" + "_".join(map(str, m)), channel_model(*m).replace(old, new), None)
            print(f"  {m[0]} {m[1]}/{m[2]} aspect {(0.1 - 0.003) / m[2] / 0.003:.1f}: "
                  f"{100 * (u['top_flange_tip'][comp] - ref) / abs(ref):+.2f} %", flush=True)


if __name__ == "__main__":
    {"channel_loads": channel_loads, "channel": channel, "nonlinear": nonlinear, "strip": strip, "strip_nl": strip_large_twist}[sys.argv[1]]()
