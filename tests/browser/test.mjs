// Opens a run's report.html in headless Chromium and checks what it drew
// (issue 51): no console error and no network request; one chart per
// history, line, energy and mode CSV the run wrote, with the series and
// points counted from that CSV; the 3D view's bounding box equal to the
// mesh's in result.vtu (read here from the file, not from the page);
// switching the field and moving the frame slider change the canvas's
// pixels; a modal or buckling run's mode selector changes them from the
// state and from mode to mode; the ply damage d_ft is a field whose range
// is not a single value. Usage: node test.mjs SCREENSHOT_FOLDER RUN_FOLDER...
// (one page per folder, screenshot <folder name>.png)
import { chromium } from "playwright-core";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";

const [shots, ...dirs] = process.argv.slice(2);
const failures = [];
const check = (ok, what) => {
  console.log((ok ? "ok   " : "FAIL ") + what);
  if (!ok) failures.push(what);
};

// the charts the page must draw, from the CSVs (src/io/html: x column, and
// the increment and the counts left out but in history.csv)
const X = { energy: "time_s", modes: "mode", buckling: "mode" }; // energy.csv has units in its header
const COUNTS = ["iterations", "plastic_points", "negative_pivots"];
function expectedCharts(dir) {
const expected = {};
for (const f of fs.readdirSync(dir).sort()) {
  const name = f.replace(/\.csv$/, "");
  const errors = name === "error_history"; // against time in a transient run, else λ; its text columns left out
  if (!f.endsWith(".csv") || !(name.startsWith("history") || name.startsWith("line_") || name in X || errors)) continue;
  const rows = fs.readFileSync(path.join(dir, f), "utf8").trim().split("\n");
  const header = rows[0].split(",");
  const x = errors ? (header.includes("time") ? "time" : "lambda") : X[name] || (name.startsWith("line_") ? "s" : "lambda");
  const text = errors ? ["state", "name"] : [];
  const series = header.filter((h) => h !== x && h !== "increment" && !text.includes(h) && (name === "history" || !COUNTS.includes(h)));
  expected[name] = { series: series.length, points: rows.length - 1 };
}
return expected;
}

// the mesh's bounding box from result.vtu's Points (binary: UInt64 byte
// count, then little-endian Float64, base64)
function vtuBox(file) {
  const text = fs.readFileSync(file, "utf8");
  const m = text.match(/<Points>\s*<DataArray[^>]*>\s*([A-Za-z0-9+/=]+)\s*</);
  const bytes = Buffer.from(m[1], "base64");
  const n = Number(bytes.readBigUInt64LE(0)) / 8;
  const box = [Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity];
  for (let i = 0; i < n; i++) {
    const v = bytes.readDoubleLE(8 + 8 * i);
    box[i % 3] = Math.min(box[i % 3], v);
    box[3 + (i % 3)] = Math.max(box[3 + (i % 3)], v);
  }
  return box;
}

