// The interactive page: draw, drag, send to the server, show its answers.
"use strict";

const $ = (id) => document.getElementById(id);
const svg = $("view");
const NS = "http://www.w3.org/2000/svg";
const clone = (x) => (x === undefined ? undefined : JSON.parse(JSON.stringify(x)));
const isAssembly = () => Boolean(state.case && state.case.format === "section-case/2");
// an assembly's bodies, each in its own colour
const COLOURS = ["#1a4fa8", "#c2571a", "#2a8a3a", "#8a2aa8", "#a8891a", "#1a8aa8", "#a81a4f", "#555"];
const colour = (i) => COLOURS[i % COLOURS.length];

const state = {
  opened: null,        // the case as opened (for reset)
  case: null,          // the case being edited (section-case/1, or section-case/2: an assembly)
  body: 0,             // an assembly's body whose law the slider sets
  outline: null,       // an assembly's bodies as drawn, before (or without) any answer
  model: "paper",
  ratio: 0.8,
  seq: 0,              // last request sent
  shown: -1,           // last answer drawn
  sent: new Map(),     // seq -> performance.now() of the pointer event
  sentAt: new Map(),   // seq -> performance.now() once sent
  result: null,        // last good answer
  view: { s: 1, tx: 0, ty: 0 },
  q: 1e3,              // path rounding: coordinates kept to 1/q world units (see applyView)
  undo: [],
  selected: null,      // {curve: "target"|"upper", index}
  drag: null,
  editsPending: false, // an edit made while dragging, drawn with its answer (editLater)
  latencies: [],       // ms from pointer event to redrawn section (for the benchmark)
  saved: "",           // the edits as last opened or saved (see dirty)
  field: "",           // the colour map on the final mesh ("" none)
  probe: null,         // the thickness probe: null (off) or its points [[x, y], ...] (world units)
  parts: [],           // the case's rigid parts as drawn: {outline [[x, y]...] at travel `at`, dir (unit travel) or null}
  contact: null,       // the contact figures of the last full deformation: {seq, rigid, support_force, units}
};
window.sdState = state;

// ---- drawing -----------------------------------------------------------

// Path coordinates are rounded to a twentieth of a screen pixel (state.q: a power of ten per world unit):
// short strings, quick to build and to parse, and no visible difference.
const round = (v) => Math.round(v * state.q) / state.q;

function pathOf(pts, close) {
  if (!pts || !pts.length) return "";
  let d = "M" + round(pts[0][0]) + " " + round(pts[0][1]);
  for (let i = 1; i < pts.length; i++) d += "L" + round(pts[i][0]) + " " + round(pts[i][1]);
  return close ? d + "Z" : d;
}

// A body as one closed path: its contour, then each hole (drawn as the body's inside by the even-odd fill rule).
function bodyOf(contour, holes) {
  let d = pathOf(contour, true);
  for (const h of holes || []) d += pathOf(h, true);
  return d;
}

// A mesh as one path: each cell a closed polygon of its nodes. Points are flat x, y (Float64Array).
function meshPath(mesh) {
  if (!mesh || !mesh.cells || !mesh.points) return "";
  const P = mesh.points, n = P.length / 2, S = new Array(n);
  for (let i = 0; i < n; i++) S[i] = round(P[2 * i]) + " " + round(P[2 * i + 1]);
  let d = "";
  for (const c of mesh.cells) {
    const order = BOUNDARY[c.length];
    d += "M" + S[c[order ? order[0] : 0]];
    for (let j = 1; j < c.length; j++) d += "L" + S[c[order ? order[j] : j]];
    d += "Z";
  }
  return d;
}
// The boundary order of a quadratic cell's nodes (corners first, then mid-edge nodes): triangle6, quad8.
const BOUNDARY = { 6: [0, 3, 1, 4, 2, 5], 8: [0, 4, 1, 5, 2, 6, 3, 7] };

function applyView() {
  const v = state.view;
  $("world").setAttribute("transform", `matrix(${v.s} 0 0 ${-v.s} ${v.tx} ${v.ty})`);
  const q = 10 ** Math.max(0, Math.ceil(Math.log10(Math.max(20 * v.s, 1e-300))));
  if (q !== state.q && Number.isFinite(q)) { state.q = q; drawResult(true); drawEdits(false); }
  drawHandles();
  drawAxes();
  drawProbe();
}

const toScreen = (p) => [state.view.s * p[0] + state.view.tx, -state.view.s * p[1] + state.view.ty];
function toWorld(evt) {
  const r = svg.getBoundingClientRect();
  return [(evt.clientX - r.left - state.view.tx) / state.view.s, (state.view.ty - (evt.clientY - r.top)) / state.view.s];
}

// ---- axes, scale bar, pointer read-out, thickness probe -------------------

const units = () => (state.case && state.case.units) || "";
// A round step (1, 2 or 5 times a power of ten) near `size`.
function niceStep(size) {
  const p = 10 ** Math.floor(Math.log10(size)), m = size / p;
  return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}
// A length or coordinate as text: as many decimals as `step` needs, no more.
function numText(v, step) {
  const d = Math.max(0, Math.min(12, -Math.floor(Math.log10(step) + 1e-9)));
  return (Math.abs(v) < step / 2 ? 0 : v).toFixed(d);
}
function svgEl(tag, attrs, text) {
  const e = document.createElementNS(NS, tag);
  for (const k in attrs) e.setAttribute(k, attrs[k]);
  if (text !== undefined) e.textContent = text;
  return e;
}

const AXIS_FONT = 11;   // px, the axes' text (.axis text in index.html)

// Axes along the bottom and left edges (ticks about every 100 px, a faint grid), the units, a scale bar.
function drawAxes() {
  const g = $("axes"), bar = $("scale");
  const r = svg.getBoundingClientRect(), v = state.view;
  if (!state.case || !(v.s > 0) || !r.width) { g.replaceChildren(); bar.replaceChildren(); return; }
  const step = niceStep(100 / v.s), u = units();
  const out = [];
  const x0 = -v.tx / v.s, x1 = (r.width - v.tx) / v.s, y0 = (v.ty - r.height) / v.s, y1 = v.ty / v.s;
  for (let x = Math.ceil(x0 / step) * step; x <= x1; x += step) {
    const sx = v.s * x + v.tx;
    out.push(svgEl("line", { class: "grid", x1: sx, x2: sx, y1: 0, y2: r.height }));
    out.push(svgEl("line", { x1: sx, x2: sx, y1: r.height - 6, y2: r.height }));
    out.push(svgEl("text", { x: sx + 2, y: r.height - 8, class: "tick-x" }, numText(x, step)));
  }
  let top = Infinity;   // the screen y of the highest tick
  for (let y = Math.ceil(y0 / step) * step; y <= y1; y += step) {
    const sy = -v.s * y + v.ty;
    top = Math.min(top, sy);
    out.push(svgEl("line", { class: "grid", x1: 0, x2: r.width, y1: sy, y2: sy }));
    out.push(svgEl("line", { x1: 0, x2: 6, y1: sy, y2: sy }));
    out.push(svgEl("text", { x: 8, y: sy - 2, class: "tick-y" }, numText(y, step)));
  }
  out.push(svgEl("text", { x: r.width - 60, y: r.height - 22, id: "axis-x-label" }, "x" + (u ? ` (${u})` : "")));
  // the y label at the top, or just under the highest tick's label where that one is too close to the top
  // (ticks are at least 57 px apart, see niceStep: the label fits between two)
  const labelY = top - 2 - AXIS_FONT < 14 + 0.4 * AXIS_FONT ? top + 2 + AXIS_FONT : 14;
  out.push(svgEl("text", { x: 8, y: labelY, id: "axis-y-label" }, "y" + (u ? ` (${u})` : "")));
  g.replaceChildren(...out);
  // the scale bar: a round length between about 60 and 150 px, bottom left
  const len = niceStep(100 / v.s), px = len * v.s, bx = 40, by = r.height - 34;
  bar.replaceChildren(svgEl("line", { x1: bx, x2: bx + px, y1: by, y2: by }),
                      svgEl("line", { x1: bx, x2: bx, y1: by - 4, y2: by + 4 }),
                      svgEl("line", { x1: bx + px, x2: bx + px, y1: by - 4, y2: by + 4 }),
                      svgEl("text", { x: bx, y: by - 6, id: "scale-label" }, `${numText(len, len)}${u ? " " + u : ""}`));
  bar.dataset.length = len; bar.dataset.pixels = px;
}

