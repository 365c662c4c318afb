#include "web/page_html.hpp"

namespace cellctl::web {

// The token is typed once, sent once (POST /login) and cleared: the page keeps no secret, the browser
// keeps the HttpOnly session cookie that /events, /cmd, /recipes and /runs accept. Everything shown
// is set as text (never as markup): names and words from the cell are no code.
std::string_view operator_page_script() noexcept {
  return R"JS('use strict';
const $=id=>document.getElementById(id);
const SVG='http://www.w3.org/2000/svg';
function el(tag,attrs,text){const e=tag.startsWith('svg:')?document.createElementNS(SVG,tag.slice(4)):document.createElement(tag);
 for(const k in attrs||{})e.setAttribute(k,attrs[k]);if(text!==undefined)e.textContent=text;return e;}
function row(cells){const r=el('tr');for(const c of cells)r.appendChild(c instanceof Node?el('td').appendChild(c).parentNode:el('td',{},c));return r;}
function fill(id,rows){const b=$(id);b.textContent='';for(const r of rows)b.appendChild(r);}
const mm=v=>typeof v==='number'?v.toFixed(3):'—';
const yes=v=>v===undefined?'—':v?'yes':'no';

// The trend: each axis's SCU position and, where it measures one, the encoder's, over the last 60 s
// of the run's clock, with a time axis, a position axis and a legend naming each line.
const hist=[];const colors=['#05a','#a50','#090','#909','#099','#990','#555','#c33'];
function niceStep(span,n){const raw=span/n,p=Math.pow(10,Math.floor(Math.log10(raw)));
 for(const m of [1,2,5,10])if(raw<=m*p)return m*p;return 10*p;}
function draw(){const s=$('trend');s.textContent='';
 if(hist.length<2){s.appendChild(el('svg:text',{class:'empty',x:450,y:130,'text-anchor':'middle'},'no samples: the trend shows the job in progress'));return;}
 const W=900,H=260,L=70,R=170,T=10,B=45;const t0=hist[0].t,t1=Math.max(hist[hist.length-1].t,t0+1);
 const names=[...new Set(hist.flatMap(h=>Object.keys(h.v)))];let lo=Infinity,hi=-Infinity;
 for(const h of hist)for(const k in h.v){lo=Math.min(lo,h.v[k]);hi=Math.max(hi,h.v[k]);}
 if(hi-lo<1){hi+=.5;lo-=.5;}const X=t=>L+(t-t0)/(t1-t0)*(W-L-R),Y=v=>H-B-(v-lo)/(hi-lo)*(H-T-B);
 const tx=niceStep(t1-t0,6),ty=niceStep(hi-lo,4);
 for(let t=Math.ceil(t0/tx)*tx;t<=t1;t+=tx){s.appendChild(el('svg:line',{class:'grid-line',x1:X(t),x2:X(t),y1:T,y2:H-B}));
  s.appendChild(el('svg:text',{class:'x-tick',x:X(t),y:H-B+16,'text-anchor':'middle'},t.toFixed(tx<1?1:0)));}
 for(let v=Math.ceil(lo/ty)*ty;v<=hi;v+=ty){s.appendChild(el('svg:line',{class:'grid-line',x1:L,x2:W-R,y1:Y(v),y2:Y(v)}));
  s.appendChild(el('svg:text',{class:'y-tick',x:L-6,y:Y(v)+4,'text-anchor':'end'},v.toFixed(ty<1?1:0)));}
 s.appendChild(el('svg:rect',{class:'frame',x:L,y:T,width:W-L-R,height:H-T-B}));
 s.appendChild(el('svg:text',{class:'x-title',x:L+(W-L-R)/2,y:H-6,'text-anchor':'middle'},'run time (s)'));
 s.appendChild(el('svg:text',{class:'y-title',x:14,y:T+(H-T-B)/2,'text-anchor':'middle',
  transform:'rotate(-90 14 '+(T+(H-T-B)/2)+')'},'position (mm)'));
 names.forEach((n,i)=>{const c=colors[i%colors.length];let d='';
  for(const h of hist)if(n in h.v)d+=(d?'L':'M')+X(h.t).toFixed(1)+' '+Y(h.v[n]).toFixed(1);
  s.appendChild(el('svg:path',{d,stroke:c,fill:'none','stroke-width':2,'stroke-dasharray':n.endsWith('encoder')?'5 3':'none'}));
  const y=T+14+i*18;s.appendChild(el('svg:line',{x1:W-R+12,x2:W-R+36,y1:y-4,y2:y-4,stroke:c,'stroke-width':2}));
  s.appendChild(el('svg:text',{class:'legend-entry',x:W-R+42,y},n+' (mm)'));});}
function trend(b){if(typeof b.t!=='number'||!b.live)return;const v={};
 for(const a of b.axes){if(typeof a.scu_mm==='number')v[a.name+' SCU']=a.scu_mm;
  if(typeof a.encoder_mm==='number')v[a.name+' encoder']=a.encoder_mm;}
 if(hist.length&&b.t<hist[hist.length-1].t)hist.length=0;  // a new job's clock starts again at 0
 if(!Object.keys(v).length)return;hist.push({t:b.t,v});while(hist[0].t<b.t-60)hist.shift();draw();}

// Per device: the safe state the newest run record left it in (cellctl serve), unless the board
// carries the live run's own verdict (its stop has resolved the device: cellctl run too).
let lastSafe={};
function board(b){
 fill('axes',b.axes.map(a=>row([a.name,mm(a.target_mm),mm(a.scu_mm),mm(a.encoder_mm),
  yes(a.homed&&a.homed.record),yes(a.homed&&a.homed.scu)])));
 fill('devices',b.devices.map(d=>{const link=b.live?el('span',{class:d.link==='up'?'good':'bad'},d.link):el('span',{},'closed: no job');
  const safe=d.safe?{safe:d.safe,evidence:'as this run\'s stop resolved it'}:lastSafe[d.name];const sf=el('span',{class:safe&&safe.safe==='unknown'?'bad':''},safe?safe.safe:'—');
  if(safe)sf.title=safe.evidence;
  return row([d.name,link,d.round_trip_ms.toFixed(1),d.last_good_s.toFixed(3),String(d.replies),
   d.timeouts+' / '+d.bad_frames+' / '+d.refusals,sf]);}));
 if(b.spindle){$('sset').textContent=b.spindle.set_hz.toFixed(0);$('sact').textContent=b.spindle.actual_hz.toFixed(0);}
 $('board-age').textContent=b.live?'':b.read_at_start?'(as read when cellctl serve started: no job yet; each job opens the links)'
  :'(as the last job left them: no job in progress; each job opens the links)';
 for(const [cmd,s] of Object.entries(b.buttons||{})){const btn=$(cmd);if(!btn)continue;
  btn.disabled=!s.enabled;btn.title=s.reason||'';const why=$('why-'+cmd);if(why)why.textContent=s.reason||'';}
 $('packml').textContent='PackML StateCurrent '+b.state_current;
 if(b.state!==lastState){lastState=b.state;if(/Complete|Stopped|Aborted|Idle/.test(b.state))loadRuns();}
 trend(b);}
let lastState='';
function status(s){$('state').textContent=s.state;$('state').className=s.state;$('step').textContent=s.step;
 $('steps').textContent=s.steps;$('label').textContent=s.label||'';$('progress').value=s.progress||0;
 $('t').textContent=(s.t||0).toFixed(1);$('jitter').textContent=(s.jitter_max_us||0).toFixed(0);}
// Faults (the safety monitor's, each with its remedy) apart from what held or stopped the cell on
// purpose (a command, a state's reason, a failed step): the latter is listed under its own heading,
// the last ten seen by this page, newest first.
const stops=[];
function admin(a){fill('faults',(a.active_faults||[]).map(f=>{const li=el('li',{},f.rule+' (stop category '+f.category+'): '+f.text);
  li.appendChild(el('div',{class:'remedy'},'Remedy: '+(f.remedy||'')));return li;}));
 const r=a.StopReason;
 if(r&&r.text&&!r.fault&&!stops.some(x=>x.t===r.t&&x.text===r.text)){stops.unshift(r);stops.length=Math.min(stops.length,10);}
 fill('stops',stops.length?stops.map(x=>el('li',{},x.text+' (at '+Number(x.t||0).toFixed(1)+' s)')):[el('li',{class:'none'},'none')]);
 if(!(a.active_faults||[]).length)fill('faults',[el('li',{class:'good'},'none')]);}
function say(what,a){$('answer').textContent=what+': '+(a.ok?a.outcome:a.reason);$('answer').className=a.ok?'accepted':'refused';}
function loggedIn(yes){$('login').hidden=yes;$('logout').hidden=!yes;if(yes)$('logout').focus();else $('token').focus();}
async function getJson(path){const r=await fetch(path);if(!r.ok)throw new Error(path+': '+r.status);return r.json();}
async function loadRecipes(){try{const l=await getJson('recipes');const sel=$('recipe'),keep=sel.value;sel.textContent='';
 for(const r of l.recipes){const o=el('option',{value:r.name},r.problem?r.name+' — not valid: '+r.problem
  :r.name+' — '+r.steps+' steps'+(typeof r.planned_s==='number'?', planned '+r.planned_s+' s':'')
  +(r.not_counted?' and '+r.not_counted+' step'+(r.not_counted>1?'s':'')+' only the run can time':''));o.disabled=!!r.problem;sel.appendChild(o);}
 if(keep)sel.value=keep;}catch(e){say('recipes',{reason:String(e)});}}
async function loadRuns(){try{const l=await getJson('runs');lastSafe={};
 if(l.runs.length&&l.runs[0].devices)for(const d of l.runs[0].devices)lastSafe[d.name]=d;
 fill('runs',l.runs.map(r=>{const link=(f,t)=>el('a',{href:'runs/'+encodeURIComponent(r.run)+'/'+f,target:'_blank',rel:'noopener'},t);
  return row([r.run,r.recipe||'—',r.outcome||'unfinished',typeof r.duration_s==='number'?r.duration_s.toFixed(1):'—',
   r.plot?link('plot.html','plot'):'—',link('report','report')]);}));
 $('runs-note').textContent=l.runs.length?(l.more?'(the newest '+l.runs.length+')':''):'no run records here';}catch(e){say('runs',{reason:String(e)});}}
// A stream refused (no session: 401; every stream taken: 503) is closed for good by the browser.
let es=null;
function live(){if(es)es.close();es=new EventSource('events');
 es.onopen=()=>{$('conn').textContent='live';loggedIn(true);loadRecipes();loadRuns();};
 es.onerror=()=>{if(es.readyState===EventSource.CLOSED){$('conn').textContent='not live: log in with the token (or every live view is taken)';loggedIn(false);}
  else $('conn').textContent='connection lost — retrying';};
 es.addEventListener('status',e=>status(JSON.parse(e.data)));
 es.addEventListener('board',e=>board(JSON.parse(e.data)));
 es.addEventListener('admin',e=>admin(JSON.parse(e.data)));
 es.addEventListener('mode',e=>{const m=JSON.parse(e.data);$('mode').textContent=m.mode+' (UnitModeCurrent '+m.UnitModeCurrent+')';$('recipe-now').textContent=m.recipe?'— '+m.recipe:'';});
 es.addEventListener('cell',e=>{$('cell').textContent=JSON.parse(e.data).cell;});}
async function post(path,headers,body){const r=await fetch(path,{method:'POST',headers,body});return r.json();}
$('login').onsubmit=async e=>{e.preventDefault();const token=$('token').value;$('token').value='';
 try{const a=await post('login',{'X-Cellctl-Token':token});say('login',a);if(a.ok)live();}catch(err){say('login',{reason:String(err)});}};
$('logout').onclick=async()=>{try{say('logout',await post('logout',{}));}catch(err){say('logout',{reason:String(err)});}
 if(es)es.close();$('conn').textContent='logged out';loggedIn(false);};
$('reload').onclick=()=>{loadRecipes();loadRuns();};
// What a command sends, and what its confirmation asks: the routines say what will move.
function ask(cmd){if(cmd==='start'){const r=$('recipe').value;
  return{body:{recipe:r},q:'Start recipe '+r+'? The cell MOVES as the recipe says.'};}
 if(cmd==='home')return{body:{},q:'Home every axis that has homing? The axes MOVE. Keep clear of the cell.'};
 if(cmd==='teach-in'){const b={axis:$('ti-axis').value.trim(),distance_mm:parseFloat($('ti-distance').value)};
  if($('ti-from').value.trim()!=='')b.from_mm=parseFloat($('ti-from').value);
  return{body:b,q:'Teach-In of the encoder on axis '+b.axis+' over '+b.distance_mm+' mm? The axis MOVES, and the verified result is written into the cell config (in a dry run, into its copy of it).'};}
 if(cmd==='abort')return{body:{},q:'abort the cell? Every actuator is stopped at once (emergency stop) and the spindle switched off.'};
 return{body:{},q:cmd+' the cell?'};}
for(const b of document.querySelectorAll('button[data-cmd]'))b.onclick=async()=>{const cmd=b.dataset.cmd;
 const a0=ask(cmd);if(!confirm(a0.q))return;$('answer').textContent=cmd+'…';$('answer').className='';
 try{say(cmd,await post('cmd/'+cmd,{'Content-Type':'application/json'},JSON.stringify(a0.body)));}
 catch(e){say(cmd,{reason:String(e)});}};
draw();
live();
)JS";
}

}  // namespace cellctl::web