const profile = fs.mkdtempSync(path.join(os.tmpdir(), "cufem-chromium-"));
// a fresh profile (playwright passes it as --user-data-dir)
const browser = await chromium.launchPersistentContext(profile, {
  viewport: { width: 1200, height: 900 },
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  args: [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
  ],
});
try {
  for (const dir of dirs) {
    const page = await browser.newPage();
    const errors = [];
    const requests = [];
    page.on("console", (m) => m.type() === "error" && errors.push(m.text()));
    page.on("pageerror", (e) => errors.push(String(e)));
    await page.route("**/*", (route) => {
      const url = route.request().url();
      if (url.startsWith("file:")) return route.continue();
      requests.push(url);
      return route.abort();
    });
    await page.goto("file://" + path.resolve(dir, "report.html"));
    console.log(`-- ${dir}`);
    const expected = expectedCharts(dir);
    await page.waitForFunction(() => window.cufemReport && window.cufemReport.ready, null, { timeout: 60000 });
    const r = await page.evaluate(() => ({
      charts: window.cufemReport.charts.map((c) => ({ name: c.name, series: c.series, points: c.points, width: c.plot.ctx.canvas.width })),
      tables: window.cufemReport.tables,
      axes: window.cufemReport.charts.filter((c) => !c.name.startsWith("section/")).map((c) => ({
        name: c.name,
        x: c.plot.axes[0].label,
        y: c.plot.axes[1].label,
        drawn: c.plot.series.slice(1).filter((s) => s.show).map((s) => s.label),
      })),
      bbox: window.cufemReport.bbox,
      fields: window.cufemReport.fields,
      frames: window.cufemReport.frames,
      modes: window.cufemReport.modes,
      mode: window.cufemReport.mode,
      scale: window.cufemReport.scale,
    }));

    // a verify run's overlays: one chart per line_<name>_<q>.csv of its verify
  // folder, cufem's and CalculiX's curves of the CSV's rows each
  const verify = path.join(dir, "verify");
  if (fs.existsSync(verify)) {
    const overlays = fs.readdirSync(verify).filter((f) => /^line_.*\.csv$/.test(f));
    check(overlays.length > 0, `verify wrote ${overlays.length} line overlays`);
    for (const f of overlays) {
      const rows = fs.readFileSync(path.join(verify, f), "utf8").trim().split("\n").length - 1;
      const c = r.charts.find((c) => c.name === "section/" + f.replace(/\.csv$/, ""));
      check(c && c.series === 2 && c.points.join() === [rows, rows].join() && c.width > 0,
        `overlay ${f}: ${c ? c.series : 0} series of ${c ? c.points : 0} points drawn, CSV 2 of ${rows}`);
    }
    const fields = JSON.parse(fs.readFileSync(path.join(verify, "table.json"), "utf8")).fields;
    const rows = await page.evaluate(() => [...document.querySelectorAll("section.added table.rows")].map((t) => t.rows.length - 1));
    check(rows[0] === fields.length && fields.length > 0, `whole-field table: ${rows[0]} rows, table.json ${fields.length}`);
    
  }
  // an adaptive run's cycles: the estimate against the DOF, a point per cycle
  // of summary.json, and the cycles' table
  const summary = JSON.parse(fs.readFileSync(path.join(dir, "summary.json"), "utf8"));
  if (summary.adapt) {
    const c = r.charts.find((c) => c.name === "section/adapt");
    check(c && c.series === 1 && c.points[0] === summary.adapt.length && summary.adapt.length >= 2 && c.width > 0,
      `adapt chart: ${c ? c.points : 0} points drawn, ${summary.adapt.length} cycles in summary.json`);
    const rows = await page.evaluate(() => document.querySelector("section.added table.rows").rows.length - 1);
    check(rows === summary.adapt.length, `cycles table: ${rows} rows`);
  }
  r.charts = r.charts.filter((c) => !c.name.startsWith("section/"));
  const drawn = Object.fromEntries(r.charts.map((c) => [c.name, c]));
    // a CSV of one row is a table of its values, not a chart of one dot
    const single = Object.fromEntries(Object.entries(expected).filter(([, e]) => e.points === 1));
    for (const name of Object.keys(single)) delete expected[name];
    const tables = Object.fromEntries(r.tables.map((t) => [t.name, t]));
    check(Object.keys(tables).sort().join() === Object.keys(single).sort().join() &&
      Object.entries(single).every(([name, e]) => tables[name].series === e.series),
      `one-row tables ${Object.keys(tables).sort()} are the CSVs of one row ${Object.keys(single).sort()}`);
    check(Object.keys(drawn).sort().join() === Object.keys(expected).sort().join(),
      `charts ${Object.keys(drawn).sort()} are the CSVs ${Object.keys(expected).sort()}`);
    // units: the abscissa's and the ordinate's (one unit, or a pointer to
    // the legend), and a line's coordinates are not drawn
    for (const a of r.axes) {
      check(a.y !== undefined && (a.y === "" || a.y === "several units: see the legend" || /^\[.+\]$/.test(a.y)) &&
        !a.drawn.some((l) => /^[xyz]( \[m\])?$/.test(l) && a.name.startsWith("line_")),
        `chart ${a.name}: x ${a.x}, y ${a.y}, drawn ${a.drawn.join(" ")}`);
    }
    // a symmetry plane's reaction along its normal is the solver's noise
    // (1e-6 N beside kN): not drawn, as a full-height curve it looked like data
    const sym = r.axes.find((a) => a.name === "history_symmetry_y");
    if (path.basename(dir) === "bending") check(sym, "the compact bar's page charts history_symmetry_y");
    if (sym) check(!sym.drawn.includes("r_y [N]"), `history_symmetry_y draws ${sym.drawn.join(" ") || "nothing"}`);
    for (const [name, e] of Object.entries(expected)) {
      const c = drawn[name] || {};
      check(c.series === e.series && c.points === e.points && c.width > 0,
        `chart ${name}: ${c.series} series of ${c.points} points drawn, CSV ${e.series} of ${e.points}`);
    }

    const box = vtuBox(path.join(dir, "result.vtu"));
    const size = Math.max(box[3] - box[0], box[4] - box[1], box[5] - box[2]);
    const off = r.bbox ? Math.max(...r.bbox.map((v, i) => Math.abs(v - box[i]))) : Infinity;
    // positions are f32: 1e-6 of the size is a few of its ulps
    check(off <= 1e-6 * size, `3D view's box ${JSON.stringify(r.bbox)} is result.vtu's ${JSON.stringify(box)} (off ${off})`);

    // pixels of the 3D canvas: how many differ from the last snapshot
    const snap = () => page.evaluate(() => {
      const gl = window.cufemReport.canvas;
      const c = document.createElement("canvas");
      c.width = gl.width;
      c.height = gl.height;
      const ctx = c.getContext("2d");
      ctx.drawImage(gl, 0, 0);
      const d = ctx.getImageData(0, 0, c.width, c.height).data;
      const prev = window.__snap;
      window.__snap = d;
      let changed = 0;
      let inked = 0;
      for (let i = 0; i < d.length; i += 4) {
        if (d[i] < 250 || d[i + 1] < 250 || d[i + 2] < 250) inked++;
        if (prev && (prev[i] !== d[i] || prev[i + 1] !== d[i + 1] || prev[i + 2] !== d[i + 2])) changed++;
      }
      return { changed, inked, total: d.length / 4 };
    });
    const first = await snap();
    check(first.inked > 1000, `the body covers ${first.inked} of ${first.total} canvas pixels`);
    const other = r.fields.includes("von_mises") ? "von_mises" : r.fields[r.fields.length - 1];
    await page.evaluate((f) => window.cufemReport.setField(f), other);
    const switched = await snap();
    check(switched.changed > 0.01 * first.inked, `field |u| → ${other} changed ${switched.changed} pixels`);
    // the first page is the history example's: its slider must move
    if (dir === dirs[0]) check(r.frames >= 2, `the slider has ${r.frames} frames`);
    if (r.frames >= 2) {
      await page.evaluate(() => window.cufemReport.setFrame(0));
      const moved = await snap();
      const label = await page.textContent("#frame-label");
      check(moved.changed > 0.01 * first.inked && label.includes("(1 of"), `frame 1 (${label}) changed ${moved.changed} pixels`);
      await page.evaluate((k) => window.cufemReport.setFrame(k), r.frames - 1);
    }
    // the run's mode_<k>.vtu files and result.vtu's ply damage must be in the view
    const modeFiles = fs.readdirSync(dir).filter((f) => /^mode_\d+\.vtu$/.test(f)).length;
    check(r.modes === modeFiles, `${r.modes} mode shapes in the view, ${modeFiles} mode_<k>.vtu`);
    const damaged = fs.readFileSync(path.join(dir, "result.vtu"), "utf8").includes('Name="d_ft"');
    check(r.fields.includes("d_ft") === damaged, `d_ft ${damaged ? "" : "not "}in result.vtu and the field list`);
    if (r.modes > 0) {
      // opened on mode 1, drawn with its largest displacement at a twentieth
      // of the body's size (a shape's amplitude is its normalisation: at
      // scale 1 it was as large as the body)
      check(r.mode === 0, `the page opens on mode ${r.mode + 1} (mode 1 expected)`);
      check(r.scale > 0 && r.scale < 1, `mode 1 drawn at scale ${r.scale}`);
      await page.evaluate(() => window.cufemReport.setMode(-1));
      const state = await snap();
      check(state.changed > 0.01 * first.inked, `the run's state changed ${state.changed} pixels from mode 1`);
      await page.evaluate(() => window.cufemReport.setMode(0));
      const mode1 = await snap();
      const label = await page.textContent("#frame-label");
      check(mode1.changed > 0.01 * first.inked && label.startsWith("mode 1"), `mode 1 (${label}) changed ${mode1.changed} pixels from the state`);
      await page.evaluate(() => window.cufemReport.setMode(1));
      const mode2 = await snap();
      check(mode2.changed > 0.01 * first.inked, `mode 2 changed ${mode2.changed} pixels from mode 1`);
      await page.evaluate(() => window.cufemReport.setMode(-1));
    }
    if (r.fields.includes("d_ft")) {
      await page.evaluate(() => window.cufemReport.setField("d_ft"));
      const damage = await snap();
      const range = await page.evaluate(() => window.cufemReport.range);
      check(range[1] > range[0] && damage.changed > 0.01 * first.inked,
        `d_ft ranges over [${range}] and changed ${damage.changed} pixels`);
    }
    const shot = path.join(shots, path.basename(dir) + ".png");
    await page.screenshot({ path: shot, fullPage: true });
    check(errors.length === 0, `no console error (${errors.join(" | ")})`);
    check(requests.length === 0, `no network request (${requests.join(" ")})`);
    await page.close();
  }
} finally {
  await browser.close();
  fs.rmSync(profile, { recursive: true, force: true });
}
if (failures.length) {
  console.log(`${failures.length} check(s) failed`);
  process.exit(1);
}
console.log(`report.html: all checks passed on ${dirs.length} pages`);
