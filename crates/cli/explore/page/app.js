// impact explore: the page. Plain JavaScript, no dependencies, nothing
// fetched but this server's own API. The state lives in the URL.
"use strict";

const $ = (id) => document.getElementById(id);

// ---------------------------------------------------------------- state

const state = {
  mode: "bilayer", // or "scene": the layers as edited
  x: 0.4,
  alpha: 0.05,
  layers: [], // {material, length, modulus, density, visc: "none"|"tau"|"e", viscValue}
  speed: 1,
  units: "reduced",
  engine: "auto",
  n: "",
  wall: "paper",
  window: null, // [t0, t1] or null: the whole impact
  sideBySide: false,
  chainN: 2000,
  quantity: "restitution",
  overlays: { tenth: true, boundary: true, xn: true, iso: true },
};

let materials = [];
let map = null; // the finest map received so far
let lastRun = null; // the last run's JSON
let lastDiagram = null; // the last diagram reply
let inflight = null; // AbortController of the point's requests

function canonicalLayers(x, alpha) {
  return [
    { material: "", length: 1 - x, modulus: 1 - alpha, density: 1, visc: "none", viscValue: "" },
    { material: "", length: x, modulus: alpha, density: 1, visc: "none", viscValue: "" },
  ];
}

function round6(v) {
  return Number(Number(v).toFixed(6));
}

// ------------------------------------------------------------ URL state

function saveUrl() {
  const p = new URLSearchParams();
  p.set("q", state.quantity);
  p.set("ov", ["tenth", "boundary", "xn", "iso"].filter((k) => state.overlays[k]).join(","));
  if (state.mode === "bilayer") {
    p.set("x", state.x);
    p.set("alpha", state.alpha);
  } else {
    p.set("layers", JSON.stringify(state.layers.map((l) => [l.material, l.length, l.modulus, l.density, l.visc, l.viscValue])));
    p.set("speed", state.speed);
    p.set("units", state.units);
  }
  if (state.engine !== "auto") p.set("engine", state.engine);
  if (state.n !== "") p.set("n", state.n);
  if (state.wall !== "paper") p.set("wall", state.wall);
  if (state.window) p.set("t", state.window.map((v) => round6(v)).join(","));
  if (state.sideBySide) p.set("sbs", "1");
  if (state.chainN !== 2000) p.set("cn", state.chainN);
  history.replaceState(null, "", "?" + p.toString());
}

function loadUrl() {
  const p = new URLSearchParams(location.search);
  if (p.has("q")) state.quantity = p.get("q");
  if (p.has("ov")) {
    const on = p.get("ov").split(",");
    for (const k of Object.keys(state.overlays)) state.overlays[k] = on.includes(k);
  }
  if (p.has("layers")) {
    try {
      state.layers = JSON.parse(p.get("layers")).map((r) => ({
        material: r[0] || "", length: r[1], modulus: r[2], density: r[3], visc: r[4] || "none", viscValue: r[5] ?? "",
      }));
      state.mode = "scene";
    } catch (e) {
      state.layers = [];
    }
  }
  if (p.has("x")) state.x = Number(p.get("x"));
  if (p.has("alpha")) state.alpha = Number(p.get("alpha"));
  if (p.has("speed")) state.speed = p.get("speed");
  if (p.has("units")) state.units = p.get("units");
  if (p.has("engine")) state.engine = p.get("engine");
  if (p.has("n")) state.n = p.get("n");
  if (p.has("wall")) state.wall = p.get("wall");
  if (p.has("t")) {
    const t = p.get("t").split(",").map(Number);
    if (t.length === 2 && t.every(Number.isFinite) && t[0] < t[1]) state.window = t;
  }
  state.sideBySide = p.get("sbs") === "1";
  if (p.has("cn")) state.chainN = Number(p.get("cn"));
  return p.toString() !== "";
}

// ------------------------------------------------------------------ map

const MAP = { left: 44, right: 8, top: 8, bottom: 36 };

// viridis, sampled: value in [0, 1] to rgb
const VIRIDIS = [
  [68, 1, 84], [72, 40, 120], [62, 74, 137], [49, 104, 142], [38, 130, 142],
  [31, 158, 137], [53, 183, 121], [110, 206, 88], [181, 222, 43], [253, 231, 37],
];
const CATEGORIES = [
  [200, 200, 200], [49, 104, 142], [53, 183, 121], [253, 231, 37], [243, 120, 60],
  [200, 40, 70], [120, 30, 120], [40, 40, 40], [150, 90, 40], [0, 150, 200],
];

function viridis(t) {
  t = Math.min(1, Math.max(0, t));
  const f = t * (VIRIDIS.length - 1);
  const i = Math.min(VIRIDIS.length - 2, Math.floor(f));
  const u = f - i;
  return VIRIDIS[i].map((c, k) => Math.round(c + u * (VIRIDIS[i + 1][k] - c)));
}

