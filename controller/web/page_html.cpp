#include "web/page_html.hpp"

namespace cellctl::web {

// One document for the panel at the cell (1366×768) and a tablet: boxes in a grid that wraps. Every
// control is a button, a select or an input, reachable by Tab and worked by Enter or Space; each
// command's confirmation says what moves. The "routines" fieldset starts jobs — a recipe from the
// recipes folder, homing, a Teach-In — through the same CommandDesk (plant_link/command_desk.hpp),
// session and confirmation as the operator's commands; `cellctl run` (one run) disables them and says why.
std::string_view operator_page_html() noexcept {
  return R"HTML(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>cellctl operator</title>
<meta name="viewport" content="width=device-width, initial-scale=1">
<link rel="stylesheet" href="page.css">
</head><body>
<header><h1>cellctl — <span id="cell">cell</span></h1><span id="conn">connecting…</span>
 <form id="login" hidden><label>token <input id="token" type="password" size="24" autocomplete="off"></label>
  <button id="log-in" type="submit">Log in</button></form>
 <button id="logout" hidden>Log out</button></header>
<main class="grid">
<section class="box" aria-label="state"><div id="state" class="Idle">?</div><small id="packml"></small>
 <div>mode <b id="mode">—</b> <span id="recipe-now"></span></div>
 <div>step <span id="step">0</span> of <span id="steps">0</span>: <span id="label"></span></div>
 <progress id="progress" max="1" value="0"></progress>
 <div>run time <span id="t">0</span> s · loop jitter max <span id="jitter">0</span> µs</div>
 <div>spindle set <span id="sset">0</span> Hz, actual <span id="sact">0</span> Hz</div></section>
<section class="box" aria-label="commands"><h2>Commands</h2><div class="cmds">
 <div><button id="hold" data-cmd="hold">Hold</button><small id="why-hold"></small></div>
 <div><button id="unhold" data-cmd="unhold">Unhold</button><small id="why-unhold"></small></div>
 <div><button id="stop" data-cmd="stop">Stop</button><small id="why-stop"></small></div>
 <div><button id="abort" data-cmd="abort">Abort</button><small id="why-abort"></small></div>
 <div><button id="reset" data-cmd="reset">Reset</button><small id="why-reset"></small></div>
 <div><button id="clear" data-cmd="clear">Clear</button><small id="why-clear"></small></div></div>
 <div id="answer" role="status"></div></section>
<section class="box" aria-label="faults"><h2>Faults</h2><ul id="faults"></ul>
 <h2>Holds, stops and commands</h2><ul id="stops"></ul></section>
<section class="box wide" aria-label="axes"><h2>Axes <small id="board-age"></small></h2><table><thead><tr>
 <th>axis</th><th>target (mm)</th><th>SCU position (mm)</th><th>encoder position (mm)</th>
 <th>homed: record</th><th>homed: SCU bit</th></tr></thead><tbody id="axes"></tbody></table></section>
<section class="box wide" aria-label="devices"><h2>Devices</h2><table><thead><tr>
 <th>device</th><th>link</th><th>round trip (ms)</th><th>last good reply (s ago)</th><th>replies</th>
 <th>errors: time-outs / bad frames / refused</th><th>safe state after the last stop</th></tr></thead>
 <tbody id="devices"></tbody></table></section>
<section class="box wide" aria-label="trend"><h2>Trend</h2>
 <svg id="trend" viewBox="0 0 900 260" role="img" aria-label="positions over time"></svg></section>
<section class="box wide" aria-label="jobs"><h2>Jobs</h2><fieldset id="routines" class="routines">
 <div><label>recipe <select id="recipe"></select></label><button id="start" data-cmd="start">Start</button>
  <button id="reload" type="button">Reload lists</button><small id="why-start"></small></div>
 <div><button id="home" data-cmd="home">Home</button><small id="why-home"></small></div>
 <div><label>Teach-In axis <input id="ti-axis" size="3" value="x"></label>
  <label>over <input id="ti-distance" size="6" value="100"> mm</label>
  <label>from <input id="ti-from" size="6" placeholder="here"> mm</label>
  <button id="teach-in" data-cmd="teach-in">Teach-In</button><small id="why-teach-in"></small></div></fieldset></section>
<section class="box wide" aria-label="runs"><h2>Run history</h2><table><thead><tr><th>run</th><th>recipe</th>
 <th>outcome</th><th>duration (s)</th><th>plot</th><th>report</th></tr></thead><tbody id="runs"></tbody></table>
 <div id="runs-note"></div></section>
</main>
<script src="page.js"></script>
</body></html>
)HTML";
}

std::string_view operator_page_style() noexcept {
  return R"CSS(body{font-family:system-ui,sans-serif;margin:.6em;background:#f4f4f4;color:#222;font-size:15px}
header{display:flex;gap:1em;align-items:center;flex-wrap:wrap} h1{font-size:1.3em;margin:0}
h2{font-size:1em;margin:.2em 0 .4em} #conn{font-size:.85em;color:#555}
.grid{display:grid;grid-template-columns:repeat(auto-fit,minmax(24em,1fr));gap:.6em;margin-top:.5em}
.box{background:#fff;border:1px solid #ccc;border-radius:6px;padding:.6em;min-width:0;overflow-x:auto}
.wide{grid-column:1/-1} #state{font-size:2em;font-weight:bold}
.Execute{color:#070}.Held,.Holding{color:#a60}.Stopped,.Stopping,.Aborted,.Aborting{color:#b00}.Complete{color:#05a}
progress{width:100%} table{border-collapse:collapse} td,th{padding:.15em .6em;text-align:right}
th{font-weight:600;font-size:.9em} td:first-child,th:first-child{text-align:left}
select{max-width:100%} button{font-size:1.05em;padding:.45em 1.1em;margin:.15em} button:disabled{opacity:.45}
:focus-visible{outline:3px solid #05a;outline-offset:2px}
.cmds{display:grid;grid-template-columns:repeat(auto-fill,minmax(12em,1fr));gap:.2em}
.cmds div,.routines div{display:flex;align-items:center;gap:.4em;flex-wrap:wrap} small{color:#666}
#faults li{color:#b00;margin-bottom:.4em} #faults li.good{color:#070} #stops li{color:#a60} #stops li.none{color:#666} .remedy{color:#444;font-size:.9em}
#answer{min-height:1.4em} .refused{color:#b00}.accepted{color:#070} .routines{border:none;padding:0;margin:0}
form{display:inline} [hidden]{display:none} .bad{color:#b00;font-weight:bold} .good{color:#070}
#trend{width:100%;height:auto;max-height:280px} #trend text{font-size:12px;fill:#333}
#trend .grid-line{stroke:#ddd} #trend .empty{fill:#666} #trend .frame{stroke:#888;fill:none}
@media (max-width:800px){body{font-size:14px} td,th{padding:.1em .3em}}
)CSS";
}

}  // namespace cellctl::web
