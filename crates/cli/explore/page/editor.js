// impact explore: the scene editor.

import { $, live, numberOrNull, state } from "./state.js";
import { schedule } from "./point.js";

// A number as the field shows it: SI moduli (2.07e+11) in exponent form,
// so a narrow field shows their leading digits; text typed is kept as typed.
function shown(v) {
  const a = Math.abs(v);
  return typeof v === "number" && (a >= 1e5 || (a > 0 && a < 1e-3)) ? v.toExponential() : v;
}

export function renderLayers() {
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
      .concat(live.materials.map((m) => `<option value="${m.name}" ${m.name === layer.material ? "selected" : ""}>${m.name}</option>`))
      .join("");
    tr.innerHTML = `<td>${k + 1}${k === 0 ? " (bottom)" : ""}</td>
      <td><select data-key="material">${opts}</select></td>
      <td><input type="number" step="any" data-key="length" value="${shown(layer.length)}"></td>
      <td><input type="number" step="any" data-key="modulus" value="${shown(layer.modulus)}"></td>
      <td><input type="number" step="any" data-key="density" value="${shown(layer.density)}"></td>
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

export function onLayerEdit(ev) {
  const el = ev.target;
  const tr = el.closest("tr");
  if (!tr || !el.dataset.key) return;
  const k = Number(tr.dataset.layer);
  const layer = state.layers[k];
  const key = el.dataset.key;
  if (key === "material") {
    layer.material = el.value;
    const m = live.materials.find((m) => m.name === el.value);
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

export function addLayer() {
  const si = state.units === "si";
  state.layers.push({ material: "", length: si ? 0.01 : 0.5, modulus: si ? 1e9 : 0.5, density: si ? 1000 : 1, visc: "none", viscValue: "" });
  state.mode = "scene";
  renderLayers();
  schedule();
}


// The scene as the command line reads it, or the field that is not a number.
export function sceneJson() {
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

export function isViscous() {
  return state.mode === "scene" && state.layers.some((l) => l.visc !== "none");
}
