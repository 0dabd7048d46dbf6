#!/usr/bin/env python3
"""Compares the summary.json of two runs of the shipped paper examples
(docs/performance.md: before/after a change must agree within 0.5 %).

Usage: bench/compare_summaries.py PREFIX_A PREFIX_B [EXAMPLE ...] — the output folder of
example E is PREFIX + E (bench/examples.sh leaves its last run of each in
`out/bench_E`; run the other binary with `--out /tmp/ob_E` and pass
`/tmp/ob_ out/bench_`). Prints per example
the largest difference of probe values, contact forces and the largest
peeq, each vector compared against its largest component, and the largest
difference of the reactions in newtons."""
import json, sys
exs=sys.argv[3:] or "block_indentation bending_compact_4L9 bending_compact_16L9 bending_tube_20L9 bending_tube_28L9 cantilevers_contact".split()
da, db = sys.argv[1], sys.argv[2]
def flat(x, pre=""):
    out={}
    if isinstance(x, dict):
        for k,v in x.items(): out.update(flat(v, pre+"/"+str(k)))
    elif isinstance(x, list):
        for i,v in enumerate(x): out.update(flat(v, pre+"/"+str(i)))
    elif isinstance(x,(int,float)) and not isinstance(x,bool): out[pre]=float(x)
    return out
for ex in exs:
    a=json.load(open(f"{da}{ex}/summary.json")); b=json.load(open(f"{db}{ex}/summary.json"))
    res=[]
    for key in ("probes","contact","max_peeq"):
        fa=flat(a.get(key),key); fb=flat(b.get(key),key)
        fa={k:v for k,v in fa.items() if not any(s in k for s in ("area","node","gap","penetration","count","active","iterations","position","point"))}
        for k,v in fa.items():
            parts=k.split("/")
            # a vector quantity (u, stress, force) is compared against its largest component
            grp=[kk for kk in fa if kk.split("/")[:-1]==parts[:-1]] if parts[-1].isdigit() else [k]
            scale=max(abs(fa[g]) for g in grp) or 1
            res.append((abs(fb[k]-v)/scale,k,v,fb[k]))
    res.sort(reverse=True)
    load=max(abs(v) for k,v in flat(a.get("contact"),"c").items() if "/force/" in k) if a.get("contact") else 1.0
    ra=flat(a["reactions"]); rb=flat(b["reactions"])
    rd=max([abs(rb[k]-ra[k]) for k in ra] or [0])
    print(f"{ex:24s} worst probe/contact/peeq diff {res[0][0]:.1e} ({res[0][1]}); reactions differ by {rd:.1e} N of load {load:.3g} N")
