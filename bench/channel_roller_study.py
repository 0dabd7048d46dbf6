#!/usr/bin/env python3
"""Issue 49: a channel pressed by a rigid roller on ONE flange (off its shear centre) twists
10-20 % off CalculiX in a user's model.  Is it the section's discretisation (cross-wall bending
locking of L9 walls, bench/section_locking_results.txt) or the contact loading (where across the
flange the roller's force acts)?

  python3 bench/channel_roller_study.py fork|nofork|patch|plastic   # cufem meshes of each variant
  python3 bench/channel_roller_study.py model STUDY [MESH] > F.toml   # a variant's model file, for
  cufem verify F.toml --refine 1 --out DIR                           # its CalculiX twin, and then
  python3 bench/channel_roller_study.py twin DIR                     # both sides' measures

Model: bench/channel_roller.toml (its header states every choice).  Runs go to out/roller/.
Measures at stations y = 25 (fork support), 100, 175, 250, 325 mm (mid-span, under the roller):
  twist  = (u_x(web top) - u_x(web bottom)) / h          (rotation of the web, rad)
  flange = (u_z(top flange tip) - u_z(web top)) / b      (rotation of the top flange)
  uz_wt  = u_z at the web's top corner;  force = roller force (full structure)."""
import json, os, re, subprocess, sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CUFEM = os.path.join(ROOT, "target", "release", "cufem")
OUT = os.path.join(ROOT, "out", "roller")
BASE = os.path.join(ROOT, "bench", "channel_roller.toml")
STATIONS = [25, 100, 175, 250, 325]
H, B = 0.06, 0.04


def measures(u, force):
    m = {"force": force}
    for y in STATIONS:
        wt, wb, tt = u[f"wt_{y}"], u[f"wb_{y}"], u[f"tt_{y}"]
        m[f"twist_{y}"] = (wt[0] - wb[0]) / H
        m[f"flange_{y}"] = (tt[2] - wt[2]) / B
        m[f"ux_{y}"] = wt[0]
    m["uz_wt"] = u["wt_325"][2]
    m["uz_wb"] = u["wb_325"][2]
    return m


def model(text, el="L9", af=2, aw=6, th=1, axis_mult=1, method=None, extra=""):
    text = re.sub(r'element = "L\d+", origin', f'element = "{el}", origin', text)
    text = re.sub(r"along_flange = \d+, along_web = \d+, through = \d+",
                  f"along_flange = {af}, along_web = {aw}, through = {th}", text)
    if axis_mult != 1:
        text = re.sub(r"elements = (\d+)", lambda mo: f"elements = {int(mo.group(1)) * axis_mult}", text)
    if method:
        text = text.replace('name = "load"\n', f'name = "load"\nmethod = "{method}"\n')
    return text + extra


def run(name, text):
    os.makedirs(OUT, exist_ok=True)
    path = os.path.join(OUT, name + ".toml")
    open(path, "w").write(text)
    out = os.path.join(OUT, name)
    p = subprocess.run([CUFEM, "run", path, "--threads", "1", "--out", out, "--force", "--quiet"],
                       capture_output=True, text=True)
    if p.returncode != 0:
        print(name, "failed:", p.stderr[-600:])
        return None
    d = json.load(open(os.path.join(out, "summary.json")))
    u = {q["name"]: q["u"] for q in d["probes"]}
    f = None
    for c in d.get("contact", []):
        if c["name"] == "load":
            f = c.get("full_structure_force", c.get("force"))
    return d["dof"], measures(u, f)


def row(label, dof, m, ref=None):
    cells = [label, str(dof)]
    for k in ["force"] + [f"twist_{y}" for y in STATIONS] + ["flange_325", "uz_wt"]:
        v = m[k]
        if isinstance(v, list):
            v = v[2]
        if ref is None:
            cells.append(f"{v:.5g}")
        else:
            r = ref[k][2] if isinstance(ref[k], list) else ref[k]
            cells.append(f"{v:.4g} ({100 * (v / r - 1):+.1f}%)")
    return " | ".join(cells)


HEADER = "mesh | DOF | force z N | twist y=25 | 100 | 175 | 250 | 325 (rad) | top flange rot 325 | u_z web top 325"

def nofork(text):
    """The forks replaced by u_x = 0 at the web's bottom corner of each support line only: the
    twist is then held by nothing but the rollers' contact near the section's corners."""
    for y in ("0.025", "0.625"):
        text = text.replace(f'where = {{ y = {y}, region = "web" }}', f"where = {{ y = {y}, x = 0.0, z = 0.0 }}")
    return text


