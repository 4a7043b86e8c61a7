// insitu studio's light and render panel: a render of the scene
// streamed pass by pass with its noise figure, the tone map's key and bias re-mapping the current
// image without rendering again (the legacy brightness slider), an A/B flip between the scene's
// integrator and `realtime` (the legacy real-time path), and the light the render uses: the
// radiance cube and its irradiance. The server renders (render_job.h); this page polls it.
"use strict";

const R = { status: null, shown: null, timer: null, seen: {} };

function tonemap_query() {
  const op = $("tonemap").value;
  if (op === "photo") return "tonemap=photo";
  const key = Math.exp(Number($("key").value));  // the slider is log(key)
  return `tonemap=${op}&key=${key.toFixed(4)}&bias=${Number($("bias").value).toFixed(2)}`;
}

function show_image() {
  const slots = R.status ? R.status.slots : {};
  if (!R.shown || !slots[R.shown] || !slots[R.shown].image) return;
  const s = slots[R.shown];
  $("render-image").src = `/api/render/${R.shown}.png?${tonemap_query()}&pass=${s.passes}&t=${s.seconds}`;
  $("render-image").hidden = false;  // hidden until there is an image (no broken-image icon)
  $("render-caption").textContent = `${R.shown}: ${s.spp_done} of ${s.spp} spp in ${s.seconds.toFixed(1)} s, ` +
    `noise ${s.noise >= 0 ? (100 * s.noise).toFixed(2) + " %" : "–"}${s.done ? "" : " (rendering)"}`;
}

function ab_buttons() {
  const row = $("ab");
  row.replaceChildren();
  for (const name of Object.keys(R.status.slots)) {
    const b = Object.assign(document.createElement("button"), { textContent: name, className: name === R.shown ? "active" : "" });
    b.dataset.slot = name;
    b.onclick = () => { R.shown = name; ab_buttons(); show_image(); };
    row.append(b);
  }
}

async function poll() {
  const { status: code, data } = await api("GET", "/api/render");
  if (code !== 200) return;
  R.status = data;
  const busy = data.state === "loading" || data.state === "rendering";
  const slot = data.slots[data.integrator];
  const percent = Math.round(100 * (data.state === "done" ? 1 : data.fraction));
  $("render-progress").value = percent;
  $("render-state").textContent = data.state === "loading" ? "loading the scene…" :
    `${data.integrator}: ${data.state}, ${percent} %` + (slot && slot.noise >= 0 ? `, noise ${(100 * slot.noise).toFixed(2)} %` : "");
  $("render-error").replaceChildren(...(data.error ? [error_span(`${data.error.where ? data.error.where + ": " : ""}${data.error.what}`)] : []));
  if (data.light && !R.seen.light) {
    R.seen.light = true;
    $("light-cube").src = `/api/light/cube.png?t=${Date.now()}`;
    $("light-irradiance").src = `/api/light/irradiance.png?t=${Date.now()}`;
    $("light-cube").hidden = $("light-irradiance").hidden = false;
  }
  if (busy || !R.shown) R.shown = data.integrator || R.shown;
  ab_buttons();
  const key = R.shown && data.slots[R.shown] ? `${R.shown}:${data.slots[R.shown].passes}:${data.slots[R.shown].done}` : "";
  if (key !== R.seen.image) { R.seen.image = key; show_image(); }
  if (!busy && R.timer) { clearInterval(R.timer); R.timer = null; }
}

async function start_render(integrator) {
  const spp = $("spp").value === "" ? 0 : Number($("spp").value);
  const denoise = $("denoise").checked;
  const { status: code, data } = await api("POST", "/api/render", { integrator, spp, denoise });
  if (code !== 200) { $("render-error").replaceChildren(error_span(data.error)); return; }
  R.seen.light = false;
  R.shown = null;
  if (!R.timer) R.timer = setInterval(poll, 300);
  poll();
}

$("render-scene").onclick = () => start_render("");
$("render-realtime").onclick = () => start_render("realtime");
$("render-stop").onclick = async () => { await api("POST", "/api/render/stop"); poll(); };
for (const id of ["tonemap", "key", "bias"]) $(id).oninput = () => {
  $("key-value").textContent = Math.exp(Number($("key").value)).toFixed(2);
  $("bias-value").textContent = Number($("bias").value).toFixed(2);
  show_image();
};
// Save asks before it replaces outputs that exist (a final render, say): the server answers 409
// with what exists and both renders' spp.
$("render-save").onclick = async () => {
  let { status: code, data } = await api("POST", "/api/render/save", {});
  if (code === 409 && data.existing && window.confirm(`${data.existing.join(", ")}: ${data.what}`))
    ({ status: code, data } = await api("POST", "/api/render/save", { overwrite: true }));
  if (code === 200) $("saved").replaceChildren(Object.assign(document.createElement("span"), { className: "ok", textContent: `wrote ${data.written.join(", ")}` }));
  else $("saved").replaceChildren(error_span(data.error));
};

// The tone map shown first is the scene's own, the one "Save outputs" writes.
api("GET", "/api/state").then(({ status: code, data }) => {
  if (code !== 200 || !data.tonemap) return;
  $("tonemap").value = data.tonemap.op;
  if (data.tonemap.key > 0) $("key").value = Math.log(data.tonemap.key);
  if (data.tonemap.bias > 0) $("bias").value = data.tonemap.bias;
  $("key-value").textContent = Math.exp(Number($("key").value)).toFixed(2);
  $("bias-value").textContent = Number($("bias").value).toFixed(2);
});
PANELS.render = poll;
