#include "web/page_html.hpp"

namespace cellctl::web {

// The "routines" fieldset starts jobs — a recipe, homing, a Teach-In — through the same CommandDesk
// (plant_link/command_desk.hpp), session and confirmation as the operator's commands; `cellctl serve`
// runs them, `cellctl run` (one run) refuses them with the reason. Each confirmation says what moves.
std::string_view operator_page_html() noexcept {
  return R"HTML(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>cellctl operator</title>
<meta name="viewport" content="width=device-width, initial-scale=1">
<link rel="stylesheet" href="page.css">
</head><body>
<h1>cellctl — <span id="cell">cell</span> <span id="conn">connecting…</span></h1>
<div class="row">
 <div class="box"><div id="state" class="Idle">?</div><div id="mode"></div>
  <div>step <span id="step">0</span> of <span id="steps">0</span>: <span id="label"></span></div>
  <progress id="progress" max="1" value="0"></progress><div>t = <span id="t">0</span> s</div></div>
 <div class="box"><table><thead><tr><th>axis</th><th>planned mm</th><th>measured mm</th></tr></thead>
  <tbody id="axes"></tbody></table>
  <div>spindle set <span id="sset">0</span> Hz, actual <span id="sact">0</span> Hz</div>
  <div>loop jitter max <span id="jitter">0</span> µs</div></div>
 <div class="box"><b>faults</b><ul id="faults"></ul><div>stop reason: <span id="reason">—</span></div></div>
</div>
<div class="box wide">
 <form id="login" hidden><label>token <input id="token" type="password" size="24" autocomplete="off"></label>
  <button id="log-in" type="submit">Log in</button></form>
 <button id="logout" hidden>Log out</button>
 <button id="hold" data-cmd="hold">Hold</button><button id="unhold" data-cmd="unhold">Unhold</button>
 <button id="stop" data-cmd="stop">Stop</button><button id="reset" data-cmd="reset">Reset</button>
 <button id="clear" data-cmd="clear">Clear</button>
 <fieldset id="routines" class="routines">
  <label>recipe <input id="recipe" size="14" value="demo"></label><button id="start" data-cmd="start">Start</button>
  <button id="home" data-cmd="home">Home</button>
  <label>Teach-In axis <input id="ti-axis" size="3" value="x"></label>
  <label>over <input id="ti-distance" size="6" value="100"> mm</label>
  <label>from <input id="ti-from" size="6" placeholder="here"> mm</label>
  <button id="teach-in" data-cmd="teach-in">Teach-In</button></fieldset>
 <div id="answer"></div></div>
<div class="box wide"><canvas id="plot" width="900" height="220"></canvas></div>
<script src="page.js"></script>
</body></html>
)HTML";
}