// The pointer's coordinates (world units), shown under the readouts.
function showPointer(e) {
  if (!state.case || !(state.view.s > 0)) return;
  const [x, y] = toWorld(e), step = niceStep(0.5 / state.view.s);   // to half a screen pixel
  $("r-pointer").textContent = `${numText(x, step)}, ${numText(y, step)}${units() ? " " + units() : ""}`;
}

// The nearest point of a polyline (flat or [[x, y]...]) to p, and its distance.
function nearest(line, p) {
  let best = { d: Infinity, q: null };
  for (let i = 0; i + 1 < line.length; i++) {
    const a = line[i], b = line[i + 1], ab = Geo.sub(b, a), l2 = Geo.dot(ab, ab);
    const t = l2 > 0 ? Math.max(0, Math.min(1, Geo.dot(Geo.sub(p, a), ab) / l2)) : 0;
    const q = [a[0] + t * ab[0], a[1] + t * ab[1]], d = Math.hypot(p[0] - q[0], p[1] - q[1]);
    if (d < best.d) best = { d, q };
  }
  return best;
}

// The lower curve a probed point is measured to: the deformed one of the answer on screen, else the outline's.
function probeLower() {
  if (state.result && state.result.lower) return { line: state.result.lower, what: "deformed lower curve" };
  if (state.outline && state.outline.length === 1) return { line: state.outline[0].contour.slice(0, OUTLINE_SAMPLES), what: "lower curve" };
  return null;
}
const OUTLINE_SAMPLES = 65;   // points of each curve of an outline (engine.OUTLINE_SAMPLES)

function drawProbe() {
  const g = $("probe-marks");
  const pts = state.probe || [];
  if (!pts.length) { g.replaceChildren(); $("r-probe").textContent = state.probe ? "click a point" : "—"; return; }
  const u = units() ? " " + units() : "", out = [], low = probeLower();
  const step = niceStep(0.5 / state.view.s);
  const texts = [];
  pts.forEach((p, i) => {
    const sp = toScreen(p), name = "AB"[i];
    if (low && i === 0) {
      const n = nearest(low.line, p), sq = toScreen(n.q);
      out.push(svgEl("line", { x1: sp[0], y1: sp[1], x2: sq[0], y2: sq[1] }));
      texts.push(`${name}: ${numText(n.d, step)}${u} to the ${low.what}`);
      g.dataset.lowerDistance = n.d;
    }
    out.push(svgEl("circle", { cx: sp[0], cy: sp[1], r: 4 }));
    out.push(svgEl("text", { x: sp[0] + 6, y: sp[1] - 6 }, name));
  });
  if (pts.length === 2) {
    const [a, b] = pts, sa = toScreen(a), sb = toScreen(b), d = Math.hypot(b[0] - a[0], b[1] - a[1]);
    out.push(svgEl("line", { x1: sa[0], y1: sa[1], x2: sb[0], y2: sb[1] }));
    texts.push(`|AB| = ${numText(d, step)}${u}`);
    g.dataset.distance = d;
  } else delete g.dataset.distance;
  g.replaceChildren(...out);
  $("r-probe").textContent = texts.join("; ");
}

function setProbe(on) {
  state.probe = on ? [] : null;
  $("probe").classList.toggle("on", on);
  svg.classList.toggle("probing", on);
  drawProbe();
}

function fit() {
  const pts = [...Geo.points(state.case.target)];
  const res = state.result;
  if (res && res.assembly) res.bodies.forEach((b) => pts.push(...b.initial_contour, ...b.contour));
  else if (res) pts.push(...res.initial_contour, ...res.contour);
  else if (state.outline) state.outline.forEach((b) => pts.push(...b.contour));
  else if (state.case.upper) pts.push(...Geo.points(state.case.upper));
  state.parts.forEach((_, i) => { const at = partPlaces(i); if (at) pts.push(...at.start, ...at.end); });
  const xs = pts.map((p) => p[0]), ys = pts.map((p) => p[1]);
  const x0 = Math.min(...xs), x1 = Math.max(...xs), y0 = Math.min(...ys), y1 = Math.max(...ys);
  const r = svg.getBoundingClientRect();
  const s = 0.8 * Math.min(r.width / Math.max(x1 - x0, 1e-9), r.height / Math.max(y1 - y0, 1e-9));
  state.view = { s, tx: r.width / 2 - s * (x0 + x1) / 2, ty: r.height / 2 + s * (y0 + y1) / 2 };
  state.fitted = JSON.stringify(state.view);
  applyView();
}

function drawResult(all) {
  const res = state.result;
  if (!res) { drawOutline(); return; }
  const show = $("show-mesh").checked;
  if (res.assembly) { drawBodies(res, all, show); return; }
  if (all || $("bodies").children.length) $("bodies").replaceChildren();   // the outline drawn before any answer
  // the initial section and mesh change only with the section: redrawn only then
  if (all || res.initialSent) {
    $("initial").setAttribute("d", bodyOf(res.initial_contour, res.initial_holes));
    $("mesh-initial").setAttribute("d", show ? meshPath(res.mesh_initial) : "");
  }
  $("deformed").setAttribute("d", bodyOf(res.contour, res.holes));
  $("target").setAttribute("d", pathOf(res.lower, false));
  $("mesh-final").setAttribute("d", show ? meshPath(res.mesh_final) : "");
  drawField(res, all);
}

// ---- colour maps ----------------------------------------------------------

// viridis at nine stops
const VIRIDIS = ["#440154", "#472d7b", "#3b528b", "#2c728e", "#21918c", "#28ae80", "#5ec962", "#addc30", "#fde725"];
const BINS = 32;   // the colour map in 32 steps: one path per step, whatever the number of elements
function viridis(t) {
  const x = Math.max(0, Math.min(1, t)) * (VIRIDIS.length - 1), i = Math.min(VIRIDIS.length - 2, Math.floor(x)), f = x - i;
  const c = (h, k) => parseInt(h.slice(1 + 2 * k, 3 + 2 * k), 16);
  const mix = (k) => Math.round(c(VIRIDIS[i], k) * (1 - f) + c(VIRIDIS[i + 1], k) * f);
  return `rgb(${mix(0)},${mix(1)},${mix(2)})`;
}
// Cells of a mesh as polygons of their corners (a quadratic cell's corners and mid-edge nodes in boundary order).
function cellPath(P, c) {
  const order = BOUNDARY[c.length];
  let d = "";
  for (let j = 0; j < c.length; j++) {
    const k = c[order ? order[j] : j];
    d += (j ? "L" : "M") + round(P[2 * k]) + " " + round(P[2 * k + 1]);
  }
  return d + "Z";
}

// The colour map of the answer on screen: each final element filled by its value's colour, clipped to the
// deformed section(s). A preview carries no field (its colours would be stale): the map waits for the release.
function drawField(res, all) {
  const g = $("field-overlay");
  const f = res && res.field;
  if (!f || f.error || !state.field) {
    g.replaceChildren(); delete g.dataset.field;
    $("field-clip-path").setAttribute("d", "");
    $("colourbar").hidden = true;
    return;
  }
  const parts = res.assembly ? res.bodies.map((b, i) => [b, f.bodies[i].values]) : [[res, f.values]];
  const span = f.max - f.min || 1;
  const ds = new Array(BINS).fill("");
  let clip = "", cells = 0;
  for (const [b, values] of parts) {
    const mesh = b.mesh_final;
    if (!mesh || !mesh.cells) continue;
    mesh.cells.forEach((c, e) => { ds[Math.min(BINS - 1, Math.floor(BINS * (values[e] - f.min) / span))] += cellPath(mesh.points, c); });
    cells += mesh.cells.length;
    clip += bodyOf(b.contour, b.holes);
  }
  $("field-clip-path").setAttribute("d", clip);
  g.replaceChildren(...ds.map((d, i) => svgEl("path", { d, fill: viridis((i + 0.5) / BINS) })).filter((p) => p.getAttribute("d")));
  g.dataset.field = f.name; g.dataset.cells = cells; g.dataset.min = f.min; g.dataset.max = f.max;
  $("colourbar").hidden = false;
  $("colourbar-label").textContent = f.label;
  $("colourbar-ramp").style.background = `linear-gradient(to right, ${VIRIDIS.join(", ")})`;
  const step = niceStep(Math.max(Math.abs(f.max - f.min), Math.abs(f.max) * 1e-6, 1e-300) / 1000);
  $("colourbar-min").textContent = numText(f.min, step);
  $("colourbar-max").textContent = numText(f.max, step);
}