function scaleOf(values, quantity) {
  if (quantity === "restitution") return [0, 1];
  let lo = Infinity, hi = -Infinity;
  for (const v of values) if (v !== null) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  if (quantity === "bounces") return [1, Math.max(hi, 2)];
  if (!(hi > lo)) hi = lo + 1;
  return [Math.min(lo, 0), hi];
}

function colour(v, quantity, scale) {
  if (v === null || v === undefined) return [255, 255, 255];
  if (quantity === "bounces") return CATEGORIES[Math.min(v, CATEGORIES.length - 1)];
  return viridis((v - scale[0]) / (scale[1] - scale[0]));
}

function plotBox(canvas) {
  return { x0: MAP.left, y0: MAP.top, w: canvas.width - MAP.left - MAP.right, h: canvas.height - MAP.top - MAP.bottom };
}

function toPixel(box, x, a) {
  return [box.x0 + x * box.w, box.y0 + (1 - a) * box.h];
}

function levelsOf(quantity, scale) {
  if (quantity === "restitution") return [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9];
  if (quantity === "bounces") {
    const out = [];
    for (let k = 1; k < Math.min(scale[1], 12); k++) out.push(k + 0.5);
    return out;
  }
  const out = [];
  for (let k = 1; k < 8; k++) out.push(scale[0] + (k * (scale[1] - scale[0])) / 8);
  return out;
}

// Marching squares on the grid: segments of the level set between cell
// centres, interpolated linearly along the cell edges.
function isolines(ctx, box, values, level) {
  const nx = map.x.length, na = map.alpha.length;
  const at = (i, j) => values[j * nx + i];
  ctx.beginPath();
  for (let j = 0; j + 1 < na; j++) {
    for (let i = 0; i + 1 < nx; i++) {
      const c = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
      if (c.some((v) => v === null)) continue;
      const p = [[map.x[i], map.alpha[j]], [map.x[i + 1], map.alpha[j]], [map.x[i + 1], map.alpha[j + 1]], [map.x[i], map.alpha[j + 1]]];
      const pts = [];
      for (let k = 0; k < 4; k++) {
        const a = c[k], b = c[(k + 1) % 4];
        if ((a < level) !== (b < level)) {
          const u = (level - a) / (b - a);
          const q0 = p[k], q1 = p[(k + 1) % 4];
          pts.push([q0[0] + u * (q1[0] - q0[0]), q0[1] + u * (q1[1] - q0[1])]);
        }
      }
      for (let k = 0; k + 1 < pts.length; k += 2) {
        const [x0, y0] = toPixel(box, pts[k][0], pts[k][1]);
        const [x1, y1] = toPixel(box, pts[k + 1][0], pts[k + 1][1]);
        ctx.moveTo(x0, y0);
        ctx.lineTo(x1, y1);
      }
    }
  }
  ctx.stroke();
}

