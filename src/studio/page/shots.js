// insitu studio's shots panel: the six shots as insitu uses them, unfolded as
// seen from inside the room, with the faced wall marked, clipped pixels red (the server paints
// them) and each shot's coverage of its face. A click turns a shot or swaps two; the server edits
// the scene file (scene_edit.h) only if it has not changed since this page read it.
"use strict";

const SHOTS = { state: null };

// Turning right about +Y (clockwise seen from above): -z → +x → +z → -x.
const RING = ["-z", "+x", "+z", "-x"];
const FACE_INDEX = { "+x": 0, "-x": 1, "up": 2, "down": 3, "+z": 4, "-z": 5 };

// Grid cells (column, row) of each face: the walls in a row from the one left of the faced wall,
// the ceiling above and the floor below the faced wall.
function cube_layout(faced) {
  const k = RING.indexOf(faced);
  const at = {};
  for (let c = 0; c < 4; ++c) at[RING[(k + 3 + c) % 4]] = [c, 1];
  at.up = [1, 0]; at.down = [1, 2];
  return at;
}

async function load_shots() {
  const { status: code, data } = await api("GET", "/api/shots");
  if (code !== 200) { $("shots-error").replaceChildren(error_span(data.error)); return; }
  SHOTS.state = data;
  $("shots-scene").textContent = data.scene;
  $("shots-error").replaceChildren();
  if (data.error) $("shots-error").replaceChildren(error_span(`${data.error.where}: ${data.error.what}`));
  $("shots-warnings").replaceChildren(...data.warnings.map((w) => { const li = document.createElement("li"); li.textContent = w; return li; }));
  if (data.image) $("shots-state").textContent = `This scene is lit by the ${data.image_kind || "image"} ${data.image}, not by six shots.`;
  if (data.faced) $("faced").value = data.faced;
  draw_cube();
  draw_stitched();
}

// One line per shot: its outline's colour, and where registration, the room's lines and the photo
// put it.
function aim_text(shot) {
  const r = shot.registration, l = shot.room_lines, p = shot.photo_anchor;
  const parts = [];
  if (!r) parts.push("aimed as given (registration off)");
  else if (r.registered) parts.push(`registered: turned ${r.rotation_deg.toFixed(2)}° (yaw ${r.yaw_deg.toFixed(2)}°, pitch ${r.pitch_deg.toFixed(2)}°, roll ${r.roll_deg.toFixed(2)}°), residual ${r.residual_deg.toFixed(3)}° over ${r.matches} matches`);
  else parts.push(`not registered: ${r.reason}`);
  if (l) {
    const what = l.axes === "vertical" ? "plumb lines" : "room lines", how = l.axes === "vertical" ? "levelled by" : "turned";
    const off_box = l.off_box_turn_deg !== undefined;  // the box's turn was past a hand's misaim
    if (off_box) parts.push(`room lines: ${l.reason}`);
    if (l.anchored) parts.push(`${what}: ${how} ${l.turn_deg.toFixed(2)}° (σ ${l.sigma_deg.toFixed(2)}°)`);
    else if (!off_box) parts.push(`${what}: ${l.reason}`);
  }
  if (p) parts.push(p.anchored ? `photo: turned ${p.turn_deg.toFixed(2)}° over ${p.matches} matches, residual ${p.residual_deg.toFixed(3)}°` : `photo: ${p.reason}`);
  return parts.join("; ");
}

function draw_stitched() {
  const st = SHOTS.state;
  const img = $("stitched"), legend = $("stitched-legend");
  legend.replaceChildren();
  if (!st.shots.length || st.error || st.shots.some((s) => s.error)) { img.hidden = true; return; }
  img.hidden = false;
  img.src = `/api/shots/stitched.png?v=${st.version}`;
  for (const shot of st.shots) {
    const li = document.createElement("li");
    const swatch = Object.assign(document.createElement("span"), { className: "swatch" });
    swatch.style.background = shot.outline;
    li.append(swatch, Object.assign(document.createElement("b"), { textContent: shot.key }), " ", aim_text(shot));
    legend.append(li);
  }
  if (st.photo_anchor_note) {
    const li = Object.assign(document.createElement("li"), { className: "warn" });
    li.textContent = `not anchored to the photo: ${st.photo_anchor_note}`;
    legend.append(li);
  }
  if (st.gap_percent !== undefined) {
    const li = document.createElement("li");
    li.className = st.gap_percent > 0.05 ? "warn" : "";
    li.textContent = st.gap_percent > 0.05 ? `${st.gap_percent.toFixed(1)} % of the sphere no shot saw (hatched): filled in from its neighbours` : "no gap: every direction is in some shot";
    legend.append(li);
  }
}

