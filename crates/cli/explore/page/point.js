// impact explore: the point: its numbers, diagram, events and downloads.

import { $, fmt, live, round6, saveUrl, state } from "./state.js";
import { drawMap } from "./map.js";
import { isViscous, sceneJson } from "./editor.js";

// The page is idle when no edit waits out its debounce and no run is in
// flight: `<body data-idle="true">`. The spinner shows only after 150 ms, so
// scripts (and the browser test) wait on this instead.
let timer = null;
export function schedule() {
  clearTimeout(timer);
  setIdle(false);
  timer = setTimeout(() => {
    timer = null;
    update();
  }, 120);
}

function setIdle(idle) {
  document.body.dataset.idle = String(idle);
}

export function cancelRun() {
  if (live.inflight) live.inflight.abort();
  live.inflight = null;
  busy(false);
  $("run-error").textContent = "cancelled";
  $("run-error").hidden = false;
  if (timer === null) setIdle(true);
}

// The picture's downloads work only while a picture is shown.
function setDiagram(d) {
  live.lastDiagram = d;
  $("dl-svg").disabled = $("dl-png").disabled = d === null;
}

export function clearErrors() {
  document.querySelectorAll(".field-error").forEach((e) => (e.textContent = ""));
  document.querySelectorAll("input.invalid").forEach((e) => e.classList.remove("invalid"));
  $("run-error").hidden = true;
  $("scene-error").hidden = true;
}