function drawMap() {
  const canvas = $("map");
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  ctx.fillStyle = "white";
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  if (!map) return;
  const box = plotBox(canvas);
  const q = state.quantity;
  const values = map[q];
  const scale = scaleOf(values, q);
  const h = map.step;
  const nx = map.x.length;
  for (let j = 0; j < map.alpha.length; j++) {
    for (let i = 0; i < nx; i++) {
      const [r, g, b] = colour(values[j * nx + i], q, scale);
      ctx.fillStyle = `rgb(${r},${g},${b})`;
      const [px, py] = toPixel(box, map.x[i] - h / 2, map.alpha[j] + h / 2);
      ctx.fillRect(Math.floor(px), Math.floor(py), Math.ceil(h * box.w) + 1, Math.ceil(h * box.h) + 1);
    }
  }
  if (state.overlays.iso) {
    ctx.strokeStyle = "rgba(0,0,0,0.45)";
    ctx.lineWidth = 0.8;
    for (const level of levelsOf(q, scale)) isolines(ctx, box, values, level);
  }
  const ov = map.overlays;
  ctx.lineWidth = 1.5;
  const hline = (a, colour, label) => {
    const [x0, y] = toPixel(box, 0, a);
    const [x1] = toPixel(box, 1, a);
    ctx.strokeStyle = colour;
    ctx.setLineDash([6, 4]);
    ctx.beginPath(); ctx.moveTo(x0, y); ctx.lineTo(x1, y); ctx.stroke();
    ctx.setLineDash([]);
    ctx.fillStyle = colour;
    ctx.font = "11px sans-serif";
    ctx.fillText(label, x1 - ctx.measureText(label).width - 4, y - 4);
  };
  if (state.overlays.tenth) hline(ov.alpha_tenth, "#ffffff", "α = 0.1");
  if (state.overlays.boundary) hline(ov.upper_boundary, "#ffffff", `α = ${ov.upper_boundary.toFixed(4)}`);
  if (state.overlays.xn) {
    ctx.strokeStyle = "rgba(255,255,255,0.85)";
    ctx.lineWidth = 1;
    ov.x_n.forEach((curve, n) => {
      ctx.beginPath();
      curve.forEach((x, j) => {
        const [px, py] = toPixel(box, x, map.alpha[j]);
        if (j === 0) ctx.moveTo(px, py); else ctx.lineTo(px, py);
      });
      ctx.stroke();
      const j = Math.floor(map.alpha.length * (0.45 + 0.08 * n));
      const [px, py] = toPixel(box, curve[j], map.alpha[j]);
      ctx.fillStyle = "white";
      ctx.font = "11px sans-serif";
      ctx.fillText(`x${n + 1}`, px + 3, py);
    });
  }
  // the chosen point
  if (state.mode === "bilayer") {
    const [px, py] = toPixel(box, state.x, state.alpha);
    ctx.strokeStyle = "#e08214";
    ctx.lineWidth = 2;
    ctx.beginPath(); ctx.arc(px, py, 6, 0, 2 * Math.PI); ctx.stroke();
  }
  // axes
  ctx.strokeStyle = "#333";
  ctx.lineWidth = 1;
  ctx.strokeRect(box.x0, box.y0, box.w, box.h);
  ctx.fillStyle = "#222";
  ctx.font = "12px sans-serif";
  for (let k = 0; k <= 10; k += 2) {
    const v = k / 10;
    const [px] = toPixel(box, v, 0);
    const [, py] = toPixel(box, 0, v);
    ctx.fillText(v.toFixed(1), px - 8, box.y0 + box.h + 14);
    ctx.fillText(v.toFixed(1), box.x0 - 26, py + 4);
  }
  ctx.fillText("x = L2/L", box.x0 + box.w / 2 - 24, box.y0 + box.h + 30);
  ctx.save();
  ctx.translate(12, box.y0 + box.h / 2 + 20);
  ctx.rotate(-Math.PI / 2);
  ctx.fillText("α", 0, 0);
  ctx.restore();
  drawLegend(q, scale);
}

function drawLegend(q, scale) {
  const canvas = $("legend");
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  const top = MAP.top, h = canvas.height - MAP.top - MAP.bottom;
  ctx.font = "11px sans-serif";
  ctx.fillStyle = "#222";
  if (q === "bounces") {
    const n = Math.min(scale[1], CATEGORIES.length - 1);
    for (let k = 1; k <= n; k++) {
      const y = top + h - (k * h) / n;
      const [r, g, b] = CATEGORIES[k];
      ctx.fillStyle = `rgb(${r},${g},${b})`;
      ctx.fillRect(0, y, 14, h / n - 2);
      ctx.fillStyle = "#222";
      ctx.fillText(String(k), 18, y + h / n / 2 + 4);
    }
    return;
  }
  for (let k = 0; k < h; k++) {
    const [r, g, b] = viridis(1 - k / h);
    ctx.fillStyle = `rgb(${r},${g},${b})`;
    ctx.fillRect(0, top + k, 14, 1);
  }
  ctx.fillStyle = "#222";
  ctx.fillText(scale[1].toFixed(2), 18, top + 8);
  ctx.fillText(scale[0].toFixed(2), 18, top + h);
}

function mapPoint(ev) {
  if (!map) return null;
  const canvas = $("map");
  // the drawing is the canvas's content box: its border is not part of it
  const rect = canvas.getBoundingClientRect();
  const px = ((ev.clientX - rect.left - canvas.clientLeft) * canvas.width) / canvas.clientWidth;
  const py = ((ev.clientY - rect.top - canvas.clientTop) * canvas.height) / canvas.clientHeight;
  const box = plotBox(canvas);
  const x = (px - box.x0) / box.w, a = 1 - (py - box.y0) / box.h;
  if (x <= 0 || x >= 1 || a <= 0 || a >= 1) return null;
  const nearest = (axis, v) => {
    let best = 0;
    axis.forEach((w, k) => { if (Math.abs(w - v) < Math.abs(axis[best] - v)) best = k; });
    return best;
  };
  // the map's nearest computed point (for the values shown), and the point
  // picked: on the paper's 0.005 grid whatever step the map has reached
  const i = nearest(map.x, x), j = nearest(map.alpha, a);
  const paper = (v) => round6(Math.min(0.995, Math.max(0.005, Math.round(v / 0.005) * 0.005)));
  return { i, j, x: round6(map.x[i]), alpha: round6(map.alpha[j]), pickX: paper(x), pickAlpha: paper(a) };
}

function fmt(v, digits) {
  return v === null || v === undefined ? "–" : Number(v).toFixed(digits);
}

