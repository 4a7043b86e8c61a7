// insitu studio's points panel: the photo with zoom and pan, a click snapped
// to the corner, the table of 2D–3D points saved to points.json, and the calibration drawn over
// the photo after every change.
"use strict";

const GAIN = 10;  // residual vectors are drawn this many times their length
const S = { width: 0, height: 0, photo: new Image(), points: [], version: "", calib: null, editable: true,
            errors: {}, selected: -1, view: { scale: 1, ox: 0, oy: 0 }, drag: null };
const canvas = $("photo"), ctx = canvas.getContext("2d");

// ---- the points and the files --------------------------------------------------------------

function complete(p) { return p.xyz.every((v) => typeof v === "number" && isFinite(v)); }
function savable() { return S.points.filter(complete).map((p) => ({ name: p.name, uv: p.uv, xyz: p.xyz })); }

// The index of the point a library error names ("points.json:$[2].xyz: ..."), or -1.
// The library counts only the saved (complete) points; the table counts all of them.
function point_of(where) {
  const m = /\$(?:\.points)?\[(\d+)\]/.exec(where || "");
  if (!m) return -1;
  let k = +m[1];
  for (let i = 0; i < S.points.length; ++i) if (complete(S.points[i]) && k-- === 0) return i;
  return -1;
}

async function load() {
  const { status: code, data } = await api("GET", "/api/state");
  if (code !== 200) { status(data.error, "error"); return; }
  $("scene").textContent = data.scene;
  // A camera from fSpy, a camera file or numbers: no points to edit, the references still are.
  S.editable = data.points_refusal === null;
  $("points-editor").hidden = !S.editable;
  $("points-refusal").hidden = S.editable;
  $("points-refusal").textContent = S.editable ? "" : `${data.points_refusal}. The references, the shots and the render work as usual.`;
  $("click-hint").hidden = !S.editable;
  $("points-file").textContent = data.points_file;
  $("model").value = data.model;
  S.width = data.photo.width; S.height = data.photo.height; S.version = data.version;
  const list = Array.isArray(data.points) ? data.points : (data.points && data.points.points) || [];
  S.points = list.map((p, i) => ({ name: p.name || `#${i + 1}`, uv: p.uv, xyz: p.xyz, snap: null }));
  S.errors = {};
  if (S.editable && data.points === null) status(`${data.points_file} is not valid JSON; saving will replace it`, "error");
  S.photo.onload = () => { fit(); changed(false, true); };
  S.photo.src = data.photo.url + "?v=" + Date.now();
}

async function save() {
  const points = savable();
  const { status: code, data } = await api("PUT", "/api/points", { version: S.version, points });
  if (code === 200) {
    S.version = data.version;
    $("save-state").innerHTML = `<span class="ok">saved ${points.length} points</span>`;
    return true;
  }
  if (code === 409) {
    $("save-state").innerHTML = `<span class="error"></span> <button id="reload">Reload</button>`;
    $("save-state").firstChild.textContent = data.error;
    $("reload").onclick = load;
  } else {
    const i = point_of(data.where);
    if (i >= 0) S.errors[i] = data.what; else $("save-state").innerHTML = `<span class="error"></span>`;
    if (i < 0) $("save-state").firstChild.textContent = data.error;
  }
  return false;
}

async function calibrate() {
  const points = savable();
  if (points.length < 5) {
    S.calib = null;
    $("summary").textContent = `${points.length} complete points: calibration needs at least 5.`;
    $("report").textContent = "";
    return;
  }
  const { status: code, data } = await api("POST", "/api/calibrate", { points, model: $("model").value });
  if (code !== 200) {
    S.calib = null;
    const i = point_of(data.where);
    if (i >= 0) S.errors[i] = data.what;
    $("summary").innerHTML = `<span class="error"></span>`;
    $("summary").firstChild.textContent = data.error;
    $("report").textContent = "";
    return;
  }
  S.calib = data;
  $("summary").textContent = `model ${data.model}, σ ${data.sigma_px.toFixed(2)} px, rms ${data.rms_px.toFixed(2)} px, ` +
                             `${data.inliers} of ${points.length} points used. ${data.selection}`;
  $("report").textContent = data.report + (data.warnings.length ? "\n" + data.warnings.join("\n") : "");
}

