// insitu studio: what its three panels share (the API call, the status line, the
// tabs). Plain JavaScript, no build step, nothing fetched but the studio's own routes
// (src/studio/studio_server.h lists them). points.js, shots.js: one panel each.
"use strict";

const $ = (id) => document.getElementById(id);

// Opened from the address insitu studio printed, the page holds its token as a cookie now
// (HttpOnly: no script reads it); the token leaves the address bar and the history.
if (new URLSearchParams(location.search).has("token")) history.replaceState(null, "", location.pathname);

async function api(method, url, body) {
  const r = await fetch(url, { method, headers: { "Content-Type": "application/json" },
                               body: body === undefined ? undefined : JSON.stringify(body) });
  let data = null;
  try { data = await r.json(); } catch (e) { data = { error: `${url}: HTTP ${r.status}` }; }
  return { status: r.status, data };
}

function status(text, cls) { const s = $("status"); s.textContent = text; s.className = cls || ""; }

// Text with the class "error" in a fresh span (never innerHTML: messages quote file contents).
function error_span(text) { const e = document.createElement("span"); e.className = "error"; e.textContent = text; return e; }

// The tabs: each panel registers what to do when it is shown.
const PANELS = {};
function show_panel(name) {
  document.querySelectorAll("nav button").forEach((b) => b.classList.toggle("active", b.dataset.panel === name));
  document.querySelectorAll("main").forEach((m) => { m.hidden = m.id !== `panel-${name}`; });
  if (PANELS[name]) PANELS[name]();
}
document.querySelectorAll("nav button").forEach((b) => { b.onclick = () => show_panel(b.dataset.panel); });
