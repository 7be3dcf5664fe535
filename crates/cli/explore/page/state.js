// impact explore: the page's state, kept in the URL, and small helpers.

export const $ = (id) => document.getElementById(id);

// ---------------------------------------------------------------- state

export const state = {
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


export function canonicalLayers(x, alpha) {
  return [
    { material: "", length: 1 - x, modulus: 1 - alpha, density: 1, visc: "none", viscValue: "" },
    { material: "", length: x, modulus: alpha, density: 1, visc: "none", viscValue: "" },
  ];
}

export function round6(v) {
  return Number(Number(v).toFixed(6));
}

// ------------------------------------------------------------ URL state

export function saveUrl() {
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

export function loadUrl() {
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

// What the page holds between requests.
export const live = {
  materials: [],
  map: null, // the finest map received so far
  lastRun: null, // the last run's JSON
  lastDiagram: null, // the last diagram reply
  inflight: null, // AbortController of the point's requests
};

export function fmt(v, digits) {
  return v === null || v === undefined ? "–" : Number(v).toFixed(digits);
}

export function numberOrNull(v) {
  if (v === "" || v === null || v === undefined) return null;
  const n = Number(v);
  return Number.isFinite(n) ? n : null;
}