// After every change: save the complete points, then calibrate, then draw. The table is rebuilt
// only when points come or go (`rebuild`); an edit updates its cells in place, so the field being
// typed in keeps its focus and its text.
async function changed(write = true, rebuild = false) {
  S.errors = {};
  if (!S.editable) { draw(); return; }
  const incomplete = S.points.filter((p) => !complete(p)).length;
  if (write) await save();
  if (incomplete) $("save-state").textContent = `${incomplete} point(s) need x, y and z before they are saved.`;
  await calibrate();
  if (rebuild) table(); else update_table();
  draw();
}

// ---- the table ---------------------------------------------------------------------------

function residual_of(i) {
  if (!S.calib || !complete(S.points[i])) return null;
  const k = S.points.slice(0, i).filter(complete).length;
  return S.calib.points[k];
}

function table() {
  const body = document.querySelector("#points tbody");
  body.innerHTML = "";
  S.points.forEach((p, i) => {
    const tr = document.createElement("tr");
    const cell = (el) => { const td = document.createElement("td"); if (el) td.append(el); tr.append(td); return td; };
    cell(document.createTextNode(String(i + 1)));
    const name = document.createElement("input");
    name.className = "name"; name.value = p.name;
    name.onchange = () => { p.name = name.value; changed(); };
    cell(name);
    const uv = cell(document.createTextNode(`${p.uv[0].toFixed(1)}, ${p.uv[1].toFixed(1)}`));
    if (p.snap) {
      const s = document.createElement("div");
      s.className = "snap";
      s.textContent = p.snap.snapped ? `snapped ${p.snap.offset[0].toFixed(2)}, ${p.snap.offset[1].toFixed(2)}` : "no corner: as clicked";
      s.title = p.snap.snapped ? "moved to the image corner found by OpenCV's cornerSubPix (offset in px)" : "no corner within 5 px: the point stays where it was clicked";
      uv.append(s);
    }
    for (let k = 0; k < 3; ++k) {
      const input = document.createElement("input");
      input.type = "number"; input.step = "any"; input.value = p.xyz[k] ?? "";
      input.dataset.point = i; input.dataset.axis = k;
      input.onchange = () => { p.xyz[k] = input.value === "" ? null : Number(input.value); changed(); };
      cell(input);
    }
    cell(null).className = "residual";
    const del = document.createElement("button");
    del.textContent = "✕"; del.title = "remove this point";
    del.onclick = () => { S.points.splice(i, 1); S.selected = -1; changed(true, true); };
    cell(del);
    tr.onclick = (ev) => { if (ev.target.tagName !== "INPUT" && ev.target.tagName !== "BUTTON") { S.selected = i; update_table(); draw(); } };
    body.append(tr);
  });
  update_table();
}

// Each row's residual, outlier mark and error, from the latest calibration.
function update_table() {
  document.querySelectorAll("#points tbody tr").forEach((tr, i) => {
    const r = residual_of(i);
    tr.classList.toggle("selected", i === S.selected);
    tr.classList.toggle("outlier", !!(r && r.outlier));
    const res = tr.querySelector("td.residual");
    res.textContent = r ? `${Math.hypot(r.residual[0], r.residual[1]).toFixed(2)} px${r.outlier ? " outlier" : ""}` : "";
    if (S.errors[i]) { const e = document.createElement("div"); e.className = "error"; e.textContent = S.errors[i]; res.append(e); }
  });
}

// ---- the photo: zoom, pan, click ------------------------------------------------------------

function fit() {
  canvas.width = canvas.clientWidth; canvas.height = canvas.clientHeight;
  const s = Math.min(canvas.width / S.width, canvas.height / S.height);
  S.view = { scale: s, ox: (canvas.width - s * S.width) / 2, oy: (canvas.height - s * S.height) / 2 };
  draw();
}
function to_screen(u, v) { return [u * S.view.scale + S.view.ox, v * S.view.scale + S.view.oy]; }
function to_image(x, y) { return [(x - S.view.ox) / S.view.scale, (y - S.view.oy) / S.view.scale]; }

