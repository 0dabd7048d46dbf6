#!/usr/bin/env python3
"""Where runs of bench/drop/damage_study.py part ways (issue 48).

Reads the energy.csv of each case (bench/drop/cases/out_<CASE>/, written by
damage_study.py) and prints, against the first case named, the first time at
which the energy dissipated by delamination differs by more than 0.1 % of the
first case's final value, and each case's final delamination and striker
energies:

    python3 bench/drop/split.py roll_a60_g1600_800 roll_a60_g1600_800_k10 ...
"""
import bisect, csv, os, sys

HERE = os.path.dirname(os.path.abspath(__file__))


def history(case):
    path = os.path.join(HERE, "cases", "out_" + case, "energy.csv")
    rows = list(csv.DictReader(open(path)))
    return [(float(r["time_s"]), float(r["delamination_J"]), float(r["impactors_J"])) for r in rows]


def value_at(rows, times, t):
    # the last row at or before t (the cases' steps need not coincide after a cutback)
    return rows[max(bisect.bisect_right(times, t + 1e-12) - 1, 0)]


if __name__ == "__main__":
    cases = sys.argv[1:]
    if len(cases) < 2:
        sys.exit(__doc__)
    base = history(cases[0])
    times = [r[0] for r in base]
    scale = base[-1][1]
    print("case, parts at (ms), delamination at 6 ms (J), striker at 6 ms (J)")
    print("%s, -, %.4f, %.4f" % (cases[0], base[-1][1], base[-1][2]))
    for case in cases[1:]:
        rows = history(case)
        parts = next((t for t, d, _ in rows if abs(d - value_at(base, times, t)[1]) > 1e-3 * scale), None)
        at = "never" if parts is None else "%.3f" % (parts * 1e3)
        print("%s, %s, %.4f, %.4f" % (case, at, rows[-1][1], rows[-1][2]))
