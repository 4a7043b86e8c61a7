// insitu studio's references of known albedo, in the points panel: a white sheet or a
// grey card in the photo, its corners clicked (snapped like points), saved to the scene file's
// "references" where inverse lighting reads them to fix the clipped light's scale.
"use strict";

const REFS = { list: [], version: "", drawing: null };

async function load_references() {
  const { status: code, data } = await api("GET", "/api/references");
  if (code !== 200) { $("ref-state").replaceChildren(error_span(data.error)); return; }
  REFS.list = data.references; REFS.version = data.version;
  references_list(); draw();
}

function references_list() {
  const ul = $("references");
  ul.replaceChildren();
  REFS.list.forEach((r, i) => {
    const li = document.createElement("li");
    const corners = Array.isArray(r.polygon_px) ? r.polygon_px.length : 0;
    li.textContent = `#${i + 1}: albedo ${r.albedo}, ${corners} corners `;
    const del = document.createElement("button");
    del.textContent = "✕"; del.title = "remove this reference from the scene file";
    del.onclick = () => edit_references({ op: "remove", index: i });
    li.append(del);
    ul.append(li);
  });
}

// An edit sent with the version it was made from: saved, refused where it is wrong, or a conflict.
async function edit_references(edit) {
  const { status: code, data } = await api("POST", "/api/references", { version: REFS.version, ...edit });
  if (code === 200) {
    $("ref-state").textContent = edit.op === "add" ? "reference saved to the scene file" : "reference removed";
    REFS.drawing = null; drawing_buttons();
  } else {
    $("ref-state").replaceChildren(error_span(data.error));
  }
  await load_references();
}

function drawing_buttons() {
  $("ref-draw").disabled = REFS.drawing !== null;
  $("ref-finish").disabled = !(REFS.drawing && REFS.drawing.length >= 3);
  $("ref-cancel").disabled = REFS.drawing === null;
  $("ref-state").textContent = REFS.drawing ? `click the reference's corners in the photo: ${REFS.drawing.length} so far` : $("ref-state").textContent;
}

// A click on the photo while drawing: a corner (snapped like a point). Returns whether it took it.
function reference_click(uv) {
  if (REFS.drawing === null) return false;
  REFS.drawing.push(uv);
  drawing_buttons(); draw();
  return true;
}

function polygon(corners, stroke, fill) {
  if (corners.length === 0) return;
  ctx.beginPath();
  corners.forEach((c, k) => { const [x, y] = to_screen(c[0], c[1]); if (k) ctx.lineTo(x, y); else ctx.moveTo(x, y); });
  if (fill) { ctx.closePath(); ctx.fillStyle = fill; ctx.fill(); }
  ctx.strokeStyle = stroke; ctx.lineWidth = 2; ctx.stroke();
}

// Called by points.js's draw(): the saved references filled, the one being drawn open.
function draw_references() {
  REFS.list.forEach((r, i) => {
    if (!Array.isArray(r.polygon_px)) return;
    polygon(r.polygon_px, "#60ff90", "rgba(96,255,144,0.25)");
    const [x, y] = to_screen(r.polygon_px[0][0], r.polygon_px[0][1]);
    ctx.fillStyle = "#60ff90"; ctx.fillText(`reference #${i + 1}, albedo ${r.albedo}`, x + 6, y - 6);
  });
  if (REFS.drawing) {
    polygon(REFS.drawing, "#60ff90", null);
    REFS.drawing.forEach((c) => circle(c, 3, "#60ff90"));
  }
}

$("ref-draw").onclick = () => { REFS.drawing = []; drawing_buttons(); };
$("ref-cancel").onclick = () => { REFS.drawing = null; $("ref-state").textContent = ""; drawing_buttons(); draw(); };
$("ref-finish").onclick = () =>
  edit_references({ op: "add", polygon_px: REFS.drawing, albedo: Number($("ref-albedo").value) });
load_references();
