"""Indentation-depth sweep of the block (paper §4.1) from Python.

Runs examples/block_indentation.toml at a few punch depths and plots the
punch force and the equivalent plastic strain at the punch edge and centre
against the depth (with the force–depth history of the deepest run).

    pip install "./python[all]"      # or "./python[plot]": matplotlib
    python examples/python/block_indentation_sweep.py [--out out/python]
"""

import argparse
from pathlib import Path

import cufem

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ModuleNotFoundError as e:
    raise SystemExit(f'{e.name} is not installed: pip install "./python[all]" (or "./python[plot]")') from e
from cufem.model import set_path

HERE = Path(__file__).resolve().parent
DEPTHS_MM = [0.25, 0.5, 0.75, 1.0]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="out/python", help="folder for the plots (default out/python)")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    model = cufem.Model.from_file(HERE.parent / "block_indentation.toml")
    base = model.to_dict()
    rows = []
    for depth in DEPTHS_MM:
        d = set_path(base, "indenters.0.displacement.2", -depth * 1e-3)
        # base=: relative paths in the model (a gmsh section) start at its folder, not the current one
        results = cufem.Model.from_dict(d, base=model.base).run(quiet=True)
        s = results.summary
        force = -next(c for c in s["contact"] if c["name"] == "punch")["force"][2]
        peeq = {p["name"]: p["peeq"] for p in s["probes"]}
        rows.append((depth, force, peeq["edge"], peeq["centre"]))
        print(f"depth {depth:.2f} mm: force {force / 1e6:.4f} MN, peeq edge {peeq['edge']:.4f}, centre {peeq['centre']:.4f} ({s['status']}, {s['wall_time_s']:.1f} s)")
    history = results.history("punch")  # the deepest run, increment by increment

    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    depth = [0.0, *(-history["d_z"] * 1e3)]
    force = [0.0, *(-history["f_z"] / 1e6)]
    a.plot(depth, force, "-", color="0.6", label="history of the 1 mm run")
    a.plot([r[0] for r in rows], [r[1] / 1e6 for r in rows], "o", label="sweep")
    a.set(xlabel="punch depth [mm]", ylabel="punch force [MN]", title="force–depth")
    a.legend()
    b.plot([r[0] for r in rows], [r[2] for r in rows], "o-", label="edge (0.2, 0.05, 0.3)")
    b.plot([r[0] for r in rows], [r[3] for r in rows], "s-", label="centre (0.25, 0.05, 0.3)")
    b.set(xlabel="punch depth [mm]", ylabel="peeq [-]", title="equivalent plastic strain–depth")
    b.legend()
    fig.suptitle("Block indentation, 1 B4 × 108 L9 (cufem)")
    fig.tight_layout()
    path = out / "block_indentation_sweep.png"
    fig.savefig(path, dpi=120)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