// Shows a message beside the field it names (layers[k].modulus, x, alpha,
// impact_speed, --n), else above the point.
export function showError(message) {
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

export function runRequest(signal) {
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

export function diagramRequest(signal, run) {
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

export class InputError extends Error {}

export async function answer(response) {
  const body = await response.json();
  if (!response.ok) throw new InputError(body.error);
  return { body, command: response.headers.get("x-impact-command") };
}

export function busy(on, text) {
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

export async function update(diagramOnly) {
  saveUrl();
  drawMap();
  clearErrors();
  if (live.inflight) live.inflight.abort();
  const controller = new AbortController();
  live.inflight = controller;
  setIdle(false);
  const viscous = isViscous();
  busy(true, viscous ? "running the chain (extrapolated to N → ∞)…" : "running…");
  try {
    if (!diagramOnly || !live.lastRun) {
      const run = await answer(await runRequest(controller.signal));
      live.lastRun = run.body;
      showNumbers(run.body);
      $("command").value = run.command || "";
      $("point-title").textContent = state.mode === "bilayer" ? `x = ${state.x}, α = ${state.alpha}` : `a scene of ${state.layers.length} layers`;
    }
    if (live.lastRun.engine === "rigid-bottom") {
      $("diagram").innerHTML = '<p class="sub">The rigid-bottom model draws no diagram: choose the wave or chain engine.</p>';
      setDiagram(null);
      fillEvents(null);
    } else {
      busy(true, "drawing…");
      // no stale picture beside new numbers while (or if) none comes
      setDiagram(null);
      const d = await answer(await diagramRequest(controller.signal, live.lastRun)).catch((e) => {
        if (!(e instanceof InputError)) throw e;
        const note = document.createElement("p");
        note.className = "sub";
        note.textContent = `No diagram: ${e.message}`;
        $("diagram").replaceChildren(note);
        fillEvents(null);
        return null;
      });
      if (d) {
        setDiagram(d.body);
        showDiagram(d.body);
      }
    }
  } catch (e) {
    if (e.name === "AbortError") return;
    if (e instanceof InputError) showError(e.message);
    else showError(String(e));
  } finally {
    if (live.inflight === controller) {
      live.inflight = null;
      busy(false);
      if (timer === null) setIdle(true);
    }
  }
}

export function showNumbers(o) {
  $("n-e").textContent = fmt(o.restitution, 12);
  $("n-tc").textContent = fmt(o.contact_time, 6);
  $("n-rtc").textContent = fmt(o.reduced_contact_time, 6);
  $("n-n1").textContent = o.n1 === null || o.n1 === undefined ? "–" : fmt(o.n1, 6);
  $("n-nb").textContent = o.bounces;
  $("n-sep").textContent = o.separations;
  $("n-err").textContent = o.error_bound === undefined || o.error_bound === null ? "–" : Number(o.error_bound).toExponential(1);
  $("n-events").textContent = o.events === undefined || o.events === null ? (o.steps ? `${o.steps} steps` : "–") : o.events.toLocaleString();
  $("n-engine").textContent = o.engine;
  $("n-law").textContent = o.wall_contact;
  // a viscous run answers for the continuum: its chains' extrapolation,
  // beside the finest chain's figures above (as `impact run` prints them)
  const x = o.extrapolation;
  $("n-limit-row").hidden = !x;
  $("n-limit").textContent = x
    ? `${fmt(x.value, 9)} ± ${Number(x.error).toExponential(1)} (Richardson over chains of ${x.sizes.join(", ")}; the figures above are the chain of ${x.sizes[x.sizes.length - 1]})`
    : "";
  // what `impact run` says beside a merged bound: whether its levels were
  // seen converging, or the ladder set aside for an exact run
  const note = boundNote(o.error_estimate);
  $("n-bound-row").hidden = !note;
  $("n-bound").textContent = note;
  $("n-contacts").textContent = o.contacts.slice(0, 8).map((c) => `[${c[0].toFixed(4)}, ${c[1].toFixed(4)}]`).join(" ") + (o.contacts.length > 8 ? ` … (${o.contacts.length})` : "");
}

// The caveat a bound carries, in the command line's words ("" for none).
export function boundNote(est) {
  if (!est) return "";
  if (est.merged_converging === false) {
    const order = est.merged_observed_order;
    const levels = order === undefined || order === null
      ? "the merged levels are not yet seen converging"
      : `the merged levels show order ${Number(order).toFixed(1)}, below 0.5`; // convergence.rs SLOWEST_ORDER
    const tried = est.exact_again_unfinished ? `; the exact run, tried again with ${est.exact_again_unfinished} events, did not finish` : "";
    return `may be low, by any factor: ${levels}${tried}`;
  }
  const ladder = est.ladder_set_aside;
  if (ladder) {
    return `exact: the merged levels did not converge, and gave ${Number(ladder.restitution).toFixed(10)} ± ${Number(ladder.merged_bound).toExponential(1)}`;
  }
  return "";
}

export function currentWindow() {
  if (state.window) return state.window;
  const tc = live.lastRun ? live.lastRun.contact_time : 1;
  return [0, 1.12 * tc];
}

export function showDiagram(d) {
  $("diagram").innerHTML = d.svg;
  $("diagram-command").value = d.command;
  const w = currentWindow();
  $("window-text").textContent = state.window ? `t from ${w[0].toPrecision(4)} to ${w[1].toPrecision(4)}` : "the whole impact";
  fillEvents(d);
}

export function kindOf(f, total) {
  if (f.parents.length === 0) return f.born === 0 ? "impact" : "landing";
  if (f.place === 0) return "wall reflection";
  if (Math.abs(f.place - total) < 1e-12 * total) return "top reflection";
  return "interface";
}

export function fillEvents(d) {
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
export const ancestry = { parents: new Map() };

export function highlight(id) {
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

export function download(name, blob) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

export function pointName() {
  return state.mode === "bilayer" ? `impact-x${state.x}-alpha${state.alpha}` : "impact-scene";
}

export function downloadPng() {
  if (!live.lastDiagram) return;
  const svg = $("diagram").querySelector("svg");
  const w = Number(svg.getAttribute("width")) || svg.viewBox.baseVal.width;
  const h = Number(svg.getAttribute("height")) || svg.viewBox.baseVal.height;
  const img = new Image();
  img.onerror = () => showError("the diagram could not be drawn as a PNG: download the SVG");
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
  img.src = "data:image/svg+xml;charset=utf-8," + encodeURIComponent(live.lastDiagram.svg);
}