async function loadMaps() {
  for (const step of ["0.05", "0.02", "0.01", "0.005"]) {
    const t0 = performance.now();
    const r = await fetch(`/api/map?step=${step}`);
    if (!r.ok) {
      $("map-status").textContent = `map failed: ${(await r.json()).error}`;
      return;
    }
    map = await r.json();
    drawMap();
    const n = map.x.length * map.alpha.length;
    $("map-status").textContent = `${map.x.length} × ${map.alpha.length} points (step ${step}), exact engine: ${map.events.toLocaleString()} events in ${(map.seconds * 1000).toFixed(0)} ms of server time; page ${(performance.now() - t0).toFixed(0)} ms` + (step === "0.005" ? " (the paper's grid)" : ", refining…");
    $("map").dataset.step = step;
    $("map").dataset.points = n;
  }
}

// ---------------------------------------------------------- the editor

function renderLayers() {
  const body = $("layers").querySelector("tbody");
  body.innerHTML = "";
  const units = state.units === "si" ? ["m", "Pa", "kg/m³"] : ["", "", ""];
  const head = $("layers").querySelectorAll("thead th");
  head[2].textContent = units[0] ? `length [${units[0]}]` : "length";
  head[3].textContent = units[1] ? `modulus [${units[1]}]` : "modulus";
  head[4].textContent = units[2] ? `density [${units[2]}]` : "density";
  state.layers.forEach((layer, k) => {
    const tr = document.createElement("tr");
    tr.dataset.layer = k;
    const opts = ['<option value="">(numbers)</option>']
      .concat(materials.map((m) => `<option value="${m.name}" ${m.name === layer.material ? "selected" : ""}>${m.name}</option>`))
      .join("");
    tr.innerHTML = `<td>${k + 1}${k === 0 ? " (bottom)" : ""}</td>
      <td><select data-key="material">${opts}</select></td>
      <td><input type="number" step="any" data-key="length" value="${layer.length}"></td>
      <td><input type="number" step="any" data-key="modulus" value="${layer.modulus}"></td>
      <td><input type="number" step="any" data-key="density" value="${layer.density}"></td>
      <td><select data-key="visc">
          <option value="none" ${layer.visc === "none" ? "selected" : ""} title="elastic">elastic</option>
          <option value="tau" ${layer.visc === "tau" ? "selected" : ""} title="relaxation time tau = eta / E">τ</option>
          <option value="e" ${layer.visc === "e" ? "selected" : ""} title="the layer's restitution e_i (Sec. VII)">eᵢ</option>
        </select>
        <input type="number" step="any" data-key="viscValue" value="${layer.viscValue}" ${layer.visc === "none" ? "hidden" : ""}></td>
      <td><button type="button" data-remove="${k}" title="remove this layer" ${state.layers.length <= 1 ? "disabled" : ""}>✕</button></td>
      <td class="field-error" data-field="layers[${k}]"></td>`;
    body.appendChild(tr);
  });
  $("mode").textContent = state.mode === "bilayer"
    ? "the canonical bilayer of (x, α): edit a layer to make it a scene of your own"
    : "a scene of your own: set x and α (or click the map) for the canonical bilayer";
}

function onLayerEdit(ev) {
  const el = ev.target;
  const tr = el.closest("tr");
  if (!tr || !el.dataset.key) return;
  const k = Number(tr.dataset.layer);
  const layer = state.layers[k];
  const key = el.dataset.key;
  if (key === "material") {
    layer.material = el.value;
    const m = materials.find((m) => m.name === el.value);
    if (m) {
      layer.modulus = m.modulus;
      layer.density = m.density;
      if (state.units !== "si") {
        state.units = "si";
        $("units").value = "si";
      }
    }
  } else if (key === "visc") {
    layer.visc = el.value;
  } else {
    layer[key] = el.value;
  }
  state.mode = "scene";
  if (key === "material" || key === "visc") renderLayers();
  schedule();
}

function addLayer() {
  const si = state.units === "si";
  state.layers.push({ material: "", length: si ? 0.01 : 0.5, modulus: si ? 1e9 : 0.5, density: si ? 1000 : 1, visc: "none", viscValue: "" });
  state.mode = "scene";
  renderLayers();
  schedule();
}

function numberOrNull(v) {
  if (v === "" || v === null || v === undefined) return null;
  const n = Number(v);
  return Number.isFinite(n) ? n : null;
}

// The scene as the command line reads it, or the field that is not a number.
function sceneJson() {
  const layers = [];
  for (const [k, l] of state.layers.entries()) {
    const layer = {};
    if (l.material) layer.material = l.material;
    for (const key of ["length", "modulus", "density"]) {
      const v = numberOrNull(l[key]);
      if (v === null) return { field: `layers[${k}].${key}`, message: `layers[${k}].${key}: enter a number` };
      layer[key] = v;
    }
    if (l.visc !== "none") {
      const v = numberOrNull(l.viscValue);
      const key = l.visc === "tau" ? "relaxation_time" : "restitution";
      if (v === null) return { field: `layers[${k}].${key}`, message: `layers[${k}].${key}: enter a number` };
      layer[key] = v;
    }
    layers.push(layer);
  }
  const speed = numberOrNull(state.speed);
  if (speed === null) return { field: "impact_speed", message: "impact_speed: enter a number" };
  const scene = { impact_speed: speed, layers };
  if (state.wall !== "paper") scene.wall_contact = state.wall;
  return { scene };
}