// One edit of the scene file, then the shots read again.
async function edit_shots(change) {
  const { status: code, data } = await api("POST", "/api/shots", { version: SHOTS.state.version, ...change });
  if (code === 200) $("shots-state").replaceChildren(Object.assign(document.createElement("span"), { className: "ok", textContent: `saved ${SHOTS.state.scene}` }));
  else if (code === 409) {
    const reload = Object.assign(document.createElement("button"), { textContent: "Reload", onclick: load_shots });
    $("shots-state").replaceChildren(error_span(data.error), " ", reload);
    return;
  } else $("shots-state").replaceChildren(error_span(data.error));
  await load_shots();
}

function shot_cell(shot, faced) {
  const cell = document.createElement("div");
  cell.className = "cell" + (shot.face === faced ? " faced" : "");
  cell.dataset.face = shot.face;
  const img = document.createElement("img");
  img.src = `/api/shot/${FACE_INDEX[shot.face]}.png?v=${SHOTS.state.version}`;
  img.alt = `the ${shot.face} shot`;
  if (!shot.error) cell.append(img);
  const title = document.createElement("div");
  title.innerHTML = `<span class="key"></span> <span class="file"></span>`;
  title.querySelector(".key").textContent = shot.key === shot.face ? shot.face : `${shot.key} (${shot.face})`;
  const shown = shot.files[Math.floor(shot.files.length / 2)].split("/").pop();
  title.querySelector(".file").textContent = shot.files.length > 1 ? `${shown} (bracket of ${shot.files.length})` : shown;
  title.title = shot.files.join("\n");
  if (shot.face === faced) title.append(" ", Object.assign(document.createElement("span"), { className: "tag", textContent: "faced" }));
  cell.append(title);
  cell.append(shot_facts(shot), shot_buttons(shot));
  if (shot.error) cell.append(error_span(`${shot.error.where}: ${shot.error.what}`));
  return cell;
}

// Size, turn, field of view, clipping and coverage, as the library's assembly found them.
function shot_facts(shot) {
  const facts = document.createElement("div");
  const parts = [];
  if (shot.width) parts.push(`${shot.width}×${shot.height}`);
  if (shot.rotate_deg) parts.push(`turned ${shot.rotate_deg}°`);
  if (shot.hfov_deg !== undefined) parts.push(`${shot.hfov_deg.toFixed(1)}°`);
  if (shot.clipped_percent !== undefined) parts.push(`${shot.clipped_percent.toFixed(2)} % clipped`);
  facts.textContent = parts.join(" · ");
  facts.title = "size as used, horizontal field of view, pixels clipped (red)";
  if (shot.coverage_percent !== undefined) {
    const partial = shot.coverage_percent < 99.95;
    const cov = Object.assign(document.createElement("div"), { className: "coverage" + (partial ? " warn" : "") });
    cov.textContent = partial ? `covers ${shot.coverage_percent.toFixed(1)} % of its face (rest filled in)` : "covers its whole face";
    facts.append(cov);
  }
  return facts;
}

function shot_buttons(shot) {
  const row = document.createElement("div");
  const turn = Object.assign(document.createElement("button"), { className: "turn", textContent: "↻ turn", title: "turn this shot a quarter clockwise" });
  turn.onclick = () => edit_shots({ op: "turn", key: shot.key, by_deg: 90 });
  const swap = document.createElement("select");
  swap.className = "swap";
  swap.append(new Option("swap with…", ""));
  for (const other of SHOTS.state.shots) if (other.key !== shot.key) swap.append(new Option(other.key, other.key));
  swap.onchange = () => { if (swap.value) edit_shots({ op: "swap", a: shot.key, b: swap.value }); };
  row.append(turn, " ", swap);
  return row;
}

function draw_cube() {
  const cube = $("cube");
  cube.replaceChildren();
  const st = SHOTS.state;
  if (!st.shots.length) return;
  const at = cube_layout(st.faced);
  for (const shot of st.shots) {
    const cell = shot_cell(shot, st.faced);
    const [c, r] = at[shot.face];
    cell.style.gridColumn = String(c + 1); cell.style.gridRow = String(r + 1);
    cube.append(cell);
  }
}

$("faced").onchange = () => edit_shots({ op: "faced", wall: $("faced").value });
PANELS.shots = load_shots;
