#!/usr/bin/env python3
"""The mesh convergence study of bench/channel_twist.toml (docs/performance.md, "The large-rotation
channel: equal accuracy"): meshes of the channel on both sides, each compared along the load path
with a 3D reference.

  python3 bench/channel_twist_study.py reference        # the 3D reference: C3D20R twin of 4 L9 along
                                                         # each flange, 8 along the web, 16 B4 (about 20 min)
  python3 bench/channel_twist_study.py cufem [NAME...]   # cufem run --threads 1 of the beam meshes
  python3 bench/channel_twist_study.py ccx [NAME...]     # cufem verify --refine 1 --threads 1 of the 3D meshes
  python3 bench/channel_twist_study.py table             # every finished run against the reference
  python3 bench/channel_twist_study.py ratio [N]         # N times (default 2), back to back, one thread
                                                         # each: CalculiX on its cheapest mesh within 3 %
                                                         # (3d_L4_2_4_6_graded), cufem run of the bench file

A mesh is (section element, along_flange, along_web, through, B4 elements, last/first length ratio[,
formulation]); the bench file's own formulation is dropped, and a name ending in `_assumed` sets the body's `formulation = "assumed_shear"`.
The 3D meshes are the CalculiX twins of CUF meshes (one hexahedron per Lagrange interval): an L4
section gives one C3D20R through each wall. The measure is verify's: the largest |u - u_3D| over the
20 increments, % of the reference's peak |u_3D|, at the top flange tip (u_x, u_z) and over all three
probes (u_x, u_z); the twist is the angle of the chord between the flange tips' probes at λ = 1.
Runs go to out/channel_study/ (needs target/release/cufem, and ccx for the 3D meshes)."""
import csv, json, math, os, re, subprocess, sys, time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CUFEM = os.path.join(ROOT, "target", "release", "cufem")
OUT = os.path.join(ROOT, "out", "channel_study")
REFERENCE = ("ref_3d", ("L9", 4, 8, 1, 16, 1))
CUFEM_MESHES = {
    "L9_2_4_12": ("L9", 2, 4, 1, 12, 1),
    "L9_2_4_12_through2": ("L9", 2, 4, 2, 12, 1),
    "L9_3_6_12": ("L9", 3, 6, 1, 12, 1),
    "L9_2_4_24": ("L9", 2, 4, 1, 24, 1),
    "L9_2_4_48": ("L9", 2, 4, 1, 48, 1),
    "L9_4_8_24": ("L9", 4, 8, 1, 24, 1),
    "L9_8_16_24": ("L9", 8, 16, 1, 24, 1),
    "L16_2_4_12": ("L16", 2, 4, 1, 12, 1),
    "L16_2_4_24": ("L16", 2, 4, 1, 24, 1),
    "L16_3_6_36": ("L16", 3, 6, 1, 36, 1),
    "L9_2_4_12_graded": ("L9", 2, 4, 1, 12, 10),
    "L9_4_8_12_graded": ("L9", 4, 8, 1, 12, 10),
    "L9_6_12_12_graded": ("L9", 6, 12, 1, 12, 10),
    "L16_2_4_10_graded": ("L16", 2, 4, 1, 10, 10),
    "L16_2_4_12_graded": ("L16", 2, 4, 1, 12, 10),
    "L16_3_6_12_graded": ("L16", 3, 6, 1, 12, 10),
    "L9_3_6_12_graded": ("L9", 3, 6, 1, 12, 10),
    "L9_2_4_12_graded_assumed": ("L9", 2, 4, 1, 12, 10, "assumed_shear"),
    "L9_3_6_12_graded_assumed": ("L9", 3, 6, 1, 12, 10, "assumed_shear"),
    "L9_2_4_16_graded_assumed": ("L9", 2, 4, 1, 16, 10, "assumed_shear"),
    "L9_4_8_12_graded_assumed": ("L9", 4, 8, 1, 12, 10, "assumed_shear"),
    "L16_2_4_12_graded_assumed": ("L16", 2, 4, 1, 12, 10, "assumed_shear"),
    "L9_3_6_10_graded_assumed": ("L9", 3, 6, 1, 10, 10, "assumed_shear"),
    "L9_3_4_12_graded_assumed": ("L9", 3, 4, 1, 12, 10, "assumed_shear"),
    "L16_2_4_10_graded_assumed": ("L16", 2, 4, 1, 10, 10, "assumed_shear"),
}
CCX_MESHES = {
    "3d_L9_2_4_12": ("L9", 2, 4, 1, 12, 1),
    "3d_L9_1_2_12": ("L9", 1, 2, 1, 12, 1),
    "3d_L4_2_4_12": ("L4", 2, 4, 1, 12, 1),
    "3d_L4_2_4_8": ("L4", 2, 4, 1, 8, 1),
    "3d_L4_2_4_8_graded": ("L4", 2, 4, 1, 8, 10),
    "3d_L4_2_4_6_graded": ("L4", 2, 4, 1, 6, 10),
    "3d_L9_3_6_12_graded": ("L9", 3, 6, 1, 12, 10),
}
PROBES = ["top_flange_tip", "bottom_flange_tip", "web_middle"]


