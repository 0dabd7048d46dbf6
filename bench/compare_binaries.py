#!/usr/bin/env python3
"""Same-run timing of two cufem binaries on the paper examples (one thread,
runs interleaved, the order alternating between repeats): median wall
time per example and the ratio new/old.

Usage: bench/compare_binaries.py OLD_BINARY NEW_BINARY [REPEATS]"""
import subprocess, time, statistics, sys, os, tempfile
exs="block_indentation bending_compact_4L9 bending_compact_16L9 bending_tube_20L9 bending_tube_28L9 cantilevers_contact cantilevers_contact_friction".split()
bins={"old":sys.argv[1],"new":sys.argv[2]}
repeats=int(sys.argv[3]) if len(sys.argv)>3 else 3
root=os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
tmp=tempfile.mkdtemp(prefix="cufem-timing-")
t={(b,e):[] for b in bins for e in exs}
for r in range(repeats):
    for e in exs:
        for b,path in (bins.items() if r%2==0 else reversed(list(bins.items()))):
            s=time.perf_counter()
            subprocess.run([path,"run",f"{root}/examples/{e}.toml","--out",f"{tmp}/{b}_{e}","--force","--quiet","--threads","1"],check=True,stdout=subprocess.DEVNULL)
            t[(b,e)].append(time.perf_counter()-s)
tot={"old":0,"new":0}
for e in exs:
    mo=statistics.median(t[("old",e)]); mn=statistics.median(t[("new",e)])
    tot["old"]+=mo; tot["new"]+=mn
    print(f"{e:32s} old {mo:7.2f} s  new {mn:7.2f} s  ratio {mn/mo:.3f}")
print(f"{'total':32s} old {tot['old']:7.2f} s  new {tot['new']:7.2f} s  ratio {tot['new']/tot['old']:.3f}")