function line(a, b, colour, width = 1) {
  const [x0, y0] = to_screen(a[0], a[1]), [x1, y1] = to_screen(b[0], b[1]);
  ctx.strokeStyle = colour; ctx.lineWidth = width;
  ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x1, y1); ctx.stroke();
}
function circle(c, radius_px, colour, label) {
  const [x, y] = to_screen(c[0], c[1]);
  ctx.strokeStyle = colour; ctx.lineWidth = 1.5;
  ctx.beginPath(); ctx.arc(x, y, radius_px, 0, 2 * Math.PI); ctx.stroke();
  if (label) { ctx.fillStyle = colour; ctx.fillText(label, x + radius_px + 3, y - 3); }
}

function draw_calibration() {
  const c = S.calib;
  for (const l of c.lines) line(l.a, l.b, l.kind === "box" ? "rgba(255,210,60,0.8)" : "rgba(80,220,255,0.45)");
  for (const p of c.points) {
    const tip = [p.uv[0] + GAIN * p.residual[0], p.uv[1] + GAIN * p.residual[1]];
    line(p.uv, tip, p.outlier ? "#ff4040" : "#ff9040", 2);
  }
  if (!c.at_objects) return;
  for (const o of c.at_objects.objects) {
    const p = o.points[0];
    if (p && p.radius95_px !== null) circle(p.uv, Math.max(3, p.radius95_px * S.view.scale), "#ffa0ff", `${o.name} ±${p.radius95_px.toFixed(1)} px (95 %)`);
  }
  const next = c.at_objects.click_next;
  if (next) circle(next.uv, 8, "#60ff60", `click here next: (${next.world.map((v) => v.toFixed(2)).join(", ")}) m`);
}

function draw() {
  if (!S.width) return;
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  ctx.imageSmoothingEnabled = S.view.scale < 2;
  ctx.drawImage(S.photo, S.view.ox, S.view.oy, S.width * S.view.scale, S.height * S.view.scale);
  ctx.font = "12px system-ui, sans-serif";
  ctx.save();
  ctx.beginPath();
  ctx.rect(S.view.ox, S.view.oy, S.width * S.view.scale, S.height * S.view.scale);
  ctx.clip();  // the overlay stays on the photo
  if (S.calib) draw_calibration();
  draw_references();
  ctx.restore();
  S.points.forEach((p, i) => circle(p.uv, i === S.selected ? 7 : 4, complete(p) ? "#ffffff" : "#ffff00", String(i + 1)));
}

canvas.addEventListener("wheel", (ev) => {
  ev.preventDefault();
  const [u, v] = to_image(ev.offsetX, ev.offsetY), k = Math.exp(-ev.deltaY * 0.0015);
  S.view.scale *= k;
  S.view.ox = ev.offsetX - u * S.view.scale; S.view.oy = ev.offsetY - v * S.view.scale;
  draw();
}, { passive: false });
canvas.addEventListener("mousedown", (ev) => { S.drag = { x: ev.offsetX, y: ev.offsetY, moved: 0 }; });
canvas.addEventListener("mousemove", (ev) => {
  if (!S.drag) return;
  const dx = ev.offsetX - S.drag.x, dy = ev.offsetY - S.drag.y;
  S.drag.moved += Math.abs(dx) + Math.abs(dy);
  S.view.ox += dx; S.view.oy += dy; S.drag.x = ev.offsetX; S.drag.y = ev.offsetY;
  draw();
});
canvas.addEventListener("mouseup", async (ev) => {
  const click = S.drag && S.drag.moved < 4;
  S.drag = null;
  if (!click) return;
  const [u, v] = to_image(ev.offsetX, ev.offsetY);
  if (u < 0 || v < 0 || u > S.width || v > S.height) return;
  const { status: code, data } = await api("POST", "/api/snap", { uv: [u, v] });
  const snap = code === 200 ? data : null;
  if (reference_click(snap ? snap.uv : [u, v])) return;  // a corner of a reference (references.js)
  if (!S.editable) return;
  S.points.push({ name: `#${S.points.length + 1}`, uv: snap ? snap.uv : [u, v], xyz: [null, null, null], snap });
  S.selected = S.points.length - 1;
  table(); draw();
  const first = document.querySelector(`input[data-point="${S.selected}"][data-axis="0"]`);
  if (first) first.focus();
});
canvas.addEventListener("keydown", (ev) => { if (ev.key === "0") fit(); });
window.addEventListener("resize", fit);
$("model").onchange = () => changed(false);
PANELS.points = fit;
load();