function isViscous() {
  return state.mode === "scene" && state.layers.some((l) => l.visc !== "none");
}

// ----------------------------------------------------------- the point

let timer = null;
function schedule() {
  clearTimeout(timer);
  timer = setTimeout(update, 120);
}

function clearErrors() {
  document.querySelectorAll(".field-error").forEach((e) => (e.textContent = ""));
  document.querySelectorAll("input.invalid").forEach((e) => e.classList.remove("invalid"));
  $("run-error").hidden = true;
  $("scene-error").hidden = true;
}

// Shows a message beside the field it names (layers[k].modulus, x, alpha,
// impact_speed, --n), else above the point.
function showError(message) {
  const text = message.replace(/^scene: /, "");
  const layer = text.match(/^layers\[(\d+)\]\.?(\w+)?/);
  if (layer) {
    const k = Number(layer[1]);
    const cell = document.querySelector(`.field-error[data-field="layers[${k}]"]`);
    const tr = document.querySelector(`#layers tr[data-layer="${k}"]`);
    if (cell) cell.textContent = text;
    const key = { relaxation_time: "viscValue", restitution: "viscValue" }[layer[2]] || layer[2];
    const input = tr && tr.querySelector(`[data-key="${key}"]`);
    if (input) input.classList.add("invalid");
    if (cell) return;
  }
  const field = text.match(/^(?:error: )?(?:--)?(x|alpha|impact_speed|n)\b/);
  if (field) {
    const span = document.querySelector(`.field-error[data-field="${field[1]}"]`);
    const input = { x: "x", alpha: "alpha", impact_speed: "speed", n: "engine-n" }[field[1]];
    if (input) $(input).classList.add("invalid");
    if (span) {
      span.textContent = text;
      return;
    }
  }
  $("run-error").textContent = text;
  $("run-error").hidden = false;
}

function runRequest(signal) {
  const params = new URLSearchParams();
  if (state.mode === "bilayer") {
    params.set("x", state.x);
    params.set("alpha", state.alpha);
  }
  if (state.engine !== "auto") params.set("engine", state.engine);
  if (state.n !== "") params.set("n", state.n);
  if (state.wall !== "paper") params.set("wall-contact", state.wall);
  if (state.mode === "bilayer") return fetch(`/api/run?${params}`, { signal });
  const built = sceneJson();
  if (built.field) return Promise.reject(new InputError(built.message));
  return fetch(`/api/run?${params}`, { method: "POST", body: JSON.stringify(built.scene), signal });
}

function diagramRequest(signal, run) {
  const params = new URLSearchParams();
  if (state.mode === "bilayer") {
    params.set("x", state.x);
    params.set("alpha", state.alpha);
  }
  const chain = run.engine === "chain";
  if (chain) {
    params.set("engine", "chain");
    params.set("n", state.n !== "" ? state.n : state.chainN);
  } else if (state.sideBySide) {
    params.set("side-by-side", "true");
    params.set("n", state.chainN);
  }
  if (state.window) {
    params.set("t-start", round6(state.window[0]));
    params.set("t-end", round6(state.window[1]));
  }
  if (state.mode === "bilayer") return fetch(`/api/diagram?${params}`, { signal });
  return fetch(`/api/diagram?${params}`, { method: "POST", body: JSON.stringify(sceneJson().scene), signal });
}

class InputError extends Error {}

async function answer(response) {
  const body = await response.json();
  if (!response.ok) throw new InputError(body.error);
  return { body, command: response.headers.get("x-impact-command") };
}

function busy(on, text) {
  const el = $("busy");
  clearInterval(busy.tick);
  if (!on) {
    el.hidden = true;
    return;
  }
  const start = performance.now();
  $("busy-text").textContent = text;
  busy.tick = setInterval(() => {
    const s = (performance.now() - start) / 1000;
    if (s > 0.15) el.hidden = false;
    $("busy-text").textContent = `${text} ${s.toFixed(1)} s`;
  }, 100);
}