def patch(text):
    """The loading roller replaced by a traction on the web's top face over the last axis element
    before mid-span (y in [0.3097, 0.325]; the faces wholly inside the band are loaded)."""
    i = text.index('[[indenters]]\nname = "load"')
    j = text.index("[[probes]]")
    load = ('[[loads]]\nname = "patch"\nbody = "beam"\n'
            'where = { z = 0.06, x = [0.0, 0.002], y = [0.3097, 0.325] }\ntraction = [0.0, 0.0, -2.209e7]\n\n')
    return text[:i] + load + text[j:]


def plastic(text):
    """Von Mises, sigma_y = 160 MPa, linear hardening H = 700 MPa; the roller moved 3 mm in 10 increments."""
    text = text.replace("poisson_ratio = 0.33\n", "poisson_ratio = 0.33\n[materials.plasticity]\nhardening = \"linear\"\n"
                        "yield_stress = 160e6\nhardening_modulus = 700e6\n")
    text = re.sub(r"increments = \d+\n", "increments = 10\n", text, count=1)
    return text.replace("displacement = [0.0, 0.0, -1e-3]", "displacement = [0.0, 0.0, -3e-3]")


SECTION = [("L9 2/6/1 x1", {}), ("L16 2/6/1 x1", {"el": "L16"}), ("L9 4/12/1 x1", {"af": 4, "aw": 12}),
           ("L9 2/6/2 x1", {"th": 2}), ("L9 2/6/1 x2", {"axis_mult": 2}),
           ("L9 4/12/2 x2", {"af": 4, "aw": 12, "th": 2, "axis_mult": 2}),
           ("L16 4/12/2 x2", {"el": "L16", "af": 4, "aw": 12, "th": 2, "axis_mult": 2})]
AXIS = [("L9 2/6/1 x4", {"axis_mult": 4}), ("L9 2/6/1 x8", {"axis_mult": 8}),
        ("L9 4/12/2 x4", {"af": 4, "aw": 12, "th": 2, "axis_mult": 4})]
CONTACT = [("L9 2/6/1 x1 surface", {"method": "surface"}),
           ("L16 4/12/2 x2 surface", {"el": "L16", "af": 4, "aw": 12, "th": 2, "axis_mult": 2, "method": "surface"})]
STUDIES = {
    "fork": (lambda t: t, SECTION + CONTACT + [("L9 4/12/1 x2", {"af": 4, "aw": 12, "axis_mult": 2})]),
    "nofork": (nofork, SECTION + AXIS + CONTACT),
    "patch": (lambda t: patch(nofork(t)), [SECTION[0]] + AXIS[:2]),
    "plastic": (plastic, SECTION + [AXIS[0]]),
}


def twin(folder):
    """Both sides of a `cufem verify` of the half model (its verify/table.json): (DOF, measures)
    of CalculiX and of cufem; forces doubled to the full structure."""
    t = json.load(open(os.path.join(folder, "verify", "table.json")))
    sides = {}
    for side in ("ccx", "cufem"):
        u = {}
        for p in t["probes"]:
            if p["quantity"] in ("u_x", "u_y", "u_z"):
                u.setdefault(p["probe"], [0.0, 0.0, 0.0])["xyz".index(p["quantity"][-1])] = p[side]
        f = next(r[side] for r in t["resultants"] if r["name"] == "load")
        sides[side] = (t["cost"][side + "_dof"], measures(u, [2 * c for c in f]))
    return sides


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) > 1 else "fork"
    text = open(BASE).read()
    if what in STUDIES:
        change, meshes = STUDIES[what]
        print(f"## python3 bench/channel_roller_study.py {what}")
        print(HEADER + ("   (patch: force = the applied traction's resultant)" if what == "patch" else ""))
        for label, kw in meshes:
            name = what + "_" + re.sub(r"\W+", "_", label)
            r = run(name, change(model(text, **kw)))
            if r:
                dof, m = r
                if what == "patch":
                    d = json.load(open(os.path.join(OUT, name, "summary.json")))
                    m["force"] = 2 * d["applied_load"][2]
                print(row(label, dof, m), flush=True)
    elif what == "twin":
        sides = twin(sys.argv[2])
        print(f"## {sys.argv[2]}")
        print(HEADER)
        print(row("CalculiX", *sides["ccx"]))
        print(row("cufem", *sides["cufem"], ref=sides["ccx"][1]))
    elif what == "model":
        # the model file of a study and mesh, for `cufem verify`:
        # python3 bench/channel_roller_study.py model nofork "L9 2/6/1 x1" > out/roller/nofork.toml
        change, meshes = STUDIES[sys.argv[2]]
        kw = dict(meshes)[sys.argv[3]] if len(sys.argv) > 3 else {}
        print(change(model(text, **kw)), end="")
