#!/usr/bin/env python3
"""What report.html costs (issue 51): every shipped example run by BIN,
one thread, with `output.report = false` and with it on (the default),
alternately, REPEAT times each (default 3); prints each example's CPU time
(user + system of the process, the smallest of the repeats: less sensitive
than wall time to other processes on a shared machine) both ways, the
ratio, and report.html's size.

usage: python3 bench/report_overhead.py BIN OUTDIR [--repeat N] [EXAMPLE ...]
"""
import pathlib
import re
import resource
import signal
import subprocess
import sys

bin_, out = pathlib.Path(sys.argv[1]).resolve(), pathlib.Path(sys.argv[2]).resolve()
root = pathlib.Path(__file__).resolve().parent.parent
args = sys.argv[3:]
repeat = 3
if args[:1] == ["--repeat"]:
    repeat, args = int(args[1]), args[2:]
examples = [pathlib.Path(e).resolve() for e in args] or sorted((root / "examples").glob("*.toml"))
out.mkdir(parents=True, exist_ok=True)
# a kill still removes the model copy (the finally below)
signal.signal(signal.SIGTERM, lambda *_: sys.exit(1))


def without_report(text: str) -> str:
    """The model file with `report = false` in its [output] table."""
    if re.search(r"^\[output\]\s*$", text, re.M):
        return re.sub(r"^\[output\]\s*$", "[output]\nreport = false", text, count=1, flags=re.M)
    return text + "\n[output]\nreport = false\n"


print(f"{'example':<42} {'off (CPU s)':>11} {'on (CPU s)':>11} {'ratio':>6} {'report.html':>12}")
for ex in examples:
    # the copy sits beside the original: relative paths (sections) still resolve
    off_model = ex.with_name(f"_report_off_{ex.name}")
    off_model.write_text(without_report(ex.read_text()))
    times = [float("inf"), float("inf")]
    try:
        for _ in range(repeat):
            for k, (model, tag) in enumerate(((off_model, "off"), (ex, "on"))):
                folder = out / f"{ex.stem}_{tag}"
                before = resource.getrusage(resource.RUSAGE_CHILDREN)
                subprocess.run([bin_, "run", "--quiet", "--threads", "1", "--force", "--out", folder, model],
                               capture_output=True)
                after = resource.getrusage(resource.RUSAGE_CHILDREN)
                cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
                times[k] = min(times[k], cpu)
    finally:
        off_model.unlink()
    html = out / f"{ex.stem}_on" / "report.html"
    size = html.stat().st_size if html.exists() else 0
    print(f"{ex.stem:<42} {times[0]:>11.3f} {times[1]:>11.3f} {times[1] / times[0]:>6.3f} {size / 1e6:>10.2f} MB",
          flush=True)