def model(mesh):
    """The text of bench/channel_twist.toml with this mesh."""
    el, af, aw, th, n, ratio = mesh[:6]
    text = open(os.path.join(ROOT, "bench", "channel_twist.toml")).read()
    text, k1 = re.subn(r'element = "L\d+", origin', f'element = "{el}", origin', text)
    text, k2 = re.subn(r"along_flange = \d+, along_web = \d+, through = \d+",
                       f"along_flange = {af}, along_web = {aw}, through = {th}", text)
    text, k3 = re.subn(r"axis = \{[^}]*\}",
                       f'axis = {{ element = "B4", from = 0.0, to = 1.0, elements = {n}, ratio = {float(ratio)} }}', text)
    assert (k1, k2, k3) == (1, 1, 1), "bench/channel_twist.toml: section or axis line not found"
    text = re.sub(r'\nformulation = "[a-z_]+"', "", text)
    if len(mesh) > 6:
        text, k4 = re.subn(r"\nsection = ", f'\nformulation = "{mesh[6]}"\nsection = ', text)
        assert k4 == 1, "bench/channel_twist.toml: one section line"
    return text


CHEAPEST_3D = "3d_L4_2_4_6_graded"


def ratio(times):
    """The equal-accuracy ratio: CalculiX's wall time (verify's, ccx alone) on its cheapest mesh
    within 3 % over the wall time of `cufem run bench/channel_twist.toml --threads 1` (start-up and
    output included), measured back to back."""
    for _ in range(times):
        run(CHEAPEST_3D, CCX_MESHES[CHEAPEST_3D], verify=True)
        ccx = json.load(open(os.path.join(OUT, CHEAPEST_3D, "verify", "table.json")))["cost"]["ccx_time_s"]
        t0 = time.monotonic()
        subprocess.run([CUFEM, "run", os.path.join(ROOT, "bench", "channel_twist.toml"), "--threads", "1",
                        "--out", os.path.join(OUT, "bench"), "--force", "--quiet"], check=True, capture_output=True)
        cufem = time.monotonic() - t0
        print(f"CalculiX {ccx:.1f} s, cufem {cufem:.1f} s: {ccx / cufem:.2f}x (load average {os.getloadavg()[0]:.1f})")


def run(name, mesh, verify):
    os.makedirs(OUT, exist_ok=True)
    path = os.path.join(OUT, name + ".toml")
    open(path, "w").write(model(mesh))
    out = os.path.join(OUT, name)
    cmd = [CUFEM, "verify" if verify else "run", path, "--threads", "1", "--out", out, "--force", "--quiet"]
    if verify:
        cmd[3:3] = ["--refine", "1"]
    t0 = time.monotonic()
    p = subprocess.run(cmd, capture_output=True, text=True)
    print(f"{name}: exit {p.returncode}, {time.monotonic() - t0:.1f} s wall", flush=True)
    if verify:
        print("\n".join(p.stdout.splitlines()[:2]))


def history(name, ccx):
    """{λ: {probe.u_c: value}} of a finished run (ccx: its CalculiX side)."""
    d = os.path.join(OUT, name)
    h = {}
    if ccx:
        for p in PROBES:
            f = os.path.join(d, "verify", f"probe_history_{p}.csv")
            if not os.path.exists(f):
                return None
            for r in csv.DictReader(open(f)):
                for c in "xz":
                    h.setdefault(round(float(r["lambda"]), 6), {})[f"{p}.u_{c}"] = float(r[f"ccx_u_{c}"])
        return h
    f = os.path.join(d, "history_probes.csv")
    if not os.path.exists(f):
        return None
    for r in csv.DictReader(open(f)):
        h[round(float(r["lambda"]), 6)] = {k: float(v) for k, v in r.items() if k[-4:-1] == ".u_"}
    return h


def twist(h):
    end = h[max(h)]
    dx = end["top_flange_tip.u_x"] - end["bottom_flange_tip.u_x"]
    dz = 0.097 + end["top_flange_tip.u_z"] - end["bottom_flange_tip.u_z"]
    return math.degrees(math.atan2(dx, dz))


def table():
    ref = history(REFERENCE[0], True)
    if ref is None:
        sys.exit("no reference yet: python3 bench/channel_twist_study.py reference")
    peak = {k: max(abs(v[k]) for v in ref.values()) for k in ref[max(ref)]}

    def diff(h, keys):
        return max(abs(h[l][k] - ref[l][k]) / peak[k] * 100 for k in keys for l in h if l in ref)

    print(f"{'mesh':24} {'DOF':>7} {'twist':>7} {'top u_x %':>9} {'top u_z %':>9} {'all %':>6}")
    rows = [(REFERENCE[0], True)] + [(n, False) for n in CUFEM_MESHES] + [(n, True) for n in CCX_MESHES]
    for name, ccx in rows:
        h = history(name, ccx)
        if h is None:
            continue
        if ccx:
            dof = json.load(open(os.path.join(OUT, name, "verify", "table.json")))["cost"]["ccx_dof"]
        else:
            dof = json.load(open(os.path.join(OUT, name, "summary.json")))["dof"]
        all_keys = [f"{p}.u_{c}" for p in PROBES for c in "xz"]
        print(f"{name:24} {dof:>7} {twist(h):7.2f} {diff(h, ['top_flange_tip.u_x']):9.2f} "
              f"{diff(h, ['top_flange_tip.u_z']):9.2f} {diff(h, all_keys):6.2f}")


if __name__ == "__main__":
    what, names = (sys.argv[1:2] or ["table"])[0], sys.argv[2:]
    if what == "ratio":
        ratio(int(names[0]) if names else 2)
        sys.exit()
    if what == "reference":
        run(*REFERENCE, verify=True)
    elif what in ("cufem", "ccx"):
        meshes = CUFEM_MESHES if what == "cufem" else CCX_MESHES
        for name in names or meshes:
            run(name, meshes[name], verify=what == "ccx")
    table()