// An assembly's bodies: one group per body (initial, its mesh, deformed, its mesh), in the body's colour.
function bodyPaths(n) {
  const g = $("bodies");
  if (g.children.length !== n) {
    g.replaceChildren();
    for (let i = 0; i < n; i++) {
      const b = document.createElementNS(NS, "g");
      b.setAttribute("class", "body");
      b.dataset.body = i;
      b.style.setProperty("--c", colour(i));
      for (const k of ["initial", "mesh-initial", "deformed", "mesh-final"]) {
        const p = document.createElementNS(NS, "path");
        p.setAttribute("class", "body-" + k);
        b.appendChild(p);
      }
      g.appendChild(b);
    }
    for (const id of ["initial", "mesh-initial", "deformed", "mesh-final"]) $(id).setAttribute("d", "");
  }
  return [...g.children].map((b) => b.children);
}

function drawBodies(res, all, show) {
  const paths = bodyPaths(res.bodies.length);
  res.bodies.forEach((b, i) => {
    const [initial, meshInitial, deformed, meshFinal] = paths[i];
    if (all || res.initialSent) {
      initial.setAttribute("d", bodyOf(b.initial_contour, b.initial_holes));
      meshInitial.setAttribute("d", show ? meshPath(b.mesh_initial) : "");
    }
    deformed.setAttribute("d", bodyOf(b.contour, b.holes));
    meshFinal.setAttribute("d", show ? meshPath(b.mesh_final) : "");
  });
  $("target").setAttribute("d", pathOf(res.lower, false));
  drawField(res, all);
}

// A case the library has not deformed (yet, or at all): its bodies as drawn, from their own curves.
function drawOutline() {
  for (const id of ["initial", "mesh-initial", "deformed", "mesh-final"]) $(id).setAttribute("d", "");
  drawField(null);
  if (!state.outline) { $("bodies").replaceChildren(); return; }
  const paths = bodyPaths(state.outline.length);
  state.outline.forEach((b, i) => {
    paths[i][0].setAttribute("d", bodyOf(b.contour, b.holes));
    for (let k = 1; k < 4; k++) paths[i][k].setAttribute("d", "");
  });
  $("target").setAttribute("d", "");
}

function drawEdits(handles = true) {
  if (!state.case) return;
  drawRigid();
  $("target-polygon").setAttribute("d", pathOf(Geo.points(state.case.target), false));
  const up = state.case.upper;
  $("upper-polygon").setAttribute("d", up && up.bspline ? pathOf(Geo.points(up), false) : "");
  if (handles) drawHandles();
}

// ---- rigid parts ---------------------------------------------------------

// Each part in its own colour, apart from the bodies'.
const RIGID_COLOURS = ["#b8860b", "#00838f", "#ad1457", "#5d4037"];
const rigidColour = (i) => RIGID_COLOURS[i % RIGID_COLOURS.length];
const rigidCase = () => (state.case && Array.isArray(state.case.rigid) ? state.case.rigid : []);
const shifted = (pts, d) => pts.map((p) => [p[0] + d[0], p[1] + d[1]]);
const centroid = (pts) => [pts.reduce((s, p) => s + p[0], 0) / pts.length, pts.reduce((s, p) => s + p[1], 0) / pts.length];

// The parts as drawn, from the case's own rigid list and the server's outlines ({contour, travel} per part:
// the outline where the part ends at that travel). A part that travels can be moved along its travel.
function setParts(given) {
  state.parts = rigidCase().map((part, i) => {
    const t = part.travel || [0, 0], len = Math.hypot(t[0], t[1]);
    const g = given && given[i];
    return { outline: g ? g.contour : null, at: g ? g.travel : null, dir: len > 0 ? [t[0] / len, t[1] / len] : null };
  });
}

// Part i's start (dashed: where it starts, the outline less its travel) and end (solid: where the travel takes it).
function partPlaces(i) {
  const p = state.parts[i], t = rigidCase()[i].travel || [0, 0];
  if (!p || !p.outline) return null;
  return { start: shifted(p.outline, [-p.at[0], -p.at[1]]), end: shifted(p.outline, [t[0] - p.at[0], t[1] - p.at[1]]) };
}

// Part i's travel along its direction (units).
const alongTravel = (i) => { const t = rigidCase()[i].travel, d = state.parts[i].dir; return d ? Geo.dot(t, d) : 0; };

// Part i travels `s` along its direction: its end (the case's contour) moves with it, its start stays.
function setTravel(i, s) {
  const part = rigidCase()[i], d = state.parts[i].dir, old = part.travel || [0, 0];
  const t = [s * d[0] + 0, s * d[1] + 0];
  part.contour = Geo.translated(part.contour, [t[0] - old[0], t[1] - old[1]]);
  part.travel = t;
}

function drawRigid() {
  const g = $("rigid"), parts = rigidCase();
  if (g.children.length !== parts.length) {
    g.replaceChildren(...parts.map((_, i) => {
      const e = svgEl("g", { class: "rigid-shape", "data-part": i });
      e.style.setProperty("--c", rigidColour(i));
      for (const k of ["initial", "arrow", "final"]) e.appendChild(svgEl("path", { class: "rigid-" + k }));
      e.appendChild(svgEl("g", { class: "rigid-pressure" }));
      return e;
    }));
  }
  const c = state.contact, res = state.result;
  // the pressure belongs to the full deformation on screen: drawn with it only
  const pressure = c && res && res.seq === c.seq && c.rigid.length === parts.length;
  const top = pressure ? Math.max(...c.rigid.map((r) => r.pressure_max), 0) || 1 : 1;
  parts.forEach((_, i) => {
    const [initial, travel, final, dots] = g.children[i].children, at = partPlaces(i);
    initial.setAttribute("d", at ? pathOf(at.start, true) : "");
    final.setAttribute("d", at ? pathOf(at.end, true) : "");
    travel.setAttribute("d", at ? pathOf([centroid(at.start), centroid(at.end)], false) : "");
    const ds = new Array(BINS).fill("");
    if (pressure) for (const [x, y, p] of c.rigid[i].pressure) ds[Math.min(BINS - 1, Math.floor(BINS * p / top))] += `M${round(x)} ${round(y)}l0 0`;
    dots.replaceChildren(...ds.map((d, k) => (d ? svgEl("path", { d, stroke: viridis((k + 0.5) / BINS) }) : null)).filter(Boolean));
  });
  $("pressure-legend").hidden = !pressure || !parts.length;
  if (pressure) {
    $("pressure-label").textContent = `contact pressure along the body (${c.units.pressure})`;
    $("pressure-ramp").style.background = `linear-gradient(to right, ${VIRIDIS.join(", ")})`;
    $("pressure-max").textContent = fmt(top, 2);
  }
}

