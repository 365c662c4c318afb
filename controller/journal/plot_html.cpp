#include "journal/plot_html.hpp"

#include "journal/plot_model.hpp"
#include "schema/plot_data.hpp"

namespace cellctl::journal {
namespace {

// The page. Kept free of any URL: the whole file must open offline (a test checks it).
constexpr const char* kPage = R"HTML(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>cellctl run plot</title>
<style>
body{font-family:sans-serif;margin:12px;color:#222}
h1{font-size:16px;margin:0 0 4px}
.sub{font-size:12px;color:#555}
.panel{position:relative;margin-top:8px}
.ptitle{font-size:13px;font-weight:bold}
canvas{display:block;cursor:crosshair}
.legend{font-size:12px;margin:2px 0 0 80px}
.legend label{margin-right:14px;white-space:nowrap}
#tip{position:fixed;pointer-events:none;background:#fffffe;border:1px solid #999;padding:6px 8px;font-size:12px;
     display:none;box-shadow:2px 2px 6px #0003;white-space:pre;font-family:monospace}
#marks{font-size:12px;margin-top:10px}
.help{font-size:12px;color:#555;margin-top:4px}
</style></head><body>
<h1 id="title"></h1><div id="subs"></div>
<div class="help">Wheel: zoom time · drag: zoom to a span · shift-drag: pan · double-click: whole run · click a legend entry to hide it</div>
<div id="panels"></div><div id="marks"></div><div id="tip"></div>
<script id="data" type="application/json">@DATA@</script>
<script>
"use strict";
const M = JSON.parse(document.getElementById("data").textContent);
const G = M.geometry, L = 80, R = 20, H = [300, 150, 190];
// The marks' numbers, then the step labels' lanes, above the first panel (laid out by the model).
const MARKROW = G.mark_px * G.mark_levels + 8, STEPBAND = MARKROW + 8 + G.lane_px * G.lanes + 10;
let view = [M.t_lo, M.t_hi];
const hidden = new Set();
document.getElementById("title").textContent = M.title;
for (const s of M.subtitle) { const d = document.createElement("div"); d.className = "sub"; d.textContent = s; document.getElementById("subs").appendChild(d); }

function niceScale(lo, hi, n) {
  if (!(lo <= hi) || !isFinite(lo) || !isFinite(hi)) { lo = 0; hi = 1; }
  if (hi - lo < 1e-9) { lo -= 0.5; hi += 0.5; }
  const rough = (hi - lo) / Math.max(1, n - 1), p = Math.pow(10, Math.floor(Math.log10(rough)));
  let step = 10 * p;
  for (const m of [1, 2, 5, 10]) if (m * p >= rough) { step = m * p; break; }
  const s = { lo: Math.floor(lo / step + 1e-9) * step, hi: Math.ceil(hi / step - 1e-9) * step, step, ticks: [] };
  for (let i = 0; s.lo + i * step <= s.hi + step * 1e-6; ++i) { const v = s.lo + i * step; s.ticks.push(Math.abs(v) < step * 1e-6 ? 0 : v); }
  s.dec = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
  return s;
}
function lowerBound(a, t) { let lo = 0, hi = a.length; while (lo < hi) { const m = (lo + hi) >> 1; if (a[m] < t) lo = m + 1; else hi = m; } return lo; }

const panels = M.panels.map((p, i) => {
  const div = document.createElement("div"); div.className = "panel";
  const title = document.createElement("div"); title.className = "ptitle"; title.textContent = p.title;
  const c = document.createElement("canvas");
  const legend = document.createElement("div"); legend.className = "legend";
  p.series.forEach((s, k) => {
    const lab = document.createElement("label"); const box = document.createElement("input");
    box.type = "checkbox"; box.checked = true; const key = i + "/" + k;
    box.onchange = () => { if (box.checked) hidden.delete(key); else hidden.add(key); draw(); };
    const sw = document.createElement("span"); sw.textContent = s.dash ? " ┄┄ " : " ━━ "; sw.style.color = s.colour;
    lab.append(box, sw, document.createTextNode(s.name)); legend.appendChild(lab);
  });
  div.append(title, c, legend); document.getElementById("panels").appendChild(div);
  return { p, c, i, h: H[i % 3] + (i === 0 ? STEPBAND : 6), top: i === 0 ? STEPBAND : 6 };
});

function xOf(P, t) { return L + (t - view[0]) / (view[1] - view[0]) * (P.c.width - L - R); }
function tOf(P, x) { return view[0] + (x - L) / (P.c.width - L - R) * (view[1] - view[0]); }

function draw() {
  const width = Math.max(L + G.plot_px + R, document.body.clientWidth - 10);
  const ts = niceScale(view[0], view[1], 14);
  for (const P of panels) {
    const c = P.c; c.width = width; c.height = P.h + 34; const g = c.getContext("2d");
    g.clearRect(0, 0, c.width, c.height); g.font = "11px sans-serif";
    let lo = Infinity, hi = -Infinity;
    P.p.series.forEach((s, k) => {
      if (hidden.has(P.i + "/" + k)) return;
      const T = M.times[s.t], a = lowerBound(T, view[0]), b = lowerBound(T, view[1]);
      for (let j = Math.max(0, a - 1); j < Math.min(T.length, b + 1); ++j) { const v = s.v[j]; if (v !== null) { lo = Math.min(lo, v); hi = Math.max(hi, v); } }
    });
    if (lo > hi) { lo = -1; hi = 1; }
    if (lo === 0 && hi === 0) hi = 1;
    const ys = niceScale(lo, hi, 6); P.ys = ys;
    const top = P.top, bottom = P.h, yOf = v => bottom - (v - ys.lo) / (ys.hi - ys.lo) * (bottom - top);
    P.yOf = yOf;
    g.strokeStyle = "#eee"; g.fillStyle = "#222"; g.textAlign = "right";
    for (const v of ys.ticks) { g.beginPath(); g.moveTo(L, yOf(v)); g.lineTo(c.width - R, yOf(v)); g.strokeStyle = v === 0 ? "#bbb" : "#eee"; g.stroke(); g.fillText(v.toFixed(ys.dec), L - 5, yOf(v) + 4); }
    g.save(); g.translate(14, (top + bottom) / 2); g.rotate(-Math.PI / 2); g.textAlign = "center"; g.font = "12px sans-serif"; g.fillText(P.p.axis, 0, 0); g.restore();
    g.textAlign = "center"; g.fillText("time [s]", L + (c.width - L - R) / 2, bottom + 29);
    for (const t of ts.ticks) { if (t < view[0] || t > view[1]) continue; const x = xOf(P, t); g.strokeStyle = "#f2f2f2"; g.beginPath(); g.moveTo(x, top); g.lineTo(x, bottom); g.stroke(); g.fillText(t.toFixed(ts.dec), x, bottom + 14); }
    g.save(); g.beginPath(); g.rect(L, top, c.width - L - R, bottom - top); g.clip();
    g.fillStyle = "rgba(242,181,58,0.18)";
    for (const h of M.holds) { const a = xOf(P, h.from); g.fillRect(a, top, Math.max(1, xOf(P, h.to) - a), bottom - top); }
    g.strokeStyle = "#ccc"; g.lineWidth = 0.8;
    for (const s of M.steps) { const x = xOf(P, s.t); g.beginPath(); g.moveTo(x, top); g.lineTo(x, bottom); g.stroke(); }
    g.lineWidth = 1.4;
    P.p.series.forEach((s, k) => {
      if (hidden.has(P.i + "/" + k)) return;
      const T = M.times[s.t], a = Math.max(0, lowerBound(T, view[0]) - 1), b = Math.min(T.length, lowerBound(T, view[1]) + 1);
      g.strokeStyle = s.colour; g.setLineDash(s.dash ? s.dash.split(",").map(Number) : []); g.beginPath();
      let pen = false;
      for (let j = a; j < b; ++j) { const v = s.v[j]; if (v === null) { pen = false; continue; } const x = xOf(P, T[j]), y = yOf(v); if (pen) g.lineTo(x, y); else g.moveTo(x, y); pen = true; }
      g.stroke();
    });
    g.setLineDash([4, 2]);
    M.marks.forEach(m => { const x = xOf(P, m.t); g.strokeStyle = m.colour; g.beginPath(); g.moveTo(x, top); g.lineTo(x, bottom); g.stroke(); });
    g.restore(); g.setLineDash([]);
    g.strokeStyle = "#888"; g.strokeRect(L, top, c.width - L - R, bottom - top);
    if (P.i === 0) {
      // The marks' lines up to their numbers, under the step labels (which stay readable).
      g.setLineDash([4, 2]); g.lineWidth = 1.2;
      M.marks.forEach(m => { const x = xOf(P, m.t); if (x < L || x > c.width - R) return; g.strokeStyle = m.colour; g.beginPath(); g.moveTo(x, MARKROW + 2); g.lineTo(x, top); g.stroke(); });
      g.setLineDash([]);
      // Every step's label whole, in its lane, where the model placed it relative to its boundary.
      g.textAlign = "left"; g.font = G.font_px + "px sans-serif"; g.lineWidth = 3; g.strokeStyle = "#fff";
      for (const s of M.steps) {
        const x = xOf(P, s.t), x0 = L + (s.t - M.t_lo) / (M.t_hi - M.t_lo) * G.plot_px;
        const left = x + (L + s.box_left - x0), w = s.box_right - s.box_left, base = top - 6 - G.lane_px * s.lane;
        if (left + w < L || left > c.width - R) continue;  // zoomed out of view
        g.strokeStyle = "#c8c8c8"; g.lineWidth = 0.8; g.beginPath(); g.moveTo(x, base - G.font_px + 1); g.lineTo(x, top); g.stroke();
        g.strokeStyle = "#fff"; g.lineWidth = 3; g.strokeText(s.label, left, base, w);
        g.fillStyle = "#444"; g.fillText(s.label, left, base, w);
      }
      M.marks.forEach((m, i) => { const x = xOf(P, m.t); if (x < L || x > c.width - R) return; g.fillStyle = m.colour; g.font = "bold 11px sans-serif"; g.textAlign = "center"; g.fillText(String(i + 1), x, MARKROW - G.mark_px * m.level); });
    }
    if (P.sel) { g.fillStyle = "#0060c022"; g.fillRect(Math.min(P.sel[0], P.sel[1]), top, Math.abs(P.sel[1] - P.sel[0]), bottom - top); }
    if (P.cursor !== undefined) { g.strokeStyle = "#000"; g.lineWidth = 0.7; g.beginPath(); g.moveTo(P.cursor, top); g.lineTo(P.cursor, bottom); g.stroke(); }
  }
}

function valueAt(s, t) {
  const T = M.times[s.t]; if (!T.length) return null;
  let j = lowerBound(T, t); if (j >= T.length) j = T.length - 1; if (j > 0 && t - T[j - 1] < T[j] - t) j -= 1;
  return s.v[j];
}
function tipText(t) {
  const lines = ["t = " + t.toFixed(3) + " s"];
  let step = null; for (const s of M.steps) if (s.t <= t) step = s;
  if (step) lines.push("step " + step.step + ": " + step.full);
  for (const h of M.holds) if (h.from <= t && t <= h.to) lines.push("held " + h.from.toFixed(3) + " s – " + h.to.toFixed(3) + " s");
  for (const P of panels) P.p.series.forEach((s, k) => {
    if (hidden.has(P.i + "/" + k)) return; const v = valueAt(s, t);
    lines.push((s.name + ":").padEnd(26) + (v === null ? "—" : v.toFixed(P.p.unit === "Hz" ? 1 : 3)) + " " + P.p.unit);
  });
  const span = (view[1] - view[0]) / 100;
  M.marks.forEach((m, i) => { if (Math.abs(m.t - t) <= span) lines.push("[" + (i + 1) + "] " + m.kind + ": " + m.text); });
  return lines.join("\n");
}

const tip = document.getElementById("tip");
let drag = null;
for (const P of panels) {
  const c = P.c;
  c.addEventListener("mousemove", e => {
    const x = e.offsetX;
    if (drag && drag.P === P) {
      if (drag.pan) { const dt = tOf(P, drag.x) - tOf(P, x); view = [drag.view[0] + dt, drag.view[1] + dt]; }
      else P.sel = [drag.x, x];
    }
    for (const Q of panels) Q.cursor = x >= L && x <= c.width - R ? x : undefined;
    draw();
    if (x < L || x > c.width - R) { tip.style.display = "none"; return; }
    tip.textContent = tipText(tOf(P, x)); tip.style.display = "block";
    const w = tip.offsetWidth; tip.style.left = (e.clientX + 16 + w > window.innerWidth ? e.clientX - w - 16 : e.clientX + 16) + "px";
    tip.style.top = Math.min(e.clientY + 12, window.innerHeight - tip.offsetHeight - 4) + "px";
  });
  c.addEventListener("mouseleave", () => { tip.style.display = "none"; for (const Q of panels) Q.cursor = undefined; draw(); });
  c.addEventListener("mousedown", e => { drag = { P, x: e.offsetX, pan: e.shiftKey, view: view.slice() }; });
  c.addEventListener("mouseup", e => {
    if (drag && !drag.pan && Math.abs(e.offsetX - drag.x) > 4) { const a = tOf(P, drag.x), b = tOf(P, e.offsetX); view = [Math.min(a, b), Math.max(a, b)]; }
    drag = null; P.sel = undefined; draw();
  });
  c.addEventListener("dblclick", () => { view = [M.t_lo, M.t_hi]; draw(); });
  c.addEventListener("wheel", e => {
    e.preventDefault(); const t = tOf(P, e.offsetX), k = e.deltaY > 0 ? 1.25 : 0.8;
    view = [t - (t - view[0]) * k, t + (view[1] - t) * k]; draw();
  }, { passive: false });
}
const ml = document.getElementById("marks");
if (!M.marks.length && !M.holds.length) ml.textContent = "No faults, no operator commands, no holds.";
M.marks.forEach((m, i) => {
  const d = document.createElement("div"); d.style.color = m.colour; d.style.cursor = "pointer";
  d.textContent = (i + 1) + "  " + m.t.toFixed(3) + " s  " + m.kind + ": " + m.text;
  d.onclick = () => { const w = (view[1] - view[0]) / 2; view = [m.t - w, m.t + w]; draw(); };
  ml.appendChild(d);
});
M.holds.forEach(h => {
  const d = document.createElement("div"); d.style.color = "#a06c00";
  d.textContent = "held " + h.from.toFixed(3) + " s – " + h.to.toFixed(3) + " s (" + (h.to - h.from).toFixed(3) + " s)";
  ml.appendChild(d);
});
window.addEventListener("resize", draw);
draw();
</script></body></html>
)HTML";

}  // namespace

std::string render_html(const std::vector<const RunRecord*>& runs) {
  const std::string data = schema::plot_data_json(plot_model(runs));
  std::string page = kPage;
  page.replace(page.find("@DATA@"), 6, data);
  return page;
}

}  // namespace cellctl::journal