std::string_view operator_page_style() noexcept {
  return R"CSS(body{font-family:system-ui,sans-serif;margin:1em;background:#f4f4f4;color:#222}
h1{font-size:1.3em;margin:0 0 .5em} .row{display:flex;gap:1em;flex-wrap:wrap}
.box{background:#fff;border:1px solid #ccc;border-radius:6px;padding:.8em;min-width:16em} .wide{margin-top:1em}
#state{font-size:2em;font-weight:bold} .Execute{color:#070}.Held,.Holding{color:#a60}
.Stopped,.Stopping,.Aborted,.Aborting{color:#b00}.Complete{color:#05a}
progress{width:100%} table{border-collapse:collapse} td,th{padding:.2em .6em;text-align:right}
button{font-size:1.1em;padding:.5em 1.2em;margin:.2em} #faults li{color:#b00;margin-bottom:.4em}
.remedy{color:#444;font-size:.9em} #answer{min-height:1.4em} .refused{color:#b00}.accepted{color:#070}
#conn{font-size:.8em;color:#666} .routines{border:none;padding:0} form{display:inline} [hidden]{display:none}
)CSS";
}

// The token is typed once, sent once (POST /login) and cleared: the page keeps no secret, the browser
// keeps the HttpOnly session cookie that /events and /cmd accept.
std::string_view operator_page_script() noexcept {
  return R"JS('use strict';
const $=id=>document.getElementById(id);
const hist=[];const colors=['#05a','#a50','#090','#909','#099','#990'];
function draw(){const c=$('plot'),g=c.getContext('2d');g.clearRect(0,0,c.width,c.height);
 if(hist.length<2)return;const t0=hist[0].t,t1=hist[hist.length-1].t;let lo=1e9,hi=-1e9;
 for(const h of hist)for(const v of h.v){lo=Math.min(lo,v);hi=Math.max(hi,v);}if(hi-lo<1){hi+=.5;lo-=.5;}
 const X=t=>(t-t0)/Math.max(t1-t0,1e-3)*(c.width-40)+35,Y=v=>c.height-10-(v-lo)/(hi-lo)*(c.height-20);
 g.fillStyle='#666';g.fillText(hi.toFixed(1)+' mm',0,12);g.fillText(lo.toFixed(1)+' mm',0,c.height-4);
 const n=hist[hist.length-1].v.length;for(let a=0;a<n;a++){g.strokeStyle=colors[a%6];g.beginPath();
  hist.forEach((h,i)=>{const p=[X(h.t),Y(h.v[a])];i?g.lineTo(...p):g.moveTo(...p);});g.stroke();}}
function status(s){$('state').textContent=s.state;$('state').className=s.state;$('step').textContent=s.step;
 $('steps').textContent=s.steps;$('label').textContent=s.label||'';$('progress').value=s.progress||0;
 $('t').textContent=(s.t||0).toFixed(1);$('jitter').textContent=(s.jitter_max_us||0).toFixed(0);
 if(s.spindle){$('sset').textContent=s.spindle.set_hz.toFixed(0);$('sact').textContent=s.spindle.actual_hz.toFixed(0);}
 $('axes').textContent='';const v=[];for(const a of s.axes){const r=document.createElement('tr');
  for(const x of [a.name,a.planned_mm,a.measured_mm]){const d=document.createElement('td');
   d.textContent=typeof x==='number'?x.toFixed(2):(x??'—');r.appendChild(d);}$('axes').appendChild(r);
  if(typeof a.measured_mm==='number')v.push(a.measured_mm);}
 if(hist.length&&s.t<hist[hist.length-1].t)hist.length=0;  // a new job's clock starts again at 0
 if(v.length){hist.push({t:s.t,v});while(hist.length&&hist[0].t<s.t-60)hist.shift();draw();}}
function admin(a){$('faults').textContent='';for(const f of a.active_faults||[]){const li=document.createElement('li');
  li.textContent=f.rule+' (category '+f.category+'): '+f.text;const r=document.createElement('div');
  r.className='remedy';r.textContent=f.remedy||'';li.appendChild(r);$('faults').appendChild(li);}
 $('reason').textContent=a.StopReason&&a.StopReason.text?a.StopReason.text:'—';}
function say(what,a){$('answer').textContent=what+': '+(a.ok?a.outcome:a.reason);$('answer').className=a.ok?'accepted':'refused';}
function loggedIn(yes){$('login').hidden=yes;$('logout').hidden=!yes;}
// A stream refused (no session: 401; every stream taken: 503) is closed for good by the browser.
let es=null;
function live(){if(es)es.close();es=new EventSource('events');
 es.onopen=()=>{$('conn').textContent='live';loggedIn(true);};
 es.onerror=()=>{if(es.readyState===EventSource.CLOSED){$('conn').textContent='not live: log in with the token (or every live view is taken)';loggedIn(false);}
  else $('conn').textContent='connection lost — retrying';};
 es.addEventListener('status',e=>status(JSON.parse(e.data)));
 es.addEventListener('admin',e=>admin(JSON.parse(e.data)));
 es.addEventListener('mode',e=>{const m=JSON.parse(e.data);$('mode').textContent=m.mode+(m.recipe?' — '+m.recipe:'');});
 es.addEventListener('cell',e=>{$('cell').textContent=JSON.parse(e.data).cell;});}
async function post(path,headers,body){const r=await fetch(path,{method:'POST',headers,body});return r.json();}
$('login').onsubmit=async e=>{e.preventDefault();const token=$('token').value;$('token').value='';
 try{const a=await post('login',{'X-Cellctl-Token':token});say('login',a);if(a.ok)live();}catch(err){say('login',{reason:String(err)});}};
$('logout').onclick=async()=>{try{say('logout',await post('logout',{}));}catch(err){say('logout',{reason:String(err)});}
 if(es)es.close();$('conn').textContent='logged out';loggedIn(false);};
// What a command sends, and what its confirmation asks: the routines say what will move.
function ask(cmd){if(cmd==='start'){const r=$('recipe').value.trim();
  return{body:{recipe:r},q:'Start recipe '+r+'? The cell MOVES as the recipe says.'};}
 if(cmd==='home')return{body:{},q:'Home every axis that has homing? The axes MOVE. Keep clear of the cell.'};
 if(cmd==='teach-in'){const b={axis:$('ti-axis').value.trim(),distance_mm:parseFloat($('ti-distance').value)};
  if($('ti-from').value.trim()!=='')b.from_mm=parseFloat($('ti-from').value);
  return{body:b,q:'Teach-In of the encoder on axis '+b.axis+' over '+b.distance_mm+' mm? The axis MOVES, and the verified result is written into the cell config (in a dry run, into its copy of it).'};}
 return{body:{},q:cmd+' the cell?'};}
for(const b of document.querySelectorAll('button[data-cmd]'))b.onclick=async()=>{const cmd=b.dataset.cmd;
 const a0=ask(cmd);if(!confirm(a0.q))return;$('answer').textContent=cmd+'…';$('answer').className='';
 try{say(cmd,await post('cmd/'+cmd,{'Content-Type':'application/json'},JSON.stringify(a0.body)));}
 catch(e){say(cmd,{reason:String(e)});}};
live();
)JS";
}

}  // namespace cellctl::web