async function update(diagramOnly) {
  saveUrl();
  drawMap();
  clearErrors();
  if (inflight) inflight.abort();
  const controller = new AbortController();
  inflight = controller;
  const viscous = isViscous();
  busy(true, viscous ? "running the chain (extrapolated to N → ∞)…" : "running…");
  try {
    if (!diagramOnly || !lastRun) {
      const run = await answer(await runRequest(controller.signal));
      lastRun = run.body;
      showNumbers(run.body);
      $("command").value = run.command || "";
      $("point-title").textContent = state.mode === "bilayer" ? `x = ${state.x}, α = ${state.alpha}` : `a scene of ${state.layers.length} layers`;
    }
    if (lastRun.engine === "rigid-bottom") {
      $("diagram").innerHTML = '<p class="sub">The rigid-bottom model draws no diagram: choose the wave or chain engine.</p>';
      lastDiagram = null;
      fillEvents(null);
    } else {
      busy(true, "drawing…");
      const d = await answer(await diagramRequest(controller.signal, lastRun));
      lastDiagram = d.body;
      showDiagram(d.body);
    }
  } catch (e) {
    if (e.name === "AbortError") return;
    if (e instanceof InputError) showError(e.message);
    else showError(String(e));
  } finally {
    if (inflight === controller) {
      inflight = null;
      busy(false);
    }
  }
}

function showNumbers(o) {
  $("n-e").textContent = fmt(o.restitution, 12);
  $("n-tc").textContent = fmt(o.contact_time, 6);
  $("n-rtc").textContent = fmt(o.reduced_contact_time, 6);
  $("n-n1").textContent = o.n1 === null || o.n1 === undefined ? "–" : fmt(o.n1, 6);
  $("n-nb").textContent = o.bounces;
  $("n-sep").textContent = o.separations;
  $("n-err").textContent = o.error_bound === undefined ? "–" : Number(o.error_bound).toExponential(1);
  $("n-events").textContent = o.events === undefined || o.events === null ? (o.steps ? `${o.steps} steps` : "–") : o.events.toLocaleString();
  $("n-engine").textContent = o.engine;
  $("n-law").textContent = o.wall_contact;
  $("n-contacts").textContent = o.contacts.slice(0, 8).map((c) => `[${c[0].toFixed(4)}, ${c[1].toFixed(4)}]`).join(" ") + (o.contacts.length > 8 ? ` … (${o.contacts.length})` : "");
}

function currentWindow() {
  if (state.window) return state.window;
  const tc = lastRun ? lastRun.contact_time : 1;
  return [0, 1.12 * tc];
}

function showDiagram(d) {
  $("diagram").innerHTML = d.svg;
  $("diagram-command").value = d.command;
  const w = currentWindow();
  $("window-text").textContent = state.window ? `t from ${w[0].toPrecision(4)} to ${w[1].toPrecision(4)}` : "the whole impact";
  fillEvents(d);
}

function kindOf(f, total) {
  if (f.parents.length === 0) return f.born === 0 ? "impact" : "landing";
  if (f.place === 0) return "wall reflection";
  if (Math.abs(f.place - total) < 1e-12 * total) return "top reflection";
  return "interface";
}

function fillEvents(d) {
  const body = $("events").querySelector("tbody");
  body.innerHTML = "";
  if (!d) {
    $("events-note").textContent = "";
    return;
  }
  const total = d.fronts.reduce((m, f) => Math.max(m, f.place), 0);
  const onPath = new Set(d.takeoff_path);
  const rows = [];
  d.outcome.contacts.forEach((c, i) => {
    if (i > 0) rows.push({ t: c[0], html: `<td>${c[0].toFixed(6)}</td><td>0</td><td>reconnection</td><td></td><td></td><td></td>`, cls: "" });
    const kind = i + 1 === d.outcome.contacts.length ? "final takeoff" : "separation";
    rows.push({ t: c[1], html: `<td>${c[1].toFixed(6)}</td><td>0</td><td>${kind}</td><td></td><td></td><td></td>`, cls: "" });
  });
  for (const f of d.fronts) {
    rows.push({
      t: f.born,
      id: f.id,
      cls: onPath.has(f.id) ? "takeoff" : "",
      html: `<td>${f.born.toFixed(6)}</td><td>${f.place.toPrecision(4)}</td><td>${kindOf(f, total)}</td><td>${f.jump.toExponential(3)}</td><td>${f.id} (${f.direction}, layer ${f.layer})</td><td>${f.parents.join(", ")}</td>`,
    });
  }
  rows.sort((a, b) => a.t - b.t);
  const html = rows.map((r) => `<tr${r.id !== undefined ? ` data-id="${r.id}"` : ""} class="${r.cls}">${r.html}</tr>`);
  body.innerHTML = html.join("");
  $("events-note").textContent = d.fronts_total > d.fronts.length
    ? `(${d.fronts.length} strongest of ${d.fronts_total} fronts; green: the path of the final takeoff)`
    : `(${d.fronts_total} fronts; green: the path of the final takeoff; point at a row or a front for its ancestry)`;
  ancestry.parents = new Map(d.fronts.map((f) => [f.id, f.parents]));
}