// The parts' panel: each part's travel (editable), and the last full deformation's force, contact and pressures.
function showRigid() {
  const parts = rigidCase(), box = $("rigid-parts");
  $("rigid-panel").hidden = !parts.length;
  if (!parts.length) { box.replaceChildren(); return; }
  if (box.children.length !== parts.length) {
    box.replaceChildren(...parts.map((part, i) => {
      const div = document.createElement("div");
      div.className = "rigid-part"; div.dataset.part = i;
      div.style.setProperty("--c", rigidColour(i));
      div.innerHTML = `<div class="rigid-head"><strong class="rigid-name"></strong><label>travel
        <input class="travel-input" type="number" step="any" min="0"></label><span class="rigid-dir"></span></div>
        <dl><dt>force</dt><dd class="r-force"></dd><dt>contact</dt><dd class="r-contact"></dd>
        <dt>peak pressure</dt><dd class="r-pressure"></dd></dl>`;
      div.querySelector(".travel-input").addEventListener("change", (e) => travelTyped(i, e.target));
      return div;
    }));
  }
  const u = units(), c = state.contact;
  const figures = c && c.rigid.length === parts.length ? c.rigid : null;
  parts.forEach((part, i) => {
    const div = box.children[i], input = div.querySelector(".travel-input"), d = state.parts[i] && state.parts[i].dir;
    div.querySelector(".rigid-name").textContent = part.name;
    input.disabled = !d;
    input.title = d ? "how far the part travels along its direction, from where it starts" : "a fixed part (no travel)";
    if (document.activeElement !== input) input.value = d ? Number(alongTravel(i).toPrecision(12)) : 0;
    div.querySelector(".rigid-dir").textContent = (u ? u + " " : "") + (d ? `along (${fmt(d[0], 2)}, ${fmt(d[1], 2)})` : "(fixed)");
    const f = figures && figures[i];
    const stale = !f || f.name !== part.name || f.travel[0] !== part.travel[0] || f.travel[1] !== part.travel[1];
    div.classList.toggle("stale", Boolean(f) && (stale || Boolean(state.refused)));
    div.dataset.travel = alongTravel(i);
    if (!f) { for (const k of ["force", "contact", "pressure"]) div.querySelector(".r-" + k).textContent = "—"; return; }
    const m = Math.hypot(f.force[0], f.force[1]), comp = (v) => (Math.abs(v) <= 1e-9 * m ? "0" : v.toPrecision(4));
    div.querySelector(".r-force").textContent = `${fmt(m)} ${c.units.force} (x ${comp(f.force[0])}, y ${comp(f.force[1])})` +
      (stale ? (state.refused ? " — refused for this travel (see the message)" : " — solving…") : "");
    div.querySelector(".r-contact").textContent = `${fmt(f.length)} ${c.units.length}`;
    div.querySelector(".r-pressure").textContent = `${fmt(f.pressure_max)} ${c.units.pressure} (mean ${fmt(f.pressure_mean, 2)})`;
    Object.assign(div.dataset, { force: m, forceX: f.force[0], forceY: f.force[1], length: f.length,
                                 pressureMax: f.pressure_max, solvedTravel: JSON.stringify(f.travel), seq: c.seq });
  });
}

// A travel typed in a part's field: solved in full.
function travelTyped(i, input) {
  const v = Number(input.value);
  if (input.value === "" || !(v >= 0)) {
    message(`${rigidCase()[i].name}: travel must be a number ≥ 0 (${units() || "units"} along the part's travel)`, "error");
    input.value = alongTravel(i);
    return;
  }
  state.undo.push(snapshot());
  setTravel(i, v);
  drawEdits(); showRigid();
  request(true);
}

// The contact figures of a full deformation: kept (with the parts' outlines where they ended) until the next one.
function takeContact(msg) {
  const parts = rigidCase();
  if (!msg.rigid || msg.rigid.length !== parts.length) return;
  msg.rigid.forEach((r, i) => {
    const p = r.pressure, out = [];
    for (let k = 0; k + 2 < p.length; k += 3) out.push([p[k], p[k + 1], p[k + 2]]);
    r.pressure = out;
    r.outline = pairs(r.outline);
    if (state.parts[i] && r.name === parts[i].name) { state.parts[i].outline = r.outline; state.parts[i].at = r.travel; }
  });
  state.contact = { seq: msg.seq, rigid: msg.rigid, support_force: msg.support_force, units: msg.contact_units };
}

// Handles: the target's points (red), the upper curve's inner points (green), whole-target handles, and each
// travelling rigid part's end (in its colour).
function handleList() {
  const list = [];
  state.parts.forEach((p, i) => {
    const at = p.dir && partPlaces(i);
    if (at) list.push({ rigid: i, p: centroid(at.end) });
  });
  const tp = Geo.points(state.case.target);
  tp.forEach((p, i) => list.push({ curve: "target", index: i, p }));
  const up = state.case.upper ? Geo.points(state.case.upper) : [];   // an assembly's bodies are not edited here
  if (state.case.upper && !state.case.upper.arc) up.forEach((p, i) => { if (i > 0 && i < up.length - 1) list.push({ curve: "upper", index: i, p }); });
  const f = Geo.frame(tp);
  const low = state.result ? state.result.lower : tp;    // the whole-curve handles hang below the target's middle
  const mid = low[Math.floor(low.length / 2)];
  const base = [f.M[0] + f.u[0] * Geo.dot(Geo.sub(mid, f.M), f.u) + f.n[0] * Math.min(0, Geo.dot(Geo.sub(mid, f.M), f.n)),
                f.M[1] + f.u[1] * Geo.dot(Geo.sub(mid, f.M), f.u) + f.n[1] * Math.min(0, Geo.dot(Geo.sub(mid, f.M), f.n))];
  const off = (k, along) => {
    const m = toScreen(base);
    return { screen: [m[0] - f.n[0] * k + f.u[0] * along, m[1] + f.n[1] * k - f.u[1] * along] };
  };
  list.push({ whole: "bend", label: "B", ...off(30, 0) });
  list.push({ whole: "move", label: "M", ...off(60, 0) });
  list.push({ whole: "rotate", label: "R", ...off(60, -40) });
  const b = toScreen(f.B);
  list.push({ whole: "stretch", label: "S", screen: [b[0] + f.u[0] * 28, b[1] - f.u[1] * 28] });
  return list;
}

// The handles' circles (and labels) are made once per set of handles, then only moved: a drag redraws them at
// every pointer move, and moving is much cheaper than rebuilding.
function drawHandles() {
  const g = $("handles");
  if (!state.case) { g.replaceChildren(); delete g.dataset.keys; return; }
  const list = handleList();
  const keys = list.map((h) => (h.rigid !== undefined ? `rigid:${h.rigid}` : `${h.curve || "target"}:${h.whole || h.index}`)).join(",");
  if (g.dataset.keys !== keys) {
    g.replaceChildren();
    for (const h of list) {
      const c = document.createElementNS(NS, "circle");
      c.setAttribute("r", h.whole || h.rigid !== undefined ? 8 : 6);
      if (h.rigid !== undefined) { c.dataset.rigid = h.rigid; c.style.setProperty("--c", rigidColour(h.rigid)); }
      else {
        c.dataset.curve = h.curve || "target";
        if (h.whole) c.dataset.whole = h.whole; else c.dataset.index = h.index;
      }
      g.appendChild(c);
      if (h.label) {
        const t = document.createElementNS(NS, "text");
        t.setAttribute("class", "handle-label");
        t.textContent = h.label;
        c.label = t;
        g.appendChild(t);
      }
    }
    g.dataset.keys = keys;
  }
  const circles = g.getElementsByTagName("circle");
  list.forEach((h, i) => {
    const c = circles[i];
    const [x, y] = h.screen || toScreen(h.p);
    c.setAttribute("cx", x); c.setAttribute("cy", y);
    const sel = state.selected && !h.whole && state.selected.curve === h.curve && state.selected.index === h.index;
    c.setAttribute("class", "handle" + (h.curve === "upper" ? " upper" : "") + (h.whole ? " whole" : "") +
                   (h.rigid !== undefined ? " rigid" : "") + (sel ? " selected" : ""));
    c.handle = h;
    if (c.label) { c.label.setAttribute("x", x + 10); c.label.setAttribute("y", y + 4); }
  });
}

// ---- readouts ----------------------------------------------------------

// A figure as text: a whole number as it is, others to d + 2 digits, yes/no for a flag.
const fmt = (v, d = 4) => (v === null || v === undefined ? "—" : typeof v === "boolean" ? (v ? "yes" : "no")
  : typeof v !== "number" ? String(v) : Number.isInteger(v) ? String(v) : v.toPrecision(d + 2));

const expo = (v) => (v === null || v === undefined ? "—" : Number(v).toExponential(2));

// Area readouts, or volumes for a body of revolution (sums over an assembly's bodies, its worst law error).
function quantityLabels(volume) {
  const what = volume ? "volume" : "area";
  $("l-initial").textContent = "initial " + what;
  $("l-target").textContent = "target " + what;
  $("l-final").textContent = "final " + what;
  $("ratio-label").textContent = what + " ratio";
}


