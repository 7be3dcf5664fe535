// impact explore: the page. Plain JavaScript modules, no dependencies,
// nothing fetched but this server's own API. The state lives in the URL.

import { $, canonicalLayers, fmt, live, loadUrl, numberOrNull, saveUrl, state } from "./state.js";
import { drawMap, loadMaps, mapPoint } from "./map.js";
import { addLayer, isViscous, onLayerEdit, renderLayers, sceneJson } from "./editor.js";
import { cancelRun, currentWindow, download, downloadPng, highlight, pointName, schedule, update } from "./point.js";

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
    const k = p.j * live.map.x.length + p.i;
    $("map-hover").textContent = `x = ${p.x}, α = ${p.alpha}: e = ${fmt(live.map.restitution[k], 6)}, t_c/(2Σt) = ${fmt(live.map.reduced_contact_time[k], 4)}, n1 = ${fmt(live.map.n1[k], 3)}, N_b = ${live.map.bounces[k] ?? "–"}`;
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
  $("cancel").addEventListener("click", cancelRun);
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
  $("dl-svg").addEventListener("click", () => live.lastDiagram && download(`${pointName()}.svg`, new Blob([live.lastDiagram.svg], { type: "image/svg+xml" })));
  $("dl-png").addEventListener("click", downloadPng);
  $("dl-json").addEventListener("click", () => live.lastRun && download(`${pointName()}.json`, new Blob([JSON.stringify(live.lastRun, null, 2)], { type: "application/json" })));
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
    live.materials = await (await fetch("/api/materials")).json();
  } catch (e) {
    live.materials = [];
  }
  if (!fromUrl) {
    const scene = await (await fetch("/api/scene")).json();
    if (scene && Array.isArray(scene.layers)) {
      state.mode = "scene";
      state.speed = scene.impact_speed;
      state.units = "si";
      if (scene.wall_contact) state.wall = scene.wall_contact;
      state.layers = scene.layers.map((l) => {
        const m = live.materials.find((m) => m.name === l.material);
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

// for scripts and the browser test: the scene as the API is sent it
window.impactExplore = { sceneJson };

start();
