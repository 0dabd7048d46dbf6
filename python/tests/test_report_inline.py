"""The run's report.html inline in Jupyter (`Results._repr_html_`): an
iframe whose `srcdoc` is the page the CLI writes, and the matplotlib charts
of `Results.plot_*` are the report's charts (same x column, same series)."""

import json
from html.parser import HTMLParser

import pytest

import cufem
from conftest import EXAMPLES
from cufem.plots import chart_columns

# a static run with contacts, lines and probes; a transient one (energy, frames)
EXAMPLES_SHOWN = ["bending_compact_4L9", "rod_impact"]


class Iframes(HTMLParser):
    """The attributes of every <iframe>, unescaped as a browser reads them."""

    def __init__(self, text):
        super().__init__()
        self.found = []
        self.feed(text)
        self.close()

    def handle_starttag(self, tag, attrs):
        if tag == "iframe":
            self.found.append(dict(attrs))


def page_data(page):
    """The JSON data report.html carries (its `cufem-data` script)."""
    text = page.split('<script type="application/json" id="cufem-data">', 1)[1].split("</script>", 1)[0]
    return json.loads(text)


@pytest.mark.parametrize("name", EXAMPLES_SHOWN)
def test_repr_html_is_the_report_page_in_an_iframe(name, memory_runs, cli_runs, tmp_path):
    results = memory_runs(name)
    frames = Iframes(results._repr_html_()).found
    assert len(frames) == 1
    frame = frames[0]
    # the page, whole, after the browser unescapes the attribute
    results.write(tmp_path / "out")
    written = (tmp_path / "out" / "report.html").read_text(encoding="utf-8")
    assert frame["srcdoc"] == written == results.report_html()
    assert frame["sandbox"] == "allow-scripts" and "height: 720px" in frame["style"]
    assert "height: 900px" in results.report_iframe(900)
    # the CLI's page for the same model: the same but for the wall time
    # its results table prints
    cli = (cli_runs(name) / "report.html").read_text(encoding="utf-8")
    ours, theirs = page_data(written), page_data(cli)
    ours.pop("results"), theirs.pop("results")
    assert ours == theirs
    assert cli.split('id="cufem-data">')[0] == written.split('id="cufem-data">')[0]


@pytest.mark.parametrize("name", EXAMPLES_SHOWN)
def test_the_plots_are_the_reports_charts(name, memory_runs):
    results = memory_runs(name)
    charts = page_data(results.report_html())["charts"]
    charted = [n for n in results.table_names() if not n.startswith("contact_")]
    # a chart for every table but the contact points (the report's order:
    # histories before lines)
    assert sorted(c["name"] for c in charts) == sorted(charted)
    for c in charts:
        assert chart_columns(c["name"], results.table(c["name"])) == (c["x"], c["series"]), c["name"]


def test_without_a_report_the_summary_line(tmp_path):
    d = cufem.Model.from_file(EXAMPLES / "cantilever_timoshenko.toml").to_dict()
    d.setdefault("output", {})["report"] = False
    results = cufem.Model.from_dict(d, base=EXAMPLES).run(threads=1, quiet=True)
    assert results.report_html() is None
    shown = results._repr_html_()
    assert not Iframes(shown).found
    assert shown.startswith("<pre>&lt;cufem.Results ") and "output.report = false" in shown
