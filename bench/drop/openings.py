#!/usr/bin/env python3
"""Issue 48: openings, slides and tractions of the cohesive interfaces over
time, at mid-span, quarter-span and the support, from the frames of a run
(analysis.output_interval) and its result.vtu (d_interface at the end).

    python3 bench/drop/openings.py OUT_FOLDER
"""
import glob, sys, re
sys.path.insert(0, __import__("os").path.dirname(__import__("os").path.abspath(__file__)))
import vtu
out = sys.argv[1]
zs = [0.0005, 0.001, 0.0015]
N, S, GI, GII = 10e6, 16.3e6, 300.0, 800.0
print("delta_f: mode I %.1f um, mode II %.1f um" % (2 * GI / N * 1e6, 2 * GII / S * 1e6))
pvd = open(out + "/frames.pvd").read()
times = dict((f, float(t)) for t, f in re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', pvd))
files = sorted(glob.glob(out + "/frame_*.vtu")) + [out + "/result.vtu"]
for f in files:
    d = vtu.read(f)
    r = vtu.interface_jumps(d, zs)
    t = times.get(f.split("/")[-1], float("nan"))
    line = []
    for z in zs:
        rows = r[z]
        ys = {}
        for (x, y), (j, szz, syz, di) in rows.items():
            ys.setdefault(y, []).append((j, szz, syz, di))
        def at(yq):
            y = min(ys, key=lambda v: abs(v - yq))
            j, szz, syz, di = ys[y][0]
            return "op%6.2f sl%6.2f szz%6.1f syz%6.1f%s" % (j[2] * 1e6, j[1] * 1e6, szz / 1e6, syz / 1e6, "" if di is None else " d%.3f" % di)
        maxop = max(v[0][2] for vs in ys.values() for v in vs) * 1e6
        maxsl = max(abs(v[0][1]) for vs in ys.values() for v in vs) * 1e6
        maxszz = max(v[1] for vs in ys.values() for v in vs) / 1e6
        maxsyz = max(abs(v[2]) for vs in ys.values() for v in vs) / 1e6
        line.append("z=%.1fmm max op %.2f sl %.2f um  szz %.1f syz %.1f MPa | mid %s | q %s | end %s" % (z * 1e3, maxop, maxsl, maxszz, maxsyz, at(0.025), at(0.0125), at(0.0)))
    print("t=%.3f ms" % (t * 1e3))
    for l in line:
        print("   " + l)