// Ancestry: a front, its parents, theirs, ... highlighted in the figure
// and the table.
const ancestry = { parents: new Map() };

function highlight(id) {
  document.querySelectorAll(".hl, .hl-self").forEach((e) => e.classList.remove("hl", "hl-self"));
  if (id === null) return;
  const seen = new Set();
  const stack = [id];
  while (stack.length && seen.size < 5000) {
    const f = stack.pop();
    if (seen.has(f)) continue;
    seen.add(f);
    for (const p of ancestry.parents.get(f) || []) stack.push(p);
  }
  for (const f of seen) {
    document.querySelectorAll(`#diagram line.front[data-id="${f}"]`).forEach((e) => e.classList.add(f === id ? "hl-self" : "hl"));
    const row = document.querySelector(`#events tr[data-id="${f}"]`);
    if (row) row.classList.add("hl");
  }
}

// ---------------------------------------------------------- downloads

function download(name, blob) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

function pointName() {
  return state.mode === "bilayer" ? `impact-x${state.x}-alpha${state.alpha}` : "impact-scene";
}

function downloadPng() {
  if (!lastDiagram) return;
  const svg = $("diagram").querySelector("svg");
  const w = Number(svg.getAttribute("width")) || svg.viewBox.baseVal.width;
  const h = Number(svg.getAttribute("height")) || svg.viewBox.baseVal.height;
  const img = new Image();
  img.onload = () => {
    const canvas = document.createElement("canvas");
    canvas.width = 2 * w;
    canvas.height = 2 * h;
    const ctx = canvas.getContext("2d");
    ctx.fillStyle = "white";
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    ctx.drawImage(img, 0, 0, canvas.width, canvas.height);
    canvas.toBlob((blob) => download(`${pointName()}.png`, blob), "image/png");
  };
  img.src = "data:image/svg+xml;charset=utf-8," + encodeURIComponent(lastDiagram.svg);
}

// --------------------------------------------------------------- wiring

function syncInputs() {
  $("x").value = state.x;
  $("alpha").value = state.alpha;
  $("speed").value = state.speed;
  $("units").value = state.units;
  $("engine").value = state.engine;
  $("engine-n").value = state.n;
  $("wall-contact").value = state.wall;
  $("side-by-side").checked = state.sideBySide;
  $("chain-n").value = state.chainN;
  document.querySelectorAll('input[name="quantity"]').forEach((r) => (r.checked = r.value === state.quantity));
  $("ov-tenth").checked = state.overlays.tenth;
  $("ov-boundary").checked = state.overlays.boundary;
  $("ov-xn").checked = state.overlays.xn;
  $("ov-iso").checked = state.overlays.iso;
}

function pickBilayer(x, alpha) {
  state.mode = "bilayer";
  state.x = x;
  state.alpha = alpha;
  state.layers = canonicalLayers(x, alpha);
  state.speed = 1;
  state.units = "reduced";
  state.window = null;
  syncInputs();
  renderLayers();
  schedule();
}