// The mesh's worst element: a layered mesh's smallest corner Jacobian (units²), or a finite-element
// solution's smallest area stretch det F (a ratio: below 0 an element is turned over).
function smallest(r) {
  if (r.jacobian_min != null) return fmt(r.jacobian_min, 3);
  if (r.det_f_min != null) return "det F " + fmt(r.det_f_min, 3);
  return "—";
}
function showBodies(res, u) {
  const table = $("bodies-readout");
  table.hidden = !res.assembly;
  if (!res.assembly) return;
  const vol = res.revolution;
  const unit = u + (vol ? "³" : "²");
  $("bodies-head").textContent = vol ? "volume final / target" : "area final / target";
  const rows = res.bodies.map((b, i) => {
    const tr = document.createElement("tr");
    tr.dataset.body = i;
    const cells = [b.name,
      vol ? `${fmt(b.volume_final)} / ${fmt(b.volume_target)} ${unit}` : `${fmt(b.area_final)} / ${fmt(b.area_target)} ${unit}`,
      expo(vol ? b.volume_error : b.relative_error), smallest(b)];
    cells.forEach((c, k) => {
      const td = document.createElement("td");
      td.textContent = c;
      if (k === 0) td.style.borderLeft = `0.6em solid ${colour(i)}`;
      tr.appendChild(td);
    });
    return tr;
  });
  $("bodies-rows").replaceChildren(...rows);
}

function showReadout(res, roundtrip) {
  const u = state.case.units || "";
  const vol = Boolean(res.revolution);
  const sum = (k) => res.bodies.reduce((s, b) => s + b[k], 0);
  quantityLabels(vol);
  const [q0, qt, q1] = vol ? [sum("volume_initial"), sum("volume_target"), sum("volume_final")]
                           : [res.area_initial, res.area_target, res.area_final];
  const unit = " " + u + (vol ? "³" : "²");
  $("r-initial").textContent = fmt(q0) + unit;
  $("r-target").textContent = fmt(qt) + unit;
  $("r-final").textContent = fmt(q1) + unit;
  $("r-error").textContent = expo(res.relative_error);
  showBodies(res, u);
  $("r-jacobian").textContent = smallest(res);
  showInfo(res);
  $("r-compute").textContent = res.compute_ms.toFixed(2) + " ms";
  $("r-roundtrip").textContent = roundtrip.toFixed(1) + " ms";
  $("r-state").textContent = (res.final ? "full deformation" : "preview") + ` (${res.model})`;
  const d = svg.dataset;
  d.seq = res.seq; d.final = res.final ? "1" : "0"; d.model = res.model;
  d.areaInitial = res.area_initial; d.areaTarget = res.area_target; d.areaFinal = res.area_final;
  d.relativeError = res.relative_error; d.jacobianMin = res.jacobian_min;
  const contours = res.assembly ? res.bodies.map((b) => b.contour) : [res.contour];
  d.contourHash = contours.map((c) => c.length + ":" + c.reduce((s, p) => s + p[0] * 1.3 + p[1] * 0.7, 0)).join(",");
  d.bodies = res.assembly ? JSON.stringify(res.bodies.map((b) => ({
    name: b.name, areaInitial: b.area_initial, areaTarget: b.area_target, areaFinal: b.area_final,
    relativeError: b.relative_error, volumeError: b.volume_error }))) : "";
  d.roundtripMs = roundtrip; d.computeMs = res.compute_ms;
}

// The model's figures as a table: one row per figure, one column per body.
function showInfo(res) {
  const bodies = res.assembly ? res.bodies : [res];
  const keys = [...new Set(bodies.flatMap((b) => Object.keys(b.info || {})))];
  const head = document.createElement("tr");
  for (const t of ["figure", ...(res.assembly ? bodies.map((b) => b.name) : [res.model + " model"])]) {
    const th = document.createElement("th"); th.textContent = t; head.appendChild(th);
  }
  $("info-head").replaceChildren(head);
  $("info-rows").replaceChildren(...keys.map((k) => {
    const tr = document.createElement("tr");
    tr.dataset.key = k;
    for (const t of [k.replace(/_/g, " "), ...bodies.map((b) => fmt((b.info || {})[k], 3))]) {
      const td = document.createElement("td"); td.textContent = t; tr.appendChild(td);
    }
    return tr;
  }));
}

// The warnings of the answer on screen (and only of it), in the warning colour.
function showWarnings(list) {
  const w = $("warnings");
  w.textContent = list && list.length ? "warning: " + list.join("; ") : "";
  w.hidden = !w.textContent;
}

function message(text, kind) {
  const m = $("message");
  m.textContent = text || "";
  m.dataset.kind = text ? kind : "none";
}

// ---- the live link -----------------------------------------------------

let socket = null;
let queued = null;
let retries = 0;       // reconnection attempts since the connection was lost
let resend = false;    // on reconnecting, send the page's current state again

// The live link. When it drops (the server restarted, the network), the page reconnects by itself, waiting
// longer after each failed attempt (RETRY_MS, doubling up to RETRY_MAX_MS), keeps every edit meanwhile, and
// once connected sends its current state again: the answer on screen is then the server's for the case
// being edited. Only a refusal of the page itself (wrong token, 1008) or a full server (1013) stops it.
const RETRY_MS = 250, RETRY_MAX_MS = 5000;
function connect() {
  socket = new WebSocket(`ws://${location.host}/ws`);
  socket.binaryType = "arraybuffer";
  socket.onmessage = (e) => {
    const t = performance.now();
    onAnswer(typeof e.data === "string" ? JSON.parse(e.data) : unframe(e.data), t);
  };
  socket.onopen = () => {
    svg.dataset.connected = "1";
    const again = retries > 0;
    retries = 0;
    if (again) {
      svg.dataset.reconnects = Number(svg.dataset.reconnects || 0) + 1;
      queued = null;
      if (resend && state.case) { message("reconnected to the server; the case being edited was sent again", "info"); request(true); }
      else message("reconnected to the server", "info");
    } else if (queued) { socket.send(queued); queued = null; }
  };
  socket.onclose = (e) => {
    svg.dataset.closed = String(e.code);
    svg.dataset.connected = "0";
    if (e.code === 1013) return;   // the server is full: its refusal, already shown, says so
    if (e.code === 1008) { message(CLOSED[1008], "error"); return; }
    if (retries === 0) resend = e.code !== 1009;   // a case too large would be refused again
    const wait = Math.min(RETRY_MAX_MS, RETRY_MS * 2 ** retries);
    retries += 1;
    message((CLOSED[e.code] || "connection to the server lost") +
            `; reconnecting in ${(wait / 1000).toFixed(1)} s (attempt ${retries}); your edits are kept`, "error");
    setTimeout(retry, wait);
  };
}
// A refused handshake looks like a lost connection (1006): after two failures, ask the server whether it still
// knows this page's token (a restart with a new one: reconnecting cannot help).
async function retry() {
  if (retries >= 2) {
    try {
      const r = await fetch("/api/start", { cache: "no-store" });
      if (r.status === 403) { svg.dataset.closed = "1008"; message(CLOSED[1008], "error"); return; }
    } catch (err) { /* the server is still down: try the WebSocket again */ }
  }
  connect();
}
const CLOSED = {
  1008: "the server refused this page (wrong or missing token; it may have restarted with a new one): open the " +
        "address the serve command printed in this tab; the case being edited is kept in it",
  1009: "the case is too large to send to the server; simplify it (open it again with the simplify option)",
};

function request(final, t0) {
  state.seq += 1;
  state.sent.set(state.seq, t0 === undefined ? performance.now() : t0);
  if (!isAssembly()) state.case.law = { area_ratio: state.ratio };   // an assembly's laws are its bodies' (setRatio)
  const req = { seq: state.seq, final, case: state.case, model: state.model, ratio: state.ratio };
  if (final && state.field) req.field = state.field;
  if (final) keep();
  const text = JSON.stringify(req);
  if (socket.readyState === WebSocket.OPEN) socket.send(text); else queued = text;
  state.sentAt.set(state.seq, performance.now());
  svg.dataset.pending = state.seq;
}

