// Compiled into the binary so the page works on a vehicle with no network and no share folder.
// It reads /events (Server-Sent Events of /state), shows /stream.mjpg, and posts /abort and
// /start with the token typed in (or given as ?token= in the address).
#include "app/view/operator_page.hpp"

namespace rovctl::app {
namespace {

constexpr std::string_view kPage = R"HTML(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>rovctl operator view</title>
<style>
  :root { color-scheme: dark; }
  body { margin: 0; font: 14px/1.35 system-ui, sans-serif; background: #10161d; color: #dde6ee; }
  header { display: flex; align-items: center; gap: 12px; padding: 8px 12px; background: #18222c; }
  header h1 { font-size: 16px; margin: 0 8px 0 0; font-weight: 600; }
  #state { font-size: 22px; font-weight: 700; padding: 2px 14px; border-radius: 6px;
           background: #2b3b4b; letter-spacing: 0.04em; }
  .banner { display: none; padding: 3px 10px; border-radius: 4px; font-weight: 700; }
  .banner.on { display: inline-block; }
  #b-failsafe { background: #c62828; } #b-hold { background: #ef6c00; }
  #b-not-ok { background: #6a5d00; } #b-link { background: #c62828; } #b-replay { background: #37474f; }
  main { display: grid; grid-template-columns: minmax(0, 3fr) minmax(260px, 1fr); gap: 10px; padding: 10px; }
  #cams { width: 100%; background: #000; border-radius: 4px; min-height: 120px; display: block; }
  .camlabels { display: flex; color: #8aa0b4; font-size: 12px; }
  .camlabels span { flex: 1; padding: 0 0 3px 4px; }
  #nocams { display: none; padding: 40px; text-align: center; background: #000; border-radius: 4px; }
  .panel { background: #18222c; border-radius: 6px; padding: 8px 10px; margin-bottom: 10px; }
  .panel h2 { font-size: 12px; text-transform: uppercase; color: #8aa0b4; margin: 0 0 6px 0; }
  table { width: 100%; border-collapse: collapse; }
  td { padding: 1px 0; } td.v { text-align: right; font-variant-numeric: tabular-nums; }
  canvas { width: 100%; display: block; }
  #abort { width: 100%; font-size: 28px; font-weight: 800; padding: 18px; margin: 4px 0 8px;
           background: #d32f2f; color: #fff; border: 3px solid #ff8a80; border-radius: 8px; cursor: pointer; }
  #start { width: 100%; font-size: 16px; padding: 8px; background: #2e7d32; color: #fff;
           border: 0; border-radius: 6px; cursor: pointer; }
  #token { width: 100%; box-sizing: border-box; margin: 6px 0; padding: 4px; }
  #cmd { min-height: 1.4em; color: #ffcc80; }
</style>
</head>
<body>
<header>
  <h1>rovctl</h1>
  <span id="state">&mdash;</span>
  <span class="banner" id="b-failsafe">FAILSAFE</span>
  <span class="banner" id="b-hold">OPERATOR HOLD</span>
  <span class="banner" id="b-not-ok">NOT OK</span>
  <span class="banner" id="b-link">NO DATA</span>
  <span class="banner" id="b-replay">REPLAY</span>
  <span style="margin-left:auto" id="clock"></span>
</header>
<main>
  <section>
    <div class="camlabels"><span>left camera</span><span>right camera</span></div>
    <img id="cams" alt="left and right cameras with the estimated marker drawn on them">
    <div id="nocams">No camera images in this recording: telemetry only.</div>
    <div class="panel" style="margin-top:10px">
      <h2>Fitness (last 30 s)</h2><canvas id="p-fit" height="90"></canvas>
      <h2>Docking errors (last 30 s): <span style="color:#4fc3f7">lateral</span>,
        <span style="color:#ffb74d">axial</span>, <span id="p-err-range"></span></h2>
      <canvas id="p-err" height="110"></canvas>
    </div>
  </section>
  <aside>
    <div class="panel">
      <button id="abort">ABORT</button>
      <button id="start">START docking</button>
      <input id="token" type="password" placeholder="operator token" autocomplete="off">
      <div id="cmd"></div>
    </div>
    <div class="panel"><h2>Estimate</h2><table>
      <tr><td>fitness</td><td class="v" id="v-fit"></td></tr>
      <tr><td>spheres seen L / R</td><td class="v" id="v-seen"></td></tr>
      <tr><td>error bound (position / rotation)</td><td class="v" id="v-bound"></td></tr>
      <tr><td>distance</td><td class="v" id="v-dist"></td></tr>
      <tr><td>lateral error</td><td class="v" id="v-lat"></td></tr>
      <tr><td>axial error</td><td class="v" id="v-ax"></td></tr>
      <tr><td>yaw error</td><td class="v" id="v-yaw"></td></tr>
    </table></div>
    <div class="panel"><h2>Thrusters</h2><canvas id="p-thr" height="120"></canvas>
      <table><tr><td>bus</td><td class="v" id="v-bus"></td></tr>
      <tr><td>armed</td><td class="v" id="v-armed"></td></tr>
      <tr><td>tick</td><td class="v" id="v-tick"></td></tr></table></div>
  </aside>
</main>
<script>
"use strict";
const $ = (id) => document.getElementById(id);
const params = new URLSearchParams(location.search);
$("token").value = params.get("token") || sessionStorage.getItem("rovctl-token") || "";
$("token").addEventListener("change", () => sessionStorage.setItem("rovctl-token", $("token").value));
window.rovctl = { seenStates: [], updates: 0, last: null, notOkShown: {} };
const history = [];
const fmt = (v, d, unit) => (v === null || v === undefined) ? "\u2014" : v.toFixed(d) + (unit || "");

function plot(canvas, series, ymin, ymax) {
  const w = canvas.width = canvas.clientWidth, h = canvas.height;
  const g = canvas.getContext("2d");
  g.fillStyle = "#0c1116"; g.fillRect(0, 0, w, h);
  if (history.length < 2) return;
  const t1 = history[history.length - 1].time_s, t0 = t1 - 30;
  const x = (t) => (t - t0) / 30 * w, y = (v) => h - (v - ymin) / (ymax - ymin) * h;
  g.strokeStyle = "#2b3b4b"; g.beginPath(); g.moveTo(0, y(0)); g.lineTo(w, y(0)); g.stroke();
  for (const [key, colour] of series) {
    g.strokeStyle = colour; g.lineWidth = 1.5; g.beginPath(); let pen = false;
    for (const s of history) {
      const v = s[key];
      if (v === null || s.time_s < t0) { pen = false; continue; }
      const cv = Math.max(ymin, Math.min(ymax, v));
      if (pen) g.lineTo(x(s.time_s), y(cv)); else g.moveTo(x(s.time_s), y(cv));
      pen = true;
    }
    g.stroke();
  }
}

function bars(canvas, values) {
  const w = canvas.width = canvas.clientWidth, h = canvas.height;
  const g = canvas.getContext("2d");
  g.fillStyle = "#0c1116"; g.fillRect(0, 0, w, h);
  const n = values.length || 1, bw = w / n, mid = h / 2;
  g.strokeStyle = "#2b3b4b"; g.beginPath(); g.moveTo(0, mid); g.lineTo(w, mid); g.stroke();
  values.forEach((v, i) => {
    g.fillStyle = v >= 0 ? "#4fc3f7" : "#ffb74d";
    g.fillRect(i * bw + 3, v >= 0 ? mid - v * mid : mid, bw - 6, Math.abs(v) * mid);
    g.fillStyle = "#8aa0b4"; g.fillText(String(i + 1), i * bw + bw / 2 - 3, h - 2);
  });
}

// Why the estimate is not trusted, as the banner says it (the reason's token from the estimator).
const NOT_OK_LABEL = { partial_view: "PARTIAL VIEW", not_refined: "NOT REFINED",
                       bound_over_limit: "BOUND OVER LIMIT", unconfirmed: "UNCONFIRMED" };

function show(s) {
  window.rovctl.updates++; window.rovctl.last = s;
  const name = s.state.toUpperCase();
  $("state").textContent = name;
  const seen = window.rovctl.seenStates;
  if (seen[seen.length - 1] !== name) seen.push(name);
  $("b-failsafe").classList.toggle("on", s.failsafe);
  $("b-hold").classList.toggle("on", s.operator_hold);
  const notOk = s.recognised && !s.ok;
  $("b-not-ok").classList.toggle("on", notOk);
  $("b-not-ok").textContent = NOT_OK_LABEL[s.not_ok_reason] || "NOT OK";
  if (notOk) window.rovctl.notOkShown[s.not_ok_reason] = $("b-not-ok").textContent;
  $("b-replay").classList.toggle("on", s.source === "replay");
  $("b-link").classList.remove("on");
  $("clock").textContent = "t = " + s.time_s.toFixed(1) + " s";
  $("v-fit").textContent = fmt(s.fitness, 3);
  $("v-seen").textContent = s.spheres_seen[0] + " / " + s.spheres_seen[1];
  $("v-bound").textContent =
      fmt(s.error_bound_mm, 1, " mm") + " / " + fmt(s.error_bound_deg, 1, "\u00b0");
  $("v-dist").textContent = fmt(s.distance_m, 3, " m");
  $("v-lat").textContent = fmt(s.lateral_error_mm, 1, " mm");
  $("v-ax").textContent = fmt(s.axial_error_mm, 1, " mm");
  $("v-yaw").textContent = fmt(s.yaw_error_deg, 2, "\u00b0");
  $("v-bus").textContent = s.bus;
  $("v-armed").textContent = s.armed ? "yes" : "no";
  $("v-tick").textContent = s.tick;
  $("abort").disabled = $("start").disabled = !s.commands_enabled;
  if (history.length && s.time_s < history[history.length - 1].time_s) history.length = 0;
  history.push(s);
  while (history.length && history[0].time_s < s.time_s - 30) history.shift();
  plot($("p-fit"), [["fitness", "#81c784"]], 0, 1);
  // Symmetric, and wide enough for the largest error in view (axial starts near a metre).
  let span = 20;
  for (const h of history) {
    for (const k of ["lateral_error_mm", "axial_error_mm"]) {
      if (h[k] !== null) span = Math.max(span, Math.abs(h[k]));
    }
  }
  span = Math.pow(10, Math.ceil(Math.log10(span) * 4) / 4);
  $("p-err-range").textContent = "\u00b1" + span.toFixed(0) + " mm";
  plot($("p-err"), [["lateral_error_mm", "#4fc3f7"], ["axial_error_mm", "#ffb74d"]], -span, span);
  bars($("p-thr"), s.thrust_fraction);
}

async function command(path) {
  const r = await fetch(path, { method: "POST", headers: { "X-Rovctl-Token": $("token").value } });
  $("cmd").textContent = path.slice(1).toUpperCase() + ": " + r.status + " " + (await r.text());
}
$("abort").addEventListener("click", () => command("/abort"));
$("start").addEventListener("click", () => command("/start"));

fetch("/info").then((r) => r.json()).then((info) => {
  if (info.images) { $("cams").src = "/stream.mjpg"; }
  else { $("cams").style.display = "none"; $("nocams").style.display = "block"; }
});
const events = new EventSource("/events");
events.onmessage = (e) => show(JSON.parse(e.data));
events.onerror = () => $("b-link").classList.add("on");
</script>
</body>
</html>
)HTML";

}  // namespace

std::string_view operator_page_html() { return kPage; }

}  // namespace rovctl::app