function wire() {
  $("map").addEventListener("mousemove", (ev) => {
    const p = mapPoint(ev);
    if (!p) {
      $("map-hover").textContent = "";
      return;
    }
    const k = p.j * map.x.length + p.i;
    $("map-hover").textContent = `x = ${p.x}, α = ${p.alpha}: e = ${fmt(map.restitution[k], 6)}, t_c/(2Σt) = ${fmt(map.reduced_contact_time[k], 4)}, n1 = ${fmt(map.n1[k], 3)}, N_b = ${map.bounces[k] ?? "–"}`;
  });
  $("map").addEventListener("click", (ev) => {
    const p = mapPoint(ev);
    if (p) pickBilayer(p.pickX, p.pickAlpha);
  });
  document.querySelectorAll('input[name="quantity"]').forEach((r) =>
    r.addEventListener("change", () => { state.quantity = r.value; saveUrl(); drawMap(); }));
  for (const [id, key] of [["ov-tenth", "tenth"], ["ov-boundary", "boundary"], ["ov-xn", "xn"], ["ov-iso", "iso"]]) {
    $(id).addEventListener("change", () => { state.overlays[key] = $(id).checked; saveUrl(); drawMap(); });
  }
  const bilayerInput = () => {
    const x = numberOrNull($("x").value), a = numberOrNull($("alpha").value);
    state.mode = "bilayer";
    state.x = x === null ? $("x").value : x;
    state.alpha = a === null ? $("alpha").value : a;
    if (x !== null && a !== null) state.layers = canonicalLayers(x, a);
    state.window = null;
    renderLayers();
    schedule();
  };
  $("x").addEventListener("input", bilayerInput);
  $("alpha").addEventListener("input", bilayerInput);
  $("layers").addEventListener("input", onLayerEdit);
  $("layers").addEventListener("change", (ev) => { if (ev.target.tagName === "SELECT") onLayerEdit(ev); });
  $("layers").addEventListener("click", (ev) => {
    const k = ev.target.dataset.remove;
    if (k === undefined) return;
    state.layers.splice(Number(k), 1);
    state.mode = "scene";
    renderLayers();
    schedule();
  });
  $("add-layer").addEventListener("click", addLayer);
  $("speed").addEventListener("input", () => { state.speed = $("speed").value; state.mode = "scene"; renderLayers(); schedule(); });
  $("units").addEventListener("change", () => { state.units = $("units").value; renderLayers(); saveUrl(); });
  $("engine").addEventListener("change", () => { state.engine = $("engine").value; schedule(); });
  $("engine-n").addEventListener("input", () => { state.n = $("engine-n").value; schedule(); });
  $("wall-contact").addEventListener("change", () => { state.wall = $("wall-contact").value; schedule(); });
  $("side-by-side").addEventListener("change", () => { state.sideBySide = $("side-by-side").checked; update(true); });
  $("chain-n").addEventListener("change", () => { state.chainN = Number($("chain-n").value) || 2000; if (state.sideBySide || isViscous()) update(true); });
  $("cancel").addEventListener("click", () => {
    if (inflight) inflight.abort();
    inflight = null;
    busy(false);
    $("run-error").textContent = "cancelled";
    $("run-error").hidden = false;
  });
  const zoom = (f) => {
    const [a, b] = currentWindow();
    const c = (a + b) / 2, half = ((b - a) / 2) * f;
    state.window = [Math.max(0, c - half), c + half];
    update(true);
  };
  $("zoom-in").addEventListener("click", () => zoom(0.5));
  $("zoom-out").addEventListener("click", () => zoom(2));
  const pan = (f) => {
    const [a, b] = currentWindow();
    const d = (b - a) * f;
    const start = Math.max(0, a + d);
    state.window = [start, start + (b - a)];
    update(true);
  };
  $("pan-left").addEventListener("click", () => pan(-0.25));
  $("pan-right").addEventListener("click", () => pan(0.25));
  $("zoom-reset").addEventListener("click", () => { state.window = null; update(true); });
  $("diagram").addEventListener("mouseover", (ev) => {
    const id = ev.target.dataset && ev.target.dataset.id;
    highlight(id === undefined ? null : Number(id));
  });
  $("events").addEventListener("mouseover", (ev) => {
    const tr = ev.target.closest("tr");
    highlight(tr && tr.dataset.id !== undefined ? Number(tr.dataset.id) : null);
  });
  $("dl-svg").addEventListener("click", () => lastDiagram && download(`${pointName()}.svg`, new Blob([lastDiagram.svg], { type: "image/svg+xml" })));
  $("dl-png").addEventListener("click", downloadPng);
  $("dl-json").addEventListener("click", () => lastRun && download(`${pointName()}.json`, new Blob([JSON.stringify(lastRun, null, 2)], { type: "application/json" })));
  $("dl-scene").addEventListener("click", () => {
    const built = state.mode === "bilayer"
      ? { scene: { impact_speed: 1, layers: state.layers.map((l) => ({ length: l.length, modulus: l.modulus, density: l.density })) } }
      : sceneJson();
    if (built.scene) download("scene.json", new Blob([JSON.stringify(built.scene, null, 2)], { type: "application/json" }));
  });
  for (const button of [$("copy"), $("copy-diagram")]) {
    const label = button.textContent;
    button.addEventListener("click", async () => {
      const source = $(button.dataset.source);
      try {
        await navigator.clipboard.writeText(source.value);
      } catch (e) {
        source.select();
        document.execCommand("copy");
      }
      button.textContent = "Copied";
      setTimeout(() => (button.textContent = label), 1200);
    });
  }
}

async function start() {
  const fromUrl = loadUrl();
  try {
    materials = await (await fetch("/api/materials")).json();
  } catch (e) {
    materials = [];
  }
  if (!fromUrl) {
    const scene = await (await fetch("/api/scene")).json();
    if (scene && Array.isArray(scene.layers)) {
      state.mode = "scene";
      state.speed = scene.impact_speed;
      state.units = "si";
      if (scene.wall_contact) state.wall = scene.wall_contact;
      state.layers = scene.layers.map((l) => {
        const m = materials.find((m) => m.name === l.material);
        return {
          material: l.material || "",
          length: l.length,
          modulus: l.modulus ?? (m ? m.modulus : ""),
          density: l.density ?? (m ? m.density : ""),
          visc: l.relaxation_time !== undefined ? "tau" : l.restitution !== undefined ? "e" : "none",
          viscValue: l.relaxation_time ?? l.restitution ?? "",
        };
      });
    }
  }
  if (state.layers.length === 0) state.layers = canonicalLayers(state.x, state.alpha);
  syncInputs();
  renderLayers();
  wire();
  update();
  loadMaps();
}

start();
