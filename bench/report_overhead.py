#!/usr/bin/env python3
"""What report.html costs (issue 51): every shipped example run by BIN on
one thread, REPEAT times (default 3); for each run the time the run spent on
report.html alone (summary.json `timings.report_s`: gathering its 3D view's
data and writing the page, timed inside the run) against the rest of the
process's wall time (the run without the report). Prints the median of the
ratios (1 + report / rest) per example, its spread, and report.html's size,
then the largest ratio and size over the examples. The ratio does not need
a quiet machine the way two separate runs with and without the report do:
both of its terms come from the same run.

usage: python3 bench/report_overhead.py BIN OUTDIR [--repeat N] [EXAMPLE ...]
exit 1 if any example's median ratio reaches 1.10 or a page 20 MB (issue 51).
"""
import json
import pathlib
import statistics
import subprocess
import sys
import time

bin_, out = pathlib.Path(sys.argv[1]).resolve(), pathlib.Path(sys.argv[2]).resolve()
root = pathlib.Path(__file__).resolve().parent.parent
args = sys.argv[3:]
repeat = 3
if args[:1] == ["--repeat"]:
    repeat, args = int(args[1]), args[2:]
examples = [pathlib.Path(e).resolve() for e in args] or sorted((root / "examples").glob("*.toml"))
out.mkdir(parents=True, exist_ok=True)
LIMIT_RATIO, LIMIT_MB = 1.10, 20.0

print(f"{'example':<42} {'run (s)':>8} {'report (s)':>10} {'ratio':>6} {'spread':>13} {'report.html':>12}")
worst_ratio, worst_size, failed = (0.0, ""), (0.0, ""), []
for ex in examples:
    folder = out / ex.stem
    ratios, walls, reports = [], [], []
    for _ in range(repeat):
        start = time.perf_counter()
        done = subprocess.run([bin_, "run", "--quiet", "--threads", "1", "--force", "--out", folder, ex],
                              capture_output=True)
        wall = time.perf_counter() - start
        if done.returncode not in (0, 2) or not (folder / "summary.json").exists():
            failed.append(ex.stem)
            break
        report = json.loads((folder / "summary.json").read_text())["timings"]["report_s"]
        walls.append(wall)
        reports.append(report)
        ratios.append(1.0 + report / (wall - report))
    if not ratios:
        print(f"{ex.stem:<42} failed (exit {done.returncode})", flush=True)
        continue
    size = (folder / "report.html").stat().st_size / 1e6
    ratio = statistics.median(ratios)
    worst_ratio = max(worst_ratio, (ratio, ex.stem))
    worst_size = max(worst_size, (size, ex.stem))
    print(f"{ex.stem:<42} {statistics.median(walls):>8.3f} {statistics.median(reports):>10.4f} {ratio:>6.3f} "
          f"{min(ratios):>6.3f}–{max(ratios):<6.3f} {size:>9.2f} MB", flush=True)
print(f"largest ratio {worst_ratio[0]:.3f} ({worst_ratio[1]}), largest page {worst_size[0]:.2f} MB ({worst_size[1]})")
if failed or worst_ratio[0] >= LIMIT_RATIO or worst_size[0] >= LIMIT_MB:
    sys.exit(1)
