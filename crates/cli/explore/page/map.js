// impact explore: the map of the canonical bilayer, drawn on a canvas.

import { $, live, round6, state } from "./state.js";

export const MAP = { left: 44, right: 8, top: 8, bottom: 36 };

// viridis, sampled: value in [0, 1] to rgb
export const VIRIDIS = [
  [68, 1, 84], [72, 40, 120], [62, 74, 137], [49, 104, 142], [38, 130, 142],
  [31, 158, 137], [53, 183, 121], [110, 206, 88], [181, 222, 43], [253, 231, 37],
];
export const CATEGORIES = [
  [200, 200, 200], [49, 104, 142], [53, 183, 121], [253, 231, 37], [243, 120, 60],
  [200, 40, 70], [120, 30, 120], [40, 40, 40], [150, 90, 40], [0, 150, 200],
];

export function viridis(t) {
  t = Math.min(1, Math.max(0, t));
  const f = t * (VIRIDIS.length - 1);
  const i = Math.min(VIRIDIS.length - 2, Math.floor(f));
  const u = f - i;
  return VIRIDIS[i].map((c, k) => Math.round(c + u * (VIRIDIS[i + 1][k] - c)));
}

export function scaleOf(values, quantity) {
  if (quantity === "restitution") return [0, 1];
  let lo = Infinity, hi = -Infinity;
  for (const v of values) if (v !== null) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  if (quantity === "bounces") return [1, Math.max(hi, 2)];
  if (!(hi > lo)) hi = lo + 1;
  return [Math.min(lo, 0), hi];
}

export function colour(v, quantity, scale) {
  if (v === null || v === undefined) return [255, 255, 255];
  if (quantity === "bounces") return CATEGORIES[Math.min(v, CATEGORIES.length - 1)];
  return viridis((v - scale[0]) / (scale[1] - scale[0]));
}

export function plotBox(canvas) {
  return { x0: MAP.left, y0: MAP.top, w: canvas.width - MAP.left - MAP.right, h: canvas.height - MAP.top - MAP.bottom };
}

export function toPixel(box, x, a) {
  return [box.x0 + x * box.w, box.y0 + (1 - a) * box.h];
}

export function levelsOf(quantity, scale) {
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
export function isolines(ctx, box, values, level) {
  const nx = live.map.x.length, na = live.map.alpha.length;
  const at = (i, j) => values[j * nx + i];
  ctx.beginPath();
  for (let j = 0; j + 1 < na; j++) {
    for (let i = 0; i + 1 < nx; i++) {
      const c = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
      if (c.some((v) => v === null)) continue;
      const p = [[live.map.x[i], live.map.alpha[j]], [live.map.x[i + 1], live.map.alpha[j]], [live.map.x[i + 1], live.map.alpha[j + 1]], [live.map.x[i], live.map.alpha[j + 1]]];
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

export function drawMap() {
  const canvas = $("map");
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  ctx.fillStyle = "white";
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  if (!live.map) return;
  const box = plotBox(canvas);
  const q = state.quantity;
  const values = live.map[q];
  const scale = scaleOf(values, q);
  const h = live.map.step;
  const nx = live.map.x.length;
  for (let j = 0; j < live.map.alpha.length; j++) {
    for (let i = 0; i < nx; i++) {
      const [r, g, b] = colour(values[j * nx + i], q, scale);
      ctx.fillStyle = `rgb(${r},${g},${b})`;
      const [px, py] = toPixel(box, live.map.x[i] - h / 2, live.map.alpha[j] + h / 2);
      ctx.fillRect(Math.floor(px), Math.floor(py), Math.ceil(h * box.w) + 1, Math.ceil(h * box.h) + 1);
    }
  }
  if (state.overlays.iso) {
    ctx.strokeStyle = "rgba(0,0,0,0.45)";
    ctx.lineWidth = 0.8;
    for (const level of levelsOf(q, scale)) isolines(ctx, box, values, level);
  }
  const ov = live.map.overlays;
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
        const [px, py] = toPixel(box, x, live.map.alpha[j]);
        if (j === 0) ctx.moveTo(px, py); else ctx.lineTo(px, py);
      });
      ctx.stroke();
      const j = Math.floor(live.map.alpha.length * (0.45 + 0.08 * n));
      const [px, py] = toPixel(box, curve[j], live.map.alpha[j]);
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

export function drawLegend(q, scale) {
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

export function mapPoint(ev) {
  if (!live.map) return null;
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
  const i = nearest(live.map.x, x), j = nearest(live.map.alpha, a);
  const paper = (v) => round6(Math.min(0.995, Math.max(0.005, Math.round(v / 0.005) * 0.005)));
  return { i, j, x: round6(live.map.x[i]), alpha: round6(live.map.alpha[j]), pickX: paper(x), pickAlpha: paper(a) };
}


export async function loadMaps() {
  for (const step of ["0.05", "0.02", "0.01", "0.005"]) {
    const t0 = performance.now();
    const r = await fetch(`/api/map?step=${step}`);
    if (!r.ok) {
      $("map-status").textContent = `map failed: ${(await r.json()).error}`;
      return;
    }
    live.map = await r.json();
    drawMap();
    const n = live.map.x.length * live.map.alpha.length;
    $("map-status").textContent = `${live.map.x.length} × ${live.map.alpha.length} points (step ${step}), exact engine: ${live.map.events.toLocaleString()} events in ${(live.map.seconds * 1000).toFixed(0)} ms of server time; page ${(performance.now() - t0).toFixed(0)} ms` + (step === "0.005" ? " (the paper's grid)" : ", refining…");
    $("map").dataset.step = step;
    $("map").dataset.points = n;
  }
}
