// report.html's own script (src/io/html): builds the page from the JSON in
// #cufem-data with uPlot (charts) and three.js (3D view), both inlined
// before it. window.cufemReport exposes what was drawn, for the browser
// test (tests/browser) and for a reader's console.
// the colour ramp (blue, cyan, green, yellow, red) and a colour on it
const ramp = [[0.13, 0.25, 0.85], [0.1, 0.75, 0.9], [0.2, 0.8, 0.25], [0.95, 0.85, 0.1], [0.85, 0.1, 0.1]];
function colour(t) {
  const s = Math.min(Math.max(t, 0), 1) * (ramp.length - 1);
  const i = Math.min(Math.floor(s), ramp.length - 2);
  const f = s - i;
  return ramp[i].map((a, k) => a + f * (ramp[i + 1][k] - a));
}
function cssColour(c) {
  return "rgb(" + c.map((v) => Math.round(255 * v)).join(",") + ")";
}

(function () {
  "use strict";
  const data = JSON.parse(document.getElementById("cufem-data").textContent);
  const report = (window.cufemReport = { charts: [], fields: [], frame: 0, bbox: null, ready: false });
  const el = (tag, attrs, text) => {
    const e = document.createElement(tag);
    Object.entries(attrs || {}).forEach(([k, v]) => e.setAttribute(k, v));
    if (text !== undefined && text !== null) e.textContent = text;
    return e;
  };
  const add = (parent, tag, attrs, text) => parent.appendChild(el(tag, attrs, text));
  const body = document.body;
  document.title = data.title + " — cufem report";

  // description, status, text, warnings
  add(body, "h1", {}, data.title);
  const converged = data.status === "converged";
  const status = add(body, "p");
  add(status, "span", { class: converged ? "status" : "status bad" }, data.status);
  if (data.failure) add(status, "span", {}, " " + data.failure);
  if (data.description) add(body, "p", { id: "description" }, data.description);
  add(body, "h2", {}, "Run");
  add(body, "pre", { id: "header" }, data.header);
  const log = add(body, "details", { id: "log" });
  const lines = data.log.split("\n").filter((l) => l).length;
  add(log, "summary", {}, "convergence history: " + lines + " converged increments");
  add(log, "pre", {}, data.log);
  add(body, "h3", {}, "Results");
  add(body, "pre", { id: "results" }, data.results);
  add(body, "h2", {}, "Warnings");
  if (data.warnings.length === 0) add(body, "p", { id: "warnings" }, "none");
  else {
    const ul = add(body, "ul", { id: "warnings", class: "warnings" });
    data.warnings.forEach((w) => add(ul, "li", {}, w));
  }

  // sections: an adaptive run's cycles; added after the run, cufem verify's
  // comparison with CalculiX
  const palette = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"];
  const cellText = (v) => (v === null ? "—" : typeof v === "number" ? String(Number(v.toPrecision(4))) : String(v));
  (data.sections || []).forEach((sec) => {
    const part = add(body, "section", { class: "added" });
    add(part, "h2", {}, sec.title);
    sec.tables.forEach((t) => {
      add(part, "h3", {}, t.title);
      // a wide table (a probe's every quantity, cycle by cycle) scrolls
      // inside the page rather than running past it
      const table = add(add(part, "div", { class: "scroll" }), "table", { class: "rows" });
      const head = add(table, "tr");
      t.columns.forEach((c) => add(head, "th", {}, c));
      t.rows.forEach((r) => {
        const tr = add(table, "tr");
        r.forEach((v) => add(tr, "td", {}, cellText(v)));
      });
    });
    // each curve at its own abscissae (uPlot's mode 2), dashed as in the PNG
    sec.plots.forEach((p) => {
      const box = add(part, "div", { class: "chart", "data-name": p.name });
      add(box, "h3", {}, p.title);
      const opts = {
        mode: 2,
        width: Math.min(1060, document.body.clientWidth || 1000),
        height: 300,
        scales: { x: { time: false } },
        axes: [{ label: p.x }, { label: p.y, size: 80 }],
        series: [{}].concat(
          p.series.map((c, i) => ({
            label: c.label,
            stroke: palette[i % palette.length],
            width: 1.5,
            dash: c.dashed ? [6, 4] : undefined,
            paths: uPlot.paths.linear(),
          }))
        ),
      };
      const plot = new uPlot(opts, [null].concat(p.series.map((c) => [c.x, c.y])), box);
      report.charts.push({ name: "section/" + p.name, series: plot.series.length - 1, points: p.series.map((c) => c.x.length), plot: plot });
    });
    add(part, "details", {}).append(el("summary", {}, "the table as printed"), el("pre", {}, sec.text));
  });

  // charts: one per table, drag to zoom, double-click to reset
  if (data.charts.length) {
    add(body, "h2", {}, "Charts");
    add(body, "p", { class: "note" }, "Drag to zoom, double-click to reset; click a legend entry to hide its curve.");
  }
  const largest = (ys) => ys.reduce((m, y) => (y === null || !isFinite(y) ? m : Math.max(m, Math.abs(y))), 0);
  const ticks = (u, vals) => vals.map((v) => (v === null ? "" : Math.abs(v) >= 1e4 || (v !== 0 && Math.abs(v) < 1e-2) ? v.toExponential(2) : String(Number(v.toPrecision(4)))));
  // the SI unit of column k of chart c (0: the abscissa), as its table
  // gives it (src/io/html: `Column::unit`; "" for counts and ratios)
  const uOf = (c, k) => c.units[k];
  // a name that ends in its unit (energy.csv's kinetic_J, time_s) keeps it
  const labelled = (name, u) => (u && !name.endsWith("_" + u) ? name + " [" + u + "]" : name);
  // a line's coordinates are not results: listed, not drawn
  const coordinate = (c, name) => c.name.startsWith("line_") && ["x", "y", "z"].includes(name);
  report.tables = [];
  // the largest value of each unit over every chart of the page: a curve
  // below a millionth of it (Newton's default tolerance) is the solver's
  // noise (a symmetry plane's reaction of 1e-6 N beside kN elsewhere),
  // hidden even where it is the largest of its own chart
  const pageTop = {};
  data.charts.forEach((c) =>
    c.series.forEach((name, i) => {
      const u = uOf(c, i + 1);
      if (u) pageTop[u] = Math.max(pageTop[u] || 0, largest(c.data[i + 1]));
    })
  );
  data.charts.forEach((c) => {
    const box = add(body, "div", { class: "chart", "data-name": c.name });
    add(box, "h3", {}, c.title);
    if (c.data[0].length === 1) {
      // one row (a linear, modal or buckling run's one increment) is a
      // table of its values, not a chart of one dot
      const table = add(add(box, "div", { class: "scroll" }), "table", { class: "rows single" });
      const head = add(table, "tr");
      const row = add(table, "tr");
      [c.x].concat(c.series).forEach((name, i) => {
        add(head, "th", {}, labelled(name, uOf(c, i)));
        add(row, "td", {}, c.data[i][0] === null ? "—" : String(Number(c.data[i][0].toPrecision(6))));
      });
      report.tables.push({ name: c.name, series: c.series.length });
      return;
    }
    const shown = c.series.map((name, i) => !coordinate(c, name) && largest(c.data[i + 1]));
    const top = Math.max(0, ...shown.filter((v) => v !== false));
    // curves far smaller than the largest (another unit) start hidden
    const visible = shown.map((v, i) => v !== false && v > 0 && v >= 1e-3 * top && !(uOf(c, i + 1) && v < 1e-6 * pageTop[uOf(c, i + 1)]));
    const units = [...new Set(c.series.map((_, i) => uOf(c, i + 1)).filter((_, i) => visible[i]))];
    if (!visible.some((v) => v))
      add(box, "p", { class: "note" }, "No curve reaches a millionth of the page's largest value of its unit (the solver's noise, or nothing recorded): all hidden; click a legend entry to show one.");
    const opts = {
      width: Math.min(1060, document.body.clientWidth || 1000),
      height: 300,
      scales: { x: { time: false } },
      axes: [
        { label: labelled(c.x, uOf(c, 0)), values: ticks },
        { size: 80, values: ticks, label: units.length === 1 ? (units[0] ? "[" + units[0] + "]" : "") : units.length ? "several units: see the legend" : "" },
      ],
      series: [{ label: labelled(c.x, uOf(c, 0)) }].concat(
        c.series.map((name, i) => ({
          label: labelled(name, uOf(c, i + 1)),
          show: visible[i],
          stroke: palette[i % palette.length],
          width: 1.5,
          points: { size: 4 },
        }))
      ),
    };
    const plot = new uPlot(opts, c.data, box);
    report.charts.push({ name: c.name, series: plot.series.length - 1, points: plot.data[0].length, plot: plot });
  });

  if (data.view) view(data.view);
  report.ready = true;

  function decode(b64, Type) {
    const s = atob(b64);
    const bytes = new Uint8Array(s.length);
    for (let i = 0; i < s.length; i++) bytes[i] = s.charCodeAt(i);
    return new Type(bytes.buffer);
  }

  // the 3D view: the outer surface, coloured by a field, deformed by a scale
  function view(v) {
    add(body, "h2", {}, "3D view");
    add(body, "p", { class: "note", id: "view-note" }, v.note + ". Drag to rotate, right-drag to pan, wheel to zoom.");
    const controls = add(body, "div", { id: "view-controls" });
    const fieldLabel = add(controls, "label", {}, "field ");
    const select = add(fieldLabel, "select", { id: "field" });
    const scaleLabel = add(controls, "label", {}, "deformation scale ");
    const scaleInput = add(scaleLabel, "input", { id: "scale", type: "number", step: "any", min: "0" });
    // a modal or buckling run: its mode shapes, chosen instead of the states
    const modeLabel = v.modes.length ? add(controls, "label", {}, "shape ") : null;
    const modeSelect = modeLabel ? add(modeLabel, "select", { id: "mode" }) : null;
    const frameLabel = add(controls, "label", {}, "frame ");
    const slider = add(frameLabel, "input", { id: "frame", type: "range", min: "0", max: String(v.frames.length - 1), step: "1" });
    const frameText = add(controls, "span", { id: "frame-label" });
    const bar = add(body, "div", { id: "colour-bar" });
    const barMin = add(bar, "span", { id: "colour-min" });
    add(bar, "div", { class: "ramp", style: "background: linear-gradient(to right, " + ramp.map(cssColour).join(", ") + ")" });
    const barMax = add(bar, "span", { id: "colour-max" });
    const holder = add(body, "div", { id: "view" });

    const n = v.vertices;
    const reference = decode(v.positions, Float32Array);
    const decodeFrame = (f) => ({
      label: f.label,
      u: decode(f.displacement, Float32Array),
      fields: Object.fromEntries(f.fields.map((g) => [g.name, g])),
    });
    const states = v.frames.map(decodeFrame);
    const modes = v.modes.map(decodeFrame);
    // the fields no frame changes (cell data: body, element)
    const cells = Object.fromEntries(v.cells.map((g) => [g.name, g]));
    // a set's fields: the displacement's magnitude and components, then
    // the grid's scalars (point data, then the ply damage), then the cells'
    const fieldNames = (set) => {
      const names = ["|u|", "u_x", "u_y", "u_z"];
      set.forEach((f) => Object.keys(f.fields).forEach((k) => names.includes(k) || names.push(k)));
      return names.concat(Object.keys(cells));
    };
    const values = (frame, name) => {
      const out = new Float32Array(n);
      const c = ["u_x", "u_y", "u_z"].indexOf(name);
      if (name === "|u|") for (let i = 0; i < n; i++) out[i] = Math.hypot(frame.u[3 * i], frame.u[3 * i + 1], frame.u[3 * i + 2]);
      else if (c >= 0) for (let i = 0; i < n; i++) out[i] = frame.u[3 * i + c];
      else {
        const g = frame.fields[name] || cells[name];
        if (!g) return out.fill(NaN);
        const q = decode(g.data, Uint16Array);
        for (let i = 0; i < n; i++) out[i] = q[i] === 65535 ? NaN : g.min + (q[i] / 65534) * (g.max - g.min);
      }
      return out;
    };
    let frames = states;
    let names = [];
    const listFields = () => {
      names = fieldNames(frames);
      select.textContent = "";
      names.forEach((name) => add(select, "option", { value: name }, name));
      report.fields = names;
    };
    listFields();

    const geometry = new THREE.BufferGeometry();
    geometry.setIndex(new THREE.BufferAttribute(decode(v.triangles, Uint32Array), 1));
    geometry.setAttribute("position", new THREE.BufferAttribute(reference.slice(), 3));
    geometry.setAttribute("color", new THREE.BufferAttribute(new Float32Array(3 * n), 3));
    geometry.computeBoundingBox();
    const box = geometry.boundingBox;
    report.bbox = [box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z];
    const size = Math.max(box.max.x - box.min.x, box.max.y - box.min.y, box.max.z - box.min.z) || 1;
    const centre = box.getCenter(new THREE.Vector3());

    const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(1);
    renderer.setSize(holder.clientWidth, holder.clientHeight);
    renderer.setClearColor(0xffffff);
    holder.appendChild(renderer.domElement);
    const scene = new THREE.Scene();
    const material = new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide });
    scene.add(new THREE.Mesh(geometry, material));
    scene.add(new THREE.AmbientLight(0xffffff, 0.55));
    const camera = new THREE.PerspectiveCamera(35, holder.clientWidth / holder.clientHeight, size * 1e-3, size * 100);
    const light = new THREE.DirectionalLight(0xffffff, 0.6);
    camera.add(light);
    scene.add(camera);
    camera.up.set(0, 0, 1);
    camera.position.set(centre.x + 1.6 * size, centre.y - 1.2 * size, centre.z + 1.0 * size);
    const orbit = new THREE.OrbitControls(camera, renderer.domElement);
    orbit.target.copy(centre);
    orbit.update();
    const render = () => renderer.render(scene, camera);
    orbit.addEventListener("change", render);

    // a scale that shows a set's largest displacement at 5 % of the body's
    // size: the run's states are never shrunk (a displacement larger than
    // that is shown as it is), the mode shapes are (their amplitude is a
    // normalisation: largest component 1, as large as the body; a new-user review)
    const autoScale = (set, shrink) => {
      let largest = 0;
      set.forEach((f) => {
        for (let i = 0; i < n; i++) largest = Math.max(largest, Math.hypot(f.u[3 * i], f.u[3 * i + 1], f.u[3 * i + 2]));
      });
      if (largest === 0 || (largest > 0.05 * size && !shrink)) return 1;
      return Number((0.05 * size / largest).toPrecision(2));
    };
    const scales = [autoScale(states, false), autoScale(modes, true)];
    let scale = scales[0];
    scaleInput.value = String(scale);
    let field = names[0];
    let frame = frames.length - 1;
    let stateFrame = frame;
    slider.value = String(frame);
    if (modeSelect) {
      add(modeSelect, "option", { value: "-1" }, "the run's state");
      modes.forEach((m, k) => add(modeSelect, "option", { value: String(k) }, m.label));
    }

    function update() {
      const f = frames[frame];
      const pos = geometry.getAttribute("position");
      for (let i = 0; i < 3 * n; i++) pos.array[i] = reference[i] + scale * f.u[i];
      pos.needsUpdate = true;
      geometry.computeVertexNormals();
      // the colour range: the field's over all frames, so the slider shows its growth
      let lo = Infinity;
      let hi = -Infinity;
      frames.forEach((g) => {
        const x = values(g, field);
        for (let i = 0; i < n; i++) if (isFinite(x[i])) (lo = Math.min(lo, x[i])), (hi = Math.max(hi, x[i]));
      });
      const x = values(f, field);
      const col = geometry.getAttribute("color");
      for (let i = 0; i < n; i++) {
        const c = isFinite(x[i]) ? colour(hi > lo ? (x[i] - lo) / (hi - lo) : 0.5) : [0.6, 0.6, 0.6];
        col.array.set(c, 3 * i);
      }
      col.needsUpdate = true;
      barMin.textContent = isFinite(lo) ? lo.toPrecision(4) : "—";
      barMax.textContent = isFinite(hi) ? hi.toPrecision(4) : "—";
      frameText.textContent = f.label + " (" + (frame + 1) + " of " + frames.length + ")";
      report.field = field;
      report.frame = frame;
      report.scale = scale;
      report.range = [lo, hi];
      render();
    }
    select.addEventListener("change", () => ((field = select.value), update()));
    slider.addEventListener("input", () => ((frame = stateFrame = Number(slider.value)), update()));
    scaleInput.addEventListener("input", () => {
      const s = Number(scaleInput.value);
      if (isFinite(s) && s >= 0) (scale = scales[frames === modes ? 1 : 0] = s), update();
    });
    // a mode shown: the modes are the frames, the slider waits for the states
    const showMode = (k) => {
      frames = k < 0 ? states : modes;
      frame = k < 0 ? stateFrame : k;
      scale = scales[k < 0 ? 0 : 1];
      scaleInput.value = String(scale);
      slider.disabled = k >= 0;
      listFields();
      if (!names.includes(field)) field = names[0];
      select.value = field;
      report.mode = k;
      update();
    };
    if (modeSelect) modeSelect.addEventListener("change", () => showMode(Number(modeSelect.value)));
    report.setMode = (k) => modeSelect && ((modeSelect.value = String(k)), modeSelect.dispatchEvent(new Event("change")));
    report.modes = modes.length;
    report.mode = -1;
    report.setField = (name) => ((select.value = name), select.dispatchEvent(new Event("change")));
    report.setFrame = (k) => ((slider.value = String(k)), slider.dispatchEvent(new Event("input")));
    report.frames = frames.length;
    report.canvas = renderer.domElement;
    // a modal or buckling run opens on its first mode: the shapes are what
    // it is run for (its state is often the unloaded structure)
    if (modeSelect && modes.length > 0) (modeSelect.value = "0"), showMode(0);
    else update();
  }
})();