// A result comes as one binary frame: uint32 n, n bytes of JSON header, then float64 data (8-byte aligned);
// each array of the header is {f64: [byte offset in the data, count, columns]}. Arrays become Float64Arrays
// (flat x, y pairs), read in place.
const utf8 = new TextDecoder();
function unframe(buf) {
  const n = new DataView(buf).getUint32(0, true);
  const base = 4 + n;
  const head = JSON.parse(utf8.decode(new Uint8Array(buf, 4, n)));
  const arrays = (v) => {
    if (Array.isArray(v)) {   // an assembly's bodies; not the meshes' cells
      if (v.length && v[0] && typeof v[0] === "object" && !Array.isArray(v[0])) v.forEach((x, i) => { v[i] = arrays(x); });
      return v;
    }
    if (!v || typeof v !== "object") return v;
    if (Array.isArray(v.f64)) return new Float64Array(buf, base + v.f64[0], v.f64[1]);
    for (const k in v) v[k] = arrays(v[k]);
    return v;
  };
  return arrays(head);
}

// Flat x, y values as [[x, y], ...].
function pairs(f) {
  if (!f) return f;
  const out = new Array(f.length / 2);
  for (let i = 0; i < out.length; i++) out[i] = [f[2 * i], f[2 * i + 1]];
  return out;
}

function onAnswer(msg, received) {
  if (msg.type === "dropped") { state.sent.delete(msg.seq); return; }
  if (msg.seq !== null && msg.seq <= state.shown) return;          // stale: a newer answer is drawn
  const t0 = state.sent.get(msg.seq), t1 = state.sentAt.get(msg.seq);
  if (msg.seq !== null) state.shown = msg.seq;
  for (const k of state.sent.keys()) if (k <= msg.seq) state.sent.delete(k);
  for (const k of state.sentAt.keys()) if (k <= msg.seq) state.sentAt.delete(k);
  if (msg.type === "refused") {
    flushEdits();
    // the library's line is the message's; the parts' panel only greys its figures and says which model refused
    // (a request the server could not read carries no model: the server refused it)
    const who = msg.model ? `the ${msg.model} model` : "the server", last = state.result;
    const rigidRefused = rigidCase().length > 0 && /^rigid\b/.test(msg.message);
    $("rigid-note").hidden = !rigidRefused;
    $("rigid-note").textContent = rigidRefused ? `not solved by ${who}` : "";
    state.refused = true;
    showRigid();
    svg.classList.add("refused");
    svg.dataset.refusedSeq = msg.seq;
    $("r-state").textContent = last ? `last good shape: ${last.final ? "full deformation" : "preview"} (${last.model}); ` +
                                      `${who} refused` : `${who} refused; the section as drawn`;
    message("refused: " + msg.message + (last ? " (the last good shape is kept)" : ""), "error");
    return;
  }
  svg.classList.remove("refused");
  // a preview sends only what moves; the rest comes with each full deformation and each new section
  const last = state.result;
  msg.lower = pairs(msg.lower);
  if (msg.assembly) {
    msg.initialSent = Boolean(msg.bodies[0].initial_contour);
    const before = last && last.assembly && last.bodies.length === msg.bodies.length ? last.bodies : null;
    msg.bodies.forEach((b, i) => {
      b.contour = pairs(b.contour); b.initial_contour = pairs(b.initial_contour);
      b.holes = (b.holes || []).map(pairs); b.initial_holes = b.initial_holes && b.initial_holes.map(pairs);
      if (!msg.initialSent && before) {
        b.initial_contour = before[i].initial_contour;
        b.initial_holes = before[i].initial_holes;
        b.mesh_initial = before[i].mesh_initial;
        if (b.mesh_final && before[i].mesh_final) b.mesh_final.cells = before[i].mesh_final.cells;
      }
    });
  } else {
    msg.initialSent = Boolean(msg.initial_contour);
    for (const k of ["contour", "initial_contour"]) msg[k] = pairs(msg[k]);
    msg.holes = (msg.holes || []).map(pairs); msg.initial_holes = msg.initial_holes && msg.initial_holes.map(pairs);
  }
  if (!msg.assembly && !msg.initialSent && last) {
    msg.initial_contour = last.initial_contour;
    msg.initial_holes = last.initial_holes;
    msg.mesh_initial = last.mesh_initial;
    if (msg.mesh_final && last.mesh_final) msg.mesh_final.cells = last.mesh_final.cells;
  }
  state.result = msg;
  state.refused = false;
  if (msg.final) { takeContact(msg); $("rigid-note").hidden = true; }
  drawResult();
  drawRigid();
  showRigid();
  if (state.editsPending) flushEdits(); else if (!state.drag) drawHandles();
  const now = performance.now();
  if (t0 !== undefined) {
    state.latencies.push({ seq: msg.seq, ms: now - t0, compute: msg.compute_ms, final: msg.final,
                           send: t1 - t0, wait: received - t1, draw: now - received });
  }
  showReadout(msg, t0 === undefined ? NaN : now - t0);
  if ($("message").dataset.kind === "error") message("", "none");
  showWarnings(msg.warnings);
  $("field-note").hidden = !(msg.field && msg.field.error);
  $("field-note").textContent = msg.field && msg.field.error ? msg.field.error : "";
  if (state.probe && state.probe.length) drawProbe();
  // fitted to the outline before the answer: fitted again to the answer (with the deformed section) unless moved since
  if (state.fitPending) { state.fitPending = false; if (state.fitted === JSON.stringify(state.view)) fit(); }
}

// ---- editing -----------------------------------------------------------

function snapshot() {
  return { target: clone(state.case.target), upper: clone(state.case.upper), ratio: state.ratio,
           laws: isAssembly() ? state.case.bodies.map((b) => clone(b.law)) : null, rigid: clone(state.case.rigid) };
}

// The whole page's case, before a reset or an opened file replaces it: undo brings it back.
function wholeSnapshot() {
  return { whole: true, case: clone(state.case), model: state.model, ratio: state.ratio, body: state.body,
           opened: state.opened, openedModel: state.openedModel, outline: state.outline, saved: state.saved,
           rigidOutline: state.parts.map((p) => (p.outline ? { contour: p.outline, travel: p.at } : null)),
           openedRigid: state.openedRigid,
           name: $("case-name").textContent };
}

// ---- unsaved edits -------------------------------------------------------

// What an edit changes: the case (target, section, laws), the model and the ratio.
function editKey() {
  if (!state.case) return "";
  if (!isAssembly()) state.case.law = { area_ratio: state.ratio };
  return JSON.stringify([state.case, state.model]);
}
// True if the case on the page differs from the one last opened or saved as a case file.
const dirty = () => Boolean(state.case) && editKey() !== state.saved;
// Ask before `what` replaces unsaved edits (it can be undone, say so); true to go on.
function mayReplace(what) {
  return !dirty() || window.confirm(`${what} replaces the edits not saved as a case file. Go on? (Ctrl+Z or undo brings them back)`);
}
window.addEventListener("beforeunload", (e) => {
  if (!dirty()) return;
  e.preventDefault();
  e.returnValue = "";   // the browser asks whether to leave the page
});
// The case being edited, kept in this tab (sessionStorage): a page reopened here after the server restarted
// with a new token takes it back.
const KEPT = "sectiondeform-edits";
function keep() {
  try {
    if (dirty()) sessionStorage.setItem(KEPT, JSON.stringify({ case: state.case, model: state.model, ratio: state.ratio,
                                                               opened: state.opened, openedModel: state.openedModel }));
    else sessionStorage.removeItem(KEPT);
  } catch (err) { /* storage full or off: the prompts still guard the edits */ }
}

function setPoints(curve, P) {
  const made = Geo.withPoints(state.case[curve], P);
  if (!made) return false;
  state.case[curve] = made;
  return true;
}

svg.addEventListener("pointerdown", (e) => {
  const t0 = performance.now();
  svg.focus();
  const h = e.target.handle;
  if (h && h.rigid !== undefined) {   // a rigid part's end, moved along its travel
    e.preventDefault();
    svg.setPointerCapture(e.pointerId);
    state.undo.push(snapshot());
    state.drag = { h, rigid: h.rigid, from: toWorld(e), s0: alongTravel(h.rigid), moved: false };
  } else if (h) {
    e.preventDefault();
    svg.setPointerCapture(e.pointerId);
    state.undo.push(snapshot());
    const curve = h.whole ? "target" : h.curve;
    state.drag = { h, curve, from: toWorld(e), P0: Geo.points(state.case[curve]), moved: false };
    if (!h.whole) { state.selected = { curve: h.curve, index: h.index }; drawHandles(); }
  } else {
    svg.setPointerCapture(e.pointerId);
    state.drag = { pan: true, x: e.clientX, y: e.clientY, tx: state.view.tx, ty: state.view.ty };
  }
});

