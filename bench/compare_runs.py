#!/usr/bin/env python3
"""compare_runs.py BASE NEW — every example's summary.json and CSV files in NEW against BASE.
Numbers equal up to round-off: |a-b| <= 1e-9*max(|a|,|b|) + 1e-12*scale, where scale is the
largest magnitude in the same file (absorbs round-off on values that should be ~0).
Skipped: wall times, timings, memory (measured, not computed) and the files list's paths."""
import json, sys, os, csv, math
SKIP = {'wall_time_s', 'timings', 'memory', 'time_s', 'seconds', 'peak_bytes'}
def walk(a, b, path, out, scale):
    if isinstance(a, dict):
        if not isinstance(b, dict): out.append(f"{path}: type"); return
        for k in set(a) | set(b):
            if k in SKIP: continue
            if k not in a or k not in b: out.append(f"{path}.{k}: missing in {'new' if k in a else 'base'}"); continue
            walk(a[k], b[k], f"{path}.{k}", out, scale)
    elif isinstance(a, list):
        if not isinstance(b, list) or len(a) != len(b): out.append(f"{path}: length {len(a)} vs {len(b) if isinstance(b,list) else b}"); return
        for i, (x, y) in enumerate(zip(a, b)): walk(x, y, f"{path}[{i}]", out, scale)
    elif isinstance(a, (int, float)) and not isinstance(a, bool) and isinstance(b, (int, float)):
        if abs(a - b) > 1e-9 * max(abs(a), abs(b)) + 1e-12 * scale: out.append(f"{path}: {a} vs {b}")
    elif a != b: out.append(f"{path}: {str(a)[:80]!r} vs {str(b)[:80]!r}")
def mag(x):
    if isinstance(x, dict): return max([mag(v) for v in x.values()] + [0])
    if isinstance(x, list): return max([mag(v) for v in x] + [0])
    if isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x): return abs(x)
    return 0
def num(s):
    try: return float(s)
    except ValueError: return s
base, new = sys.argv[1], sys.argv[2]
bad = 0; n = 0
for name in sorted(os.listdir(base)):
    bd, nd = os.path.join(base, name), os.path.join(new, name)
    if not os.path.isdir(bd): continue
    for f in sorted(os.listdir(bd)):
        if not (f.endswith('.json') or f.endswith('.csv')): continue
        n += 1
        if not os.path.exists(os.path.join(nd, f)): print(f"{name}/{f}: missing"); bad += 1; continue
        if f.endswith('.json'):
            a, b = json.load(open(os.path.join(bd, f))), json.load(open(os.path.join(nd, f)))
            if f == 'summary.json':
                for k in ('files',): a.pop(k, None); b.pop(k, None)
        else:
            a = [[num(c) for c in r] for r in csv.reader(open(os.path.join(bd, f)))]
            b = [[num(c) for c in r] for r in csv.reader(open(os.path.join(nd, f)))]
        out = []; walk(a, b, '', out, mag(a))
        if out: bad += 1; print(f"{name}/{f}: {len(out)} differences, e.g."); [print("   ", o) for o in out[:5]]
print(f"{n} files compared, {bad} differ")
sys.exit(1 if bad else 0)
