"""Every output file stays valid for its readers (issue 24, "What to build"
item 2): `title = "bell \\u0007 only"` once gave a result.vtu that expat (and
so VTK and ParaView) rejects. A run whose title holds control characters,
quotes, markup, `-->` and non-ASCII text, and whose names use every
character a name may hold (letters, digits, `_`, `-`, `.`), must give VTUs
that expat parses, CSVs whose every row has the header's column count, and a
summary.json that `json` reads back with the title intact."""

import csv
import json
import xml.parsers.expat

from conftest import EXAMPLES

# the title as TOML escapes it, and as Python reads it
TITLE_TOML = (
    r'"bell \u0007 nul \u0000 esc \u001b ff \f vt \u000b del \u007f quote \" apos '
    r"' <tag a=\"1\"> & &amp; --> --- <!-- ]]> end- \uFFFE \uFFFF ü 日本 \U0001F600"
    '"'
)
TITLE = (
    "bell \x07 nul \x00 esc \x1b ff \x0c vt \x0b del \x7f quote \" apos ' <tag a=\"1\"> & &amp; "
    "--> --- <!-- ]]> end- \ufffe \uffff ü 日本 \U0001F600"
)
# names: the example's names → names using every allowed kind of character
NAMES = {
    '"block"': '"block-1.b"',
    '"punch"': '"punch_2.x-y"',
    '"top"': '"top.3"',
    '"bottom"': '"Bottom_4-z"',
    '"edge"': '"e.5"',
}


def hostile_model(tmp_path):
    text = (EXAMPLES / "block_indentation.toml").read_text()
    lines = text.splitlines()
    k = next(i for i, l in enumerate(lines) if l.startswith("title = "))
    lines[k] = "title = " + TITLE_TOML
    text = "\n".join(lines) + "\n"
    for old, new in NAMES.items():
        assert old in text, old
        text = text.replace(old, new)
    assert 'recovery = "projection"' in text
    text = text.replace('recovery = "projection"', 'recovery = "projection"\ngauss_points = true')
    path = tmp_path / "hostile.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_outputs_parse_with_independent_readers(cli, tmp_path):
    out = tmp_path / "out"
    cli("run", hostile_model(tmp_path), "--out", out, "--threads", "1", "--quiet")
    files = sorted(p.name for p in out.iterdir())

    # every VTU: well-formed XML for expat (VTK's own parser)
    vtus = [f for f in files if f.endswith(".vtu")]
    assert {"result.vtu", "gauss.vtu", "contact_punch_2.x-y.vtu"} <= set(vtus), files
    for name in vtus:
        data = (out / name).read_bytes()
        parser = xml.parsers.expat.ParserCreate()
        try:
            parser.Parse(data, True)
        except xml.parsers.expat.ExpatError as e:
            line = data.splitlines()[e.lineno - 1][:200]
            raise AssertionError(f"{name}: {e}: {line!r}") from e
    # the title is in the VTU's comment, its control characters shown as text
    head = (out / "result.vtu").read_text(encoding="utf-8").splitlines()[1]
    assert "\\u{7}" in head and "日本" in head, head

    # every CSV: one header, every row with its column count, numbers parse
    csvs = [f for f in files if f.endswith(".csv")]
    expected = {"history_punch_2.x-y.csv", "history_Bottom_4-z.csv", "contact_punch_2.x-y.csv", "line_top.3.csv"}
    assert expected <= set(csvs), files
    for name in csvs:
        with open(out / name, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
        assert len(rows) >= 2, name
        width = len(rows[0])
        # error_history.csv names each state (`state`, `name`): text columns
        text = {"state", "name"} if name == "error_history.csv" else set()
        for i, row in enumerate(rows[1:], start=2):
            assert len(row) == width, f"{name} row {i}: {len(row)} columns, header has {width}"
            for column, cell in zip(rows[0], row):
                if cell and column not in text:
                    float(cell)

    # summary.json: JSON, with the title and the names as given
    with open(out / "summary.json", encoding="utf-8") as f:
        summary = json.load(f)
    assert summary["title"] == TITLE
    assert summary["probes"][0]["name"] == "e.5"
    assert {r["name"] for r in summary["reactions"]} == {"Bottom_4-z"}
    assert "punch_2.x-y" in json.dumps(summary["contact"])


def test_names_that_cannot_be_file_names_are_refused(cli, tmp_path):
    model = hostile_model(tmp_path).read_text(encoding="utf-8")
    for bad in [r"top\u0007", "top/x", r"top\\x", "top ü"]:
        path = tmp_path / "bad.toml"
        path.write_text(model.replace('"top.3"', f'"{bad}"'), encoding="utf-8")
        p = cli("check", path, check=False)
        assert p.returncode == 1, p.stderr
        assert "lines[0].name" in p.stderr and "letters, digits" in p.stderr, p.stderr