// With the probe on, a click on the background (a press and release without moving) places a point:
// the first is measured to the lower curve, the second to the first; a third starts again.
function probeClick(e, d) {
  if (!state.probe || !d || !d.pan || Math.hypot(e.clientX - d.x, e.clientY - d.y) > 3) return;
  if (state.probe.length >= 2) state.probe = [];
  state.probe.push(toWorld(e));
  drawProbe();
}

svg.addEventListener("pointermove", (e) => {
  const t0 = performance.now();
  const d = state.drag;
  if (!d || d.pan) showPointer(e);
  if (!d) return;
  if (d.pan) {
    state.view.tx = d.tx + e.clientX - d.x; state.view.ty = d.ty + e.clientY - d.y;
    applyView();
    return;
  }
  const to = toWorld(e);
  if (d.rigid !== undefined) {   // previewed as it moves (the contact linearised about the last full solve), solved on release
    const step = niceStep(1 / state.view.s);   // a round travel, to about a screen pixel
    const s = Math.max(0, d.s0 + Geo.dot(Geo.sub(to, d.from), state.parts[d.rigid].dir));
    const before = JSON.stringify(rigidCase()[d.rigid].travel);
    setTravel(d.rigid, Number(numText(Math.round(s / step) * step, step)));
    d.moved = true;
    drawEdits(); showRigid();
    if (JSON.stringify(rigidCase()[d.rigid].travel) !== before) request(false, t0);
    return;
  }
  let P;
  if (d.h.whole) P = Geo.wholeEdit(d.h.whole, d.P0, d.from, to);
  else {
    P = d.P0.map((p) => p.slice());
    P[d.h.index] = [d.P0[d.h.index][0] + to[0] - d.from[0], d.P0[d.h.index][1] + to[1] - d.from[1]];
  }
  if (!setPoints(d.curve, P)) return;
  d.moved = true;
  request(false, t0);
  editLater();
});

// While dragging, the edited curve is drawn with the answer to its request, in the same frame. Drawn at
// once, it would make the browser render a frame for it alone (style, layout, paint, commit: several ms
// on a busy machine) while the answer, ready sooner, waits behind it. An answer that takes longer than
// EDIT_WAIT ms (a slow model, a section being prepared) lets the edit be drawn alone meanwhile.
const EDIT_WAIT = 20;
let editTimer = 0;
function editLater() {
  state.editsPending = true;
  if (!editTimer) editTimer = setTimeout(flushEdits, EDIT_WAIT);
}
function flushEdits() {
  clearTimeout(editTimer);
  editTimer = 0;
  if (state.editsPending) { state.editsPending = false; drawEdits(); }
}

function endDrag(e) {
  const d = state.drag;
  state.drag = null;
  if (d && d.pan && e.type === "pointerup") probeClick(e, d);
  if (!d || d.pan) return;
  flushEdits();
  if (d.moved) request(true); else state.undo.pop();
}
svg.addEventListener("pointerup", endDrag);
svg.addEventListener("pointercancel", endDrag);

svg.addEventListener("wheel", (e) => {
  e.preventDefault();
  const r = svg.getBoundingClientRect();
  const x = e.clientX - r.left, y = e.clientY - r.top;
  const k = Math.exp(-e.deltaY * 0.0015);
  const v = state.view;
  v.tx = x - (x - v.tx) * k; v.ty = y - (y - v.ty) * k; v.s *= k;
  applyView();
}, { passive: false });

function undo() {
  const s = state.undo.pop();
  if (!s) return;
  if (s.whole) { restore(s); return; }
  state.case.target = s.target;
  if (s.laws) { s.laws.forEach((law, i) => { state.case.bodies[i].law = law; }); showRatio(); }
  else { state.case.upper = s.upper; setRatio(s.ratio); }
  if (s.model) setModel(s.model);
  if (s.rigid) state.case.rigid = s.rigid;
  drawEdits(); showRigid(); request(true);
}

// The law key of an assembly's body: its own, else the volume ratio for a body of revolution.
function lawKey(body) {
  const own = body.law && Object.keys(body.law)[0];
  return own === "area_ratio" || own === "volume_ratio" ? own : (state.case.revolution ? "volume_ratio" : "area_ratio");
}

// The slider's ratio: the case's law, or the law of the assembly's selected body.
function setRatio(r) {
  state.ratio = r;
  $("ratio").value = r;
  $("ratio-value").value = Number(r).toFixed(3);
  if (isAssembly()) {
    const body = state.case.bodies[state.body];
    body.law = { [lawKey(body)]: r };
  }
}

// Show the selected body's ratio (and its kind) on the slider, changing nothing.
function showRatio() {
  const body = state.case.bodies[state.body];
  const key = lawKey(body);
  const r = body.law && typeof body.law[key] === "number" ? body.law[key] : 1;
  state.ratio = r;
  $("ratio").value = r;
  $("ratio-value").value = Number(r).toFixed(3);
  $("ratio-label").textContent = key === "volume_ratio" ? "volume ratio" : "area ratio";
}

document.addEventListener("keydown", (e) => {
  if (e.target.tagName === "INPUT" || e.target.tagName === "SELECT") return;
  if ((e.ctrlKey || e.metaKey) && e.key === "z") { e.preventDefault(); undo(); return; }
  if (e.key === "f" || e.key === "F") { fit(); return; }
  if (e.key === "p" || e.key === "P") { setProbe(!state.probe); return; }
  const dirs = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1] };
  const sel = state.selected;
  if (!sel || !dirs[e.key]) return;
  e.preventDefault();
  const step = (e.shiftKey ? 10 : 1) / state.view.s;     // one screen pixel (ten with Shift)
  state.undo.push(snapshot());
  const P = Geo.points(state.case[sel.curve]);
  P[sel.index] = [P[sel.index][0] + dirs[e.key][0] * step, P[sel.index][1] + dirs[e.key][1] * step];
  if (setPoints(sel.curve, P)) { drawEdits(); request(true); } else state.undo.pop();
});

$("ratio").addEventListener("pointerdown", () => state.undo.push(snapshot()));
$("ratio").addEventListener("input", (e) => { setRatio(Number(e.target.value)); request(false); });
$("ratio").addEventListener("change", () => request(true));
$("ratio-value").addEventListener("change", (e) => {
  const r = Number(e.target.value);
  if (!(r > 0)) { message($("ratio-label").textContent + ": must be a number > 0", "error"); return; }
  state.undo.push(snapshot());
  setRatio(r);
  request(true);
});
$("body").addEventListener("change", (e) => { state.body = Number(e.target.value); showRatio(); });
// A model change: the warnings on screen were the other model's; the stresses exist for the hyperelastic model only.
$("model").addEventListener("change", (e) => {
  state.undo.push({ ...snapshot(), model: state.model });
  setModel(e.target.value);
  request(true);
});
function setModel(model) {
  state.model = model;
  $("model").value = model;
  showWarnings([]);
  for (const o of $("field").options) o.disabled = Boolean(o.dataset.stress) && model !== "hyperelastic";
  if ($("field").selectedOptions[0].disabled) { $("field").value = ""; state.field = ""; }
}
$("field").addEventListener("change", (e) => { state.field = e.target.value; drawField(null); if (state.field) request(true); });
$("probe").addEventListener("click", () => setProbe(!state.probe));
$("show-mesh").addEventListener("change", () => drawResult(true));
$("undo").addEventListener("click", undo);
$("fit").addEventListener("click", fit);
$("reset").addEventListener("click", () => {
  if (!mayReplace("Reset")) return;
  load({ case: state.opened, model: state.openedModel, outline: state.openedOutline, rigid: state.openedRigid }, false, true);
});

// ---- files -------------------------------------------------------------

