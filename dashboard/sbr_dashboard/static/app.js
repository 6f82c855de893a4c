// SPDX-License-Identifier: MIT
// sbr dashboard page: renders the JSON snapshots the server pushes (server-sent events).
"use strict";
const $ = (id) => document.getElementById(id);
const NS = "http://www.w3.org/2000/svg";
const MANDATORY = /^(Go|Keep|Roundabout)/;
const DANGER = /^(Danger|Bend|UnevenRoad|SlipperyRoad|RoadNarrows|Construction|TrafficSignal|PedestrianCrossing|SchoolCrossing|CyclesCrossing|Snow|Animals|PriorityNextIntersection)/;

function esc(s) {
  return String(s).replace(/[&<>"]/g, (c) => ({"&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;"}[c]));
}

// A sign icon (SVG markup) from the DBC class name; speed-limit signs show their value.
function signIcon(name, speed) {
  name = name || "?";
  const label = speed != null ? String(speed) : name.replace(/[a-z]/g, "").slice(0, 4);
  const text = (fill, size) =>
    `<text x="50" y="${50 + size * 0.35}" font-size="${size}" text-anchor="middle" font-family="sans-serif" font-weight="bold" fill="${fill}">${esc(label)}</text>`;
  let body;
  if (name.startsWith("RestrictionEnds")) {
    body = `<circle cx="50" cy="50" r="44" fill="#fff" stroke="#333" stroke-width="3"/><line x1="20" y1="80" x2="80" y2="20" stroke="#555" stroke-width="10"/>`;
  } else if (name === "Stop") {
    body = `<polygon points="30,6 70,6 94,30 94,70 70,94 30,94 6,70 6,30" fill="#c8102e"/>` +
      `<text x="50" y="59" font-size="26" text-anchor="middle" font-family="sans-serif" font-weight="bold" fill="#fff">STOP</text>`;
  } else if (name === "GiveWay") {
    body = `<polygon points="6,10 94,10 50,92" fill="#fff" stroke="#c8102e" stroke-width="10"/>`;
  } else if (name === "PriorityRoad") {
    body = `<polygon points="50,4 96,50 50,96 4,50" fill="#fff"/><polygon points="50,18 82,50 50,82 18,50" fill="#f2b300"/>`;
  } else if (name === "NoEntry") {
    body = `<circle cx="50" cy="50" r="46" fill="#c8102e"/><rect x="20" y="42" width="60" height="16" fill="#fff"/>`;
  } else if (MANDATORY.test(name)) {
    body = `<circle cx="50" cy="50" r="46" fill="#1f5fbf"/>` + text("#fff", 24);
  } else if (DANGER.test(name)) {
    body = `<polygon points="50,6 96,90 4,90" fill="#fff" stroke="#c8102e" stroke-width="9" stroke-linejoin="round"/>` +
      `<text x="50" y="76" font-size="22" text-anchor="middle" font-family="sans-serif" font-weight="bold" fill="#111">${esc(label)}</text>`;
  } else {
    body = `<circle cx="50" cy="50" r="42" fill="#fff" stroke="#c8102e" stroke-width="9"/>` + text("#111", speed != null ? 34 : 22);
  }
  return `<svg viewBox="0 0 100 100">${body}</svg>`;
}

// The bans as an instrument cluster draws them: a red ring with two cars (the truck's
// one dark red on the left), and the priority-road diamond.
function banIcon(trucks) {
  const car = (x, fill) => `<rect x="${x}" y="40" width="18" height="26" rx="4" fill="${fill}"/>`;
  return `<svg viewBox="0 0 100 100"><circle cx="50" cy="50" r="42" fill="#fff" stroke="#c8102e" stroke-width="9"/>` +
    (trucks ? `<rect x="24" y="36" width="22" height="32" rx="2" fill="#c8102e"/>` : car(28, "#c8102e")) +
    car(54, "#111") + `</svg>`;
}

function renderRestrictions(s) {
  const r = s.restrictions;
  const icons = [];
  if (r && r.no_overtaking) icons.push(`<div class="restr" id="restr-no-overtaking" title="no overtaking">${banIcon(false)}</div>`);
  if (r && r.no_overtaking_trucks) icons.push(`<div class="restr" id="restr-no-overtaking-trucks" title="no overtaking for trucks">${banIcon(true)}</div>`);
  if (r && r.priority_road) icons.push(`<div class="restr" id="restr-priority" title="priority road">${signIcon("PriorityRoad")}</div>`);
  $("restr-icons").innerHTML = icons.join("");
  $("limit-age").textContent = r && r.speed_limit != null ? `(seen ${r.speed_age_s} s ago)` : "";
  $("restr-text").textContent = r == null ? "the ECU sends no restrictions: the limit is read from the confirmed signs"
    : [r.no_overtaking ? "no overtaking" : "", r.no_overtaking_trucks ? "no overtaking for trucks" : "",
       r.priority_road ? "priority road" : ""].filter((x) => x).join(" · ");
}

function setCount(id, v) {
  const el = $(id);
  el.textContent = v;
  el.classList.toggle("nonzero", Number(v) > 0);
}

function fmt(v, digits) {
  return v == null ? "--" : Number(v).toFixed(digits);
}

function renderPlane(s) {
  const svg = $("plane");
  let w = 1360, h = 800;
  for (const d of s.detections) { w = Math.max(w, d.cx + d.w / 2); h = Math.max(h, d.cy + d.h / 2); }
  for (const o of s.objects) { w = Math.max(w, o.x + 10); h = Math.max(h, o.y + 10); }
  svg.setAttribute("viewBox", `0 0 ${Math.ceil(w)} ${Math.ceil(h)}`);
  let out = `<rect x="0" y="0" width="${w}" height="${h}" fill="none" stroke="#333"/>`;
  for (const d of s.detections) {
    out += `<g class="det"><rect x="${d.cx - d.w / 2}" y="${d.cy - d.h / 2}" width="${d.w}" height="${d.h}" fill="none" stroke="#ffd400" stroke-width="3"/>` +
      `<text x="${d.cx - d.w / 2}" y="${d.cy - d.h / 2 - 6}" fill="#ffd400" font-size="22">${esc(d.class_name || d.class_id)} ${fmt(d.confidence, 0)}%</text></g>`;
  }
  for (const o of s.objects) {
    out += `<g class="obj"><circle cx="${o.x}" cy="${o.y}" r="9" fill="#3fd0ff"/>` +
      `<line x1="${o.x}" y1="${o.y}" x2="${o.x + o.vx * 0.5}" y2="${o.y + o.vy * 0.5}" stroke="#3fd0ff" stroke-width="3"/>` +
      `<text x="${o.x + 12}" y="${o.y - 12}" fill="#3fd0ff" font-size="20">#${o.track} ${fmt(o.certainty, 0)}%</text></g>`;
  }
  svg.innerHTML = out;
}

const expanded = new Set();  // message names whose signals are shown
let lastState = null;

function messageRow(m) {
  const cols = ["received", "valid", "crc", "repeated", "skipped", "bad_counter", "length", "out_of_range", "timeouts"];
  const period = m.period_ms == null ? "--" : `${fmt(m.period_ms, 1)} ms`;
  const off = m.period_ms != null && Math.abs(m.period_ms - m.cycle_ms) > 0.1 * m.cycle_ms;
  return `<tr data-msg="${esc(m.name)}" class="msg state-${m.state.replace(/ /g, "-")}${expanded.has(m.name) ? " open" : ""}">` +
    `<td>${m.id}</td><td class="name">${esc(m.name)}</td><td class="state">${esc(m.state)}</td>` +
    `<td class="dlc">${m.dlc == null ? "--" : m.dlc}</td><td class="bytes">${esc(m.data || "--")}</td>` +
    `<td class="cycle">${m.cycle_ms} ms</td><td class="period${off ? " nonzero" : ""}">${period}</td>` +
    `<td class="jitter">${m.jitter_ms == null ? "--" : fmt(m.jitter_ms, 1) + " ms"}</td>` +
    cols.map((c) => `<td class="${c}${c !== "received" && c !== "valid" && m[c] > 0 ? " nonzero" : ""}">${m[c]}</td>`).join("") +
    `</tr>`;
}

function signalRows(m) {
  if (!m.signals.length) return `<tr class="signals" data-for="${esc(m.name)}"><td></td><td colspan="16">no valid frame yet</td></tr>`;
  const rows = m.signals.map((g) =>
    `<tr><td class="sig-name">${esc(g.name)}</td><td class="sig-value">${esc(g.value)}${g.unit ? " " + esc(g.unit) : ""}</td>` +
    `<td class="sig-raw">raw ${g.raw}</td><td class="sig-choice">${esc(g.choice)}</td></tr>`).join("");
  return `<tr class="signals" data-for="${esc(m.name)}"><td></td><td colspan="16">` +
    `<table class="sig"><thead><tr><th>signal (newest valid frame)</th><th>value</th><th>raw</th><th>DBC value name</th></tr></thead>` +
    `<tbody>${rows}</tbody></table></td></tr>`;
}

function renderMessages(s) {
  $("messages").tBodies[0].innerHTML = s.messages.map((m) =>
    messageRow(m) + (expanded.has(m.name) ? signalRows(m) : "")).join("");
}

function traceMatches(f, q, problemsOnly) {
  if (problemsOnly && f.check === "ok") return false;
  if (!q) return true;
  q = q.trim().toLowerCase();
  return f.id.toLowerCase() === q || f.id.toLowerCase() === "0x" + q.replace(/^0x0*/, "").padStart(3, "0") ||
    f.name.toLowerCase().includes(q);
}

function renderTrace() {
  if (!lastState) return;
  const q = $("trace-filter").value, only = $("trace-problems").checked;
  const shown = lastState.trace.filter((f) => traceMatches(f, q, only)).reverse();
  $("trace-count").textContent = lastState.trace.length;
  $("trace").tBodies[0].innerHTML = shown.map((f) =>
    `<tr class="check-${esc(f.check)}" data-id="${f.id}"><td>${fmt(f.t, 4)}</td><td>${f.id}</td><td>${esc(f.name || "?")}</td>` +
    `<td>${f.dlc}</td><td class="bytes">${esc(f.data)}</td><td class="check">${esc(f.check)}</td></tr>`).join("");
}

function render(s) {
  $("source").textContent = s.source;
  const st = $("source-state");
  const problems = s.totals.e2e_errors + s.totals.timeouts + s.totals.out_of_range;
  st.textContent = s.source_ended ? "source ended" : (s.frames ? "receiving" : "waiting");
  st.className = "badge " + (s.source_ended ? "ended" : (problems ? "bad" : "ok"));
  $("speed-limit").textContent = s.speed_limit == null ? "--" : `${s.speed_limit} km/h`;
  $("limit-sign").innerHTML = s.speed_limit == null ? "" : signIcon("SpeedLimit", s.speed_limit);
  renderRestrictions(s);
  $("sign-count").textContent = s.signs.length;
  $("signs").innerHTML = s.signs.map((x) =>
    `<div class="sign" data-class="${x.class_id}">${signIcon(x.class_name, x.speed)}` +
    `<div class="sign-name">${esc(x.class_name || x.class_id)}</div>` +
    `<div><span class="sign-conf">${fmt(x.confidence, 0)}</span> % · age ${x.age} frames</div></div>`).join("");
  $("det-count").textContent = s.detections.length;
  $("obj-text").innerHTML = s.tracker_seen
    ? `<span id="obj-count">${s.objects.length}</span> tracked objects`
    : `no SBR_TrackedObject frame received<span id="obj-count" hidden>0</span>`;
  renderPlane(s);
  const h = s.health, status = h.status || {};
  $("h-fps").textContent = fmt(h.fps, 1);
  $("h-proc").textContent = fmt(h.processing_ms, 1);
  $("h-proc-mean").textContent = fmt(h.processing_ms_mean, 1);
  $("h-cycle").textContent = h.cycle_ms == null ? "--" : h.cycle_ms;
  $("h-overload-now").hidden = !h.overload_now;
  $("h-frame-counter").textContent = status.FrameCounter == null ? "--" : status.FrameCounter;
  $("h-regions").textContent = status.RegionCount == null ? "--" : status.RegionCount;
  $("h-status-frames").textContent = h.status_frames;
  setCount("h-overload", h.flag_counts.overload);
  $("h-late").textContent = h.flag_counts.late;
  $("h-dropped").textContent = h.flag_counts.dropped;
  setCount("h-error", h.flag_counts.error);
  setCount("h-capacity", h.flag_counts.capacity);
  $("h-frames").textContent = s.frames;
  setCount("h-unknown", s.unknown);
  setCount("h-skipped", s.skipped_lines);
  setCount("t-e2e", s.totals.e2e_errors);
  setCount("t-timeouts", s.totals.timeouts);
  setCount("t-range", s.totals.out_of_range);
  $("h-time").textContent = `${fmt(s.source_time, 1)} s`;
  renderMessages(s);
  $("events").innerHTML = s.problems.map((t, i) =>
    `<li class="${esc(s.events[i] ? s.events[i].kind : "")}">${esc(t)}</li>`).join("");
  lastState = s;
  renderTrace();
  document.body.dataset.version = s.version;
  document.body.dataset.updates = Number(document.body.dataset.updates || 0) + 1;
  document.body.dataset.ended = s.source_ended ? "1" : "0";
}

document.addEventListener("click", (ev) => {
  const row = ev.target.closest("tr.msg");
  if (!row) return;
  const name = row.dataset.msg;
  if (expanded.has(name)) expanded.delete(name); else expanded.add(name);
  if (lastState) renderMessages(lastState);
});

function connect() {
  $("trace-filter").addEventListener("input", renderTrace);
  $("trace-problems").addEventListener("change", renderTrace);
  const es = new EventSource("/events");
  es.onopen = () => { $("link-state").textContent = "live"; $("link-state").className = "badge ok"; };
  es.onmessage = (ev) => render(JSON.parse(ev.data));
  es.onerror = () => { $("link-state").textContent = "reconnecting"; $("link-state").className = "badge bad"; };
}
connect();
