"""cufem.study: a process pool and a Dask cluster give the same DataFrame."""

import math

import numpy as np
import pandas as pd
import pytest

import cufem
from cufem import study
from conftest import EXAMPLES

MODEL = EXAMPLES / "bending_compact_4L9.toml"
OUTPUTS = ["status", "load_factor", "max_peeq", "probe.contact_centre.s_yy", "contact.load.f_z", "reaction.symmetry_y.f_y"]


def small_model():
    d = cufem.Model.from_file(MODEL).to_dict()
    d["solver"]["increments"] = 4
    return d


# three depths and one deliberately invalid variant (a negative Young's modulus)
VARIANTS = [
    {"indenters.2.displacement.2": -0.25e-3, "materials.0.young_modulus": 68e9},
    {"indenters.2.displacement.2": -0.5e-3, "materials.0.young_modulus": 68e9},
    {"indenters.2.displacement.2": -0.5e-3, "materials.0.young_modulus": -68e9},
    {"indenters.2.displacement.2": -0.75e-3, "materials.0.young_modulus": 68e9},
]


@pytest.fixture(scope="module")
def local():
    return study.run(small_model(), VARIANTS, OUTPUTS, max_workers=2)


def test_a_failed_variant_is_a_row_with_its_message(local):
    assert list(local.columns) == ["indenters.2.displacement.2", "materials.0.young_modulus", "error", *OUTPUTS]
    assert len(local) == 4
    bad = local.iloc[2]
    d = cufem.study.set_path(small_model(), "materials.0.young_modulus", -68e9)
    with pytest.raises(cufem.ModelError) as e:
        cufem.Model.from_dict(d)
    assert bad["error"] == str(e.value)
    assert "young_modulus" in bad["error"]
    assert math.isnan(bad["max_peeq"])
    ok = local.drop(index=2)
    assert ok["error"].isna().all()
    assert (ok["status"] == "converged").all()
    # deeper indentation: larger force and plastic strain
    assert (-ok["contact.load.f_z"]).is_monotonic_increasing
    assert ok["max_peeq"].is_monotonic_increasing


def test_rows_equal_single_runs(local):
    d = cufem.study.set_path(small_model(), "indenters.2.displacement.2", -0.5e-3)
    d = cufem.study.set_path(d, "materials.0.young_modulus", 68e9)
    s = cufem.Model.from_dict(d).run(threads=1, quiet=True).summary
    # to the Newton tolerance (see the Dask test): a separate process may sum
    # in another order and so stop one iteration earlier or later
    assert local.iloc[1]["probe.contact_centre.s_yy"] == pytest.approx(s["probes"][0]["stress"][1], rel=1e-6)
    assert local.iloc[1]["max_peeq"] == pytest.approx(s["max_peeq"], rel=1e-6)


def test_dask_local_cluster_gives_the_same_dataframe(local):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            on_dask = study.run(small_model(), VARIANTS, OUTPUTS, client=client)
    # Equal to the Newton tolerance, not bit for bit. The serial solve's SIMD
    # kernels may sum in an order that depends on where buffers land in
    # memory (faer aligns its reductions to the address), so the Dask threads
    # and the pool's processes see residuals that differ in their 16th
    # digit. Usually that stays round-off (CI once saw 7e-17 relative), but
    # when a residual sits at the convergence threshold one run takes one
    # more Newton iteration than the other, and the results then differ by
    # that iteration's correction: CI saw max_peeq differ by 6e-9 relative.
    # Both are converged answers to the solver's residual and displacement
    # tolerance of 1e-6 (NewtonSettings::default), so that is the equality
    # the test can honestly ask for; it still catches a variant mixed up
    # with another (they differ from the first digit) or a dropped
    # increment (max_peeq moves by percent). A force that is zero by
    # symmetry (a symmetry plane's in-plane reaction) is round-off of the
    # forces around it, so forces are compared to 1e-6 of the largest force
    # in the frame, the residual tolerance's own scale (CI once saw such a
    # reaction at 1.6e-7 against 1.3e-8 N).
    forces = [c for c in local.columns if c.startswith(("reaction.", "contact."))]
    scale = float(np.nanmax(np.abs(local[forces].to_numpy(dtype=float))))
    others = [c for c in local.columns if c not in forces]
    pd.testing.assert_frame_equal(on_dask[others], local[others], check_exact=False, rtol=1e-6, atol=0.0)
    pd.testing.assert_frame_equal(on_dask[forces], local[forces], check_exact=False, rtol=1e-6, atol=1e-6 * scale)


def test_grid_and_bad_paths():
    assert study.grid({"a": [1, 2], "b": [3, 4]}) == [{"a": 1, "b": 3}, {"a": 1, "b": 4}, {"a": 2, "b": 3}, {"a": 2, "b": 4}]
    df = study.run(small_model(), [{"indenters.9.displacement.2": -1e-3}, {"nothing.here": 1}], ["max_peeq"], max_workers=0)
    assert "past the end" in df["error"][0]
    assert "no key nothing" in df["error"][1]


def test_the_study_report_tables_every_variant_and_charts_every_output(local, tmp_path):
    pytest.importorskip("matplotlib")
    path = study.report(local, tmp_path / "report.html", title="depth <and> modulus")
    page = (tmp_path / "report.html").read_text()
    assert path == str(tmp_path / "report.html")
    # self-contained: nothing fetched at view time, no script at all
    for link in ["src=\"http", "href=\"http", "<script", "<link", "@import"]:
        assert link not in page
    assert "<title>depth &lt;and&gt; modulus</title>" in page
    # the table: a header and a row per variant, the failed one with its message
    table = page[page.index("<table"):page.index("</table>")]
    assert table.count("<tr") == len(local) + 1
    from html import escape
    assert escape(local.iloc[2]["error"], quote=False) in table
    # a chart of every numeric output (status is text) against each varied
    # parameter (both take several numeric values), the other parameter's
    # values as separate lines
    numeric = ["load_factor", "max_peeq", "probe.contact_centre.s_yy", "contact.load.f_z", "reaction.symmetry_y.f_y"]
    parameters = ["indenters.2.displacement.2", "materials.0.young_modulus"]
    figures = [(f.split('data-output="')[1].split('"')[0], f.split('data-parameter="')[1].split('"')[0])
               for f in page.split("<figure")[1:]]
    assert figures == [(o, p) for o in numeric for p in parameters]
    assert page.count("<svg") == len(figures)