// Show a case: opened (a file, the server's start, a reset) or brought back by undo. `undoable`: the case it
// replaces goes on the undo stack; otherwise the stack starts empty.
function load(data, refit = true, undoable = false) {
  if (undoable && state.case) state.undo.push(wholeSnapshot()); else state.undo = [];
  state.opened = clone(data.case);
  state.openedModel = data.model || "paper";
  state.openedOutline = data.outline || null;
  state.openedRigid = data.rigid || null;
  show(data.case, state.openedModel, data.outline || null, refit, undefined, undefined, data.rigid);
  state.saved = editKey();
  keep();
  request(true);
}

// Undo of a reset or an opened file: the case before it, with what it was opened from.
function restore(s) {
  state.opened = s.opened; state.openedModel = s.openedModel; state.openedRigid = s.openedRigid;
  show(s.case, s.model, s.outline, true, s.ratio, s.body, s.rigidOutline);
  state.saved = s.saved;
  $("case-name").textContent = s.name;
  keep();
  request(true);
}

// Put a case on the page, drawn at once from its own curves (`outline`) until the server's answer comes.
function show(caseJson, model, outline, refit, ratio, body, rigid) {
  state.case = clone(caseJson);
  state.contact = null;
  setParts(rigid);
  $("rigid-parts").replaceChildren();
  $("rigid-note").hidden = true;
  showRigid();
  drawRigid();
  setModel(model);
  state.body = body || 0;
  state.outline = outline;
  const bodies = isAssembly() ? state.case.bodies : [];
  $("body").replaceChildren(...bodies.map((b, i) => new Option(b.name || `body ${i}`, i)));
  $("body-label").hidden = !bodies.length;
  $("assembly-hint").hidden = bodies.length < 2;   // one body: nothing for the body list to pick
  svg.classList.remove("refused");
  if (bodies.length) { $("body").value = state.body; showRatio(); quantityLabels(Boolean(state.case.revolution)); }
  else {
    setRatio(ratio !== undefined ? ratio : caseJson.law && caseJson.law.area_ratio !== undefined ? caseJson.law.area_ratio : 0.8);
    quantityLabels(false);
  }
  $("bodies-readout").hidden = true;
  showOutlineReadout();
  state.selected = null;
  $("case-name").textContent = caseJson.name || "";
  state.result = null;
  showWarnings([]);
  drawResult(true);
  state.fitPending = refit;
  state.fitted = JSON.stringify(state.view);
  if (refit && state.outline) fit(); else { drawEdits(); drawAxes(); }
}

// Until the first answer: the areas from the case's own curves, the rest "computing".
function showOutlineReadout() {
  const waiting = "computing…";
  for (const id of ["final", "error", "jacobian", "compute", "roundtrip"]) $("r-" + id).textContent = waiting;
  $("r-state").textContent = "sent to the server";
  $("info-head").replaceChildren(); $("info-rows").replaceChildren();
  const u = " " + units() + "²";
  const areas = state.outline && !state.case.revolution ? state.outline.map((b) => b.area) : null;
  if (!areas) { $("r-initial").textContent = waiting; $("r-target").textContent = waiting; return; }
  const ratios = isAssembly() ? state.case.bodies.map((b) => (b.law && b.law.area_ratio) || NaN) : [state.ratio];
  const total = areas.reduce((s, a) => s + a, 0), target = areas.reduce((s, a, i) => s + ratios[i] * a, 0);
  $("r-initial").textContent = fmt(total) + u;
  $("r-target").textContent = Number.isFinite(target) ? fmt(target) + u : waiting;
}

// The drawing options of the form, by their library names (the server checks them: one line if wrong).
// Lists are split at commas; what is not a number is sent as typed, for the library to name.
function drawingOptions() {
  const list = (id) => $(id).value.split(/[,;\s]+/).filter((t) => t !== "").map((t) => (Number.isFinite(Number(t)) ? Number(t) : t));
  const out = {};
  for (const [id, key] of [["o-snap", "snap"], ["o-close-gap", "close_gap"], ["o-join-tol", "join_tol"],
                           ["o-target-arc", "target_arc"], ["o-simplify", "simplify"], ["o-split-tol", "split_tol"],
                           ["o-chordal-error", "chordal_error"]]) {
    if ($(id).value !== "") out[key] = Number($(id).value);
  }
  if ($("o-bbox").value.trim()) out.bbox = list("o-bbox");
  if ($("o-split-a").value.trim() || $("o-split-b").value.trim()) out.split = [list("o-split-a"), list("o-split-b")];
  if ($("o-lower-side").value) out.lower_side = $("o-lower-side").value;
  if ($("o-units").value) out.units = $("o-units").value;
  if ($("o-layers").value.trim()) {
    out.layers = {};
    for (const item of $("o-layers").value.split(",")) {
      const [role, name] = item.split("=").map((t) => t.trim());
      if (role) out.layers[role] = name || "";
    }
  }
  return out;
}

async function openFile(file) {
  if (!mayReplace(`Opening ${file.name}`)) return;
  const form = new FormData();
  form.append("file", file);
  if ($("o-area-ratio").value !== "") form.append("area_ratio", $("o-area-ratio").value);
  form.append("options", JSON.stringify(drawingOptions()));
  try {
    const r = await fetch("/api/open", { method: "POST", body: form });
    if (!r.ok) { message(`cannot open ${file.name}: ${await failure(r)}`, "error"); return; }
    const data = await r.json();
    load(data, true, true);
    message(`opened ${file.name}` + (data.report.length ? ": " + data.report.join("; ") : ""), "info");
  } catch (err) {
    message(`cannot open ${file.name}: ${err}`, "error");
  }
}

$("file").addEventListener("change", (e) => { if (e.target.files[0]) openFile(e.target.files[0]); e.target.value = ""; });
document.addEventListener("dragover", (e) => { e.preventDefault(); $("drop").hidden = false; });
document.addEventListener("dragleave", (e) => { if (!e.relatedTarget) $("drop").hidden = true; });
document.addEventListener("drop", (e) => {
  e.preventDefault();
  $("drop").hidden = true;
  if (e.dataTransfer.files[0]) openFile(e.dataTransfer.files[0]);
});

function download(blob, name) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.appendChild(a);
  a.click();
  setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
}

// The one line a failed request gets: the server's own message, else the HTTP status.
async function failure(r) {
  try { return (await r.json()).error || `HTTP ${r.status}`; } catch (err) { return `HTTP ${r.status}`; }
}

document.querySelectorAll("[data-save]").forEach((b) => b.addEventListener("click", async () => {
  const name = b.dataset.save;
  const sent = editKey();   // sets a one-body case's law from the slider (an assembly's laws are its bodies')
  try {
    const r = await fetch("/api/save/" + name, {
      method: "POST", headers: { "Content-Type": "application/json" },
      body: JSON.stringify({ case: state.case, model: state.model }),
    });
    if (!r.ok) { message(`not saved: ${name}: ${await failure(r)}`, "error"); return; }
    download(await r.blob(), (state.case.name || "section") + "-" + name);
    if (name.startsWith("case.") && sent === editKey()) { state.saved = sent; keep(); }
  } catch (err) {
    message(`not saved: ${name}: the server cannot be reached (${err.message || err}); nothing was written`, "error");
  }
}));


window.addEventListener("resize", () => applyView());
svg.addEventListener("pointerleave", () => { $("r-pointer").textContent = "—"; });

// ---- start -------------------------------------------------------------

// The address carried the run's token: the server has set it as a cookie; keep it off the address bar.
if (new URLSearchParams(location.search).has("token")) history.replaceState(null, "", location.pathname);
connect();
fetch("/api/start").then((r) => r.json()).then((data) => {
  let kept = null;
  try { kept = JSON.parse(sessionStorage.getItem(KEPT) || "null"); } catch (err) { kept = null; }
  load(data);
  if (kept && kept.case) {   // edits of this tab not saved before the page was left: back, one undo away
    state.undo.push(wholeSnapshot());
    state.opened = kept.opened || kept.case; state.openedModel = kept.openedModel || kept.model;
    state.openedOutline = null;
    show(kept.case, kept.model, null, true, kept.ratio);
    keep();
    request(true);
    message("the edits not saved before this page was left are back (undo shows the case the server started with)", "info");
  }
});
