"""Wall-thickness sweep of the tube in three-point bending (paper §4.2),
run through cufem.study on a local Dask cluster.

Each variant is the tube of examples/bending_tube_20L9.toml with another
wall thickness, solved in 5 increments (a short sweep: about a minute on
two cores). The same call with the Client of a real cluster runs it there.

    pip install "./python[all]"      # dask[distributed] and matplotlib
    python examples/python/tube_wall_thickness_dask.py [--out out/python]
"""

import argparse
from pathlib import Path

import cufem
from cufem import study

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from dask.distributed import Client, LocalCluster
except ModuleNotFoundError as e:
    raise SystemExit(f'{e.name} is not installed: pip install "./python[all]"') from e

HERE = Path(__file__).resolve().parent
THICKNESS_MM = [1.0, 1.5, 2.0]
OUTPUTS = ["status", "max_peeq", "contact.load.f_z", "probe.contact_centre.s_yy", "probe.contact_centre.peeq"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="out/python", help="folder for the table and the plot (default out/python)")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    model = cufem.Model.from_file(HERE.parent / "bending_tube_20L9.toml").to_dict()
    model["solver"]["increments"] = 5
    variants = {"bodies.0.section.thickness": [t * 1e-3 for t in THICKNESS_MM]}
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, Client(cluster) as client:
        df = study.run(model, variants, OUTPUTS, client=client)
    df["roller force [kN]"] = -df["contact.load.f_z"] / 1e3
    print(df.to_string())
    df.to_csv(out / "tube_wall_thickness.csv", index=False)

    t = df["bodies.0.section.thickness"] * 1e3
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    a.plot(t, df["roller force [kN]"], "o-")
    a.set(xlabel="wall thickness [mm]", ylabel="roller force at 0.75 mm [kN]", title="stiffness")
    b.plot(t, df["max_peeq"], "o-", label="largest in the tube")
    b.plot(t, df["probe.contact_centre.peeq"], "s-", label="contact centre")
    b.set(xlabel="wall thickness [mm]", ylabel="peeq [-]", title="plastic strain")
    b.legend()
    fig.suptitle("Tube 30 × 30 mm in three-point bending, 22 B4 × 20 L9 (cufem.study on Dask)")
    fig.tight_layout()
    fig.savefig(out / "tube_wall_thickness.png", dpi=120)
    print(f"wrote {out / 'tube_wall_thickness.csv'} and {out / 'tube_wall_thickness.png'}")


if __name__ == "__main__":
    main()
