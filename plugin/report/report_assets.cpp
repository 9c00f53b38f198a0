/// \file report_assets.cpp
/// The hole report's stylesheet and its two inline table scripts (no network, no library).
#include "plugin/report/hole_sections.hpp"

namespace roprec::report {

/// Layout, colours and print rules of the hole report.
const char* const kReportCss = R"CSS(
:root{--fg:#1f2328;--muted:#59636e;--line:#d1d9e0;--soft:#f6f8fa;--accent:#0b5cad}
*{box-sizing:border-box}
html{-webkit-text-size-adjust:100%}
body{margin:0;color:var(--fg);background:#fff;font:14px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,"Helvetica Neue",Arial,"Noto Sans","Liberation Sans",sans-serif;font-variant-numeric:tabular-nums}
main{max-width:1480px;margin:0 auto;padding:24px 32px 40px}
h1{font-size:24px;line-height:1.25;margin:0 0 4px;font-weight:650;letter-spacing:-.01em}
h2{font-size:18px;margin:34px 0 10px;padding-bottom:6px;border-bottom:1px solid var(--line);font-weight:620}
h3{font-size:14px;margin:18px 0 8px;font-weight:620}
p{margin:6px 0 10px}
.sub{color:var(--muted);margin:0 0 16px}
.meta{display:grid;grid-template-columns:repeat(3,minmax(0,1fr));gap:8px 24px;margin:0 0 16px;padding:12px 16px;background:var(--soft);border:1px solid var(--line);border-radius:8px}
.meta div{min-width:0}
.meta dt{font-size:11px;text-transform:uppercase;letter-spacing:.05em;color:var(--muted)}
.meta dd{margin:0;overflow-wrap:anywhere}
.meta .wide{grid-column:1/-1}
.meta .src{color:var(--muted);font-size:12px}
.summary{font-size:15.5px;max-width:1100px;margin:14px 0 16px}
.kpis{display:grid;grid-template-columns:repeat(6,minmax(0,1fr));gap:10px;margin:8px 0 4px}
.kpi{border:1px solid var(--line);border-radius:8px;padding:10px 12px;border-top:4px solid var(--c,#8c959f)}
.kpi b{display:block;font-size:22px;font-weight:650;line-height:1.2}
.kpi span{color:var(--muted);font-size:12px}
.kpi b small{font-size:14px;font-weight:500;color:var(--muted)}
.face{margin:10px 0 6px;color:var(--fg)}
.face small{color:var(--muted);font-weight:400}
.maps{display:grid;grid-template-columns:repeat(3,minmax(0,1fr));gap:14px}
.maps.four{grid-template-columns:repeat(2,minmax(0,1fr))}
.panel{margin:0;border:1px solid var(--line);border-radius:8px;padding:8px 8px 2px;break-inside:avoid}
.panel figcaption{font-weight:600;font-size:13px;padding:0 4px 2px}
.panel svg{display:block;width:100%;height:auto}
.maps.four .panel svg{max-width:600px;margin:0 auto}
svg text{font-family:inherit;font-size:11px;fill:#424a53}
svg .axis{font-size:11.5px;fill:#1f2328}
svg .plot{fill:#fcfcfd;stroke:#afb8c1;stroke-width:1}
svg .grid line{stroke:#eaeef2;stroke-width:1}
svg .path{fill:none;stroke:#afb8c1;stroke-width:.8;stroke-dasharray:3 2}
svg .mk{stroke:#24292f;stroke-width:.7}
svg .chg{fill:none;stroke:#e3120b;stroke-width:1.9}
svg .v-ok{stroke:#24292f;stroke-width:.7}
svg .v-comp{stroke:#b07d00;stroke-width:2.4}
svg .v-nc{stroke:#cf222e;stroke-width:2.8}
svg .v-unr,svg .v-sing,svg .v-nconv{stroke:#57606a;stroke-width:2.4}
svg .bin{stroke-width:0}
svg .bin.v-comp{stroke-width:1.2}
svg .bin.v-nc{stroke-width:1.6}
svg .flabel{font-size:10.5px;font-weight:650;paint-order:stroke;stroke:#fff;stroke-width:3px;stroke-linejoin:round}
svg .f-nc{fill:#a40e26}
svg .f-comp{fill:#7d4e00}
svg .f-unr,svg .f-sing,svg .f-nconv{fill:#424a53}
svg .tol line{stroke:#cf222e;stroke-width:2}
svg .tol text{fill:#a40e26;font-size:10.5px;font-weight:600}
svg .arrow line{stroke:#1f2328;stroke-width:1.5}
svg .arrow polygon{fill:#1f2328}
svg .maxlabel{font-size:11px;font-weight:600;fill:#1f2328;paint-order:stroke;stroke:#fff;stroke-width:3px;stroke-linejoin:round}
svg .barframe{fill:none;stroke:#8c959f;stroke-width:.8}
svg .barTick{stroke:#57606a;stroke-width:1}
.legend{display:flex;flex-wrap:wrap;gap:6px 18px;align-items:center;margin:10px 0 4px;padding:8px 12px;border:1px solid var(--line);border-radius:8px;background:var(--soft);font-size:12.5px}
.legend span{display:inline-flex;align-items:center;gap:4px}
.legend .icon{flex:none}
.note{color:var(--muted);font-size:12.5px}
.two{display:grid;grid-template-columns:minmax(0,1fr) minmax(0,1fr);gap:24px;align-items:start}
.card{border:1px solid var(--line);border-radius:8px;padding:12px 16px}
.card h3{margin-top:0}
.vbars svg{width:100%;height:auto;display:block}
.big{font-size:28px;font-weight:650;line-height:1.15}
.big small{font-size:14px;color:var(--muted);font-weight:400}
.meter{height:12px;border-radius:6px;background:#eaeef2;overflow:hidden;margin:6px 0 12px}
.meter i{display:block;height:100%;background:#2da44e}
table{border-collapse:separate;border-spacing:0;font-size:12.5px}
th,td{padding:4px 8px;text-align:right;white-space:nowrap;border-bottom:1px solid #eaeef2}
th{background:#f0f3f6;font-weight:600;text-align:center;color:#1f2328;vertical-align:bottom}
th small{font-weight:400;color:var(--muted)}
td.l,th.l{text-align:left}
tbody tr:nth-child(even) td{background:#f8fafc}
tbody tr:hover td{background:#eef5ff}
.budget{width:100%}
.budget td,.budget th{padding:5px 10px}
.budget tr.sum td{border-top:1px solid var(--line);background:#fff}
.budget tr.sum td:first-child,.budget tr.sum td.n{font-weight:600}
.sw{display:inline-block;width:10px;height:10px;border-radius:2px;margin-right:6px;vertical-align:-1px}
.share{display:inline-block;height:8px;background:#8fbbe6;border-radius:2px;vertical-align:middle;margin-left:6px}
.stack{display:flex;height:22px;border-radius:5px;overflow:hidden;border:1px solid var(--line);margin:10px 0 4px}
.stack span{display:block;height:100%;overflow:hidden;white-space:nowrap;font-size:11px;line-height:22px;padding-left:5px;color:#fff}
.stack span.lt{color:#1f2328}
.scroll{max-height:78vh;overflow:auto;border:1px solid var(--line);border-radius:8px}
.holes{font-size:12px}
.holes th,.holes td{padding:3px 5px}
.holes th{white-space:normal;line-height:1.25}
.holes thead th{position:sticky;top:0;z-index:2;box-shadow:inset 0 -1px 0 var(--line)}
.holes .c0,.holes .c1{position:sticky;z-index:1;background:#fff}
.holes .c0{left:0;min-width:34px}
.holes .c1{left:34px;box-shadow:inset -1px 0 0 var(--line)}
.holes thead .c0,.holes thead .c1{z-index:3;background:#f0f3f6}
.holes td.id{font-weight:600;text-align:left}
.holes thead th{cursor:pointer;user-select:none}
.holes th[aria-sort=ascending]::after{content:" \25b2"}
.holes th[aria-sort=descending]::after{content:" \25bc"}
.holes.fonly tr.pass{display:none}
.holes td.cfgchg{color:#a40e26;font-weight:600}
.filter{display:inline-block;margin:4px 0 8px;font-size:13px}
.pager{margin:8px 0;font-size:13px}
.holes td.v span{display:inline-block;min-width:3em}
.holes td.j span{display:inline-block;min-width:3.1em}
.holes td.reason{text-align:left;color:#57606a;font-style:italic}
.holes td.why{min-width:14em;max-width:26em;white-space:normal;font-size:12px;color:#57606a}
.holes td.chg b{display:inline-block;min-width:1.7em;border:2px solid #e3120b;border-radius:999px;text-align:center;line-height:1.2}
.badge{display:inline-block;padding:0 7px;border-radius:999px;font-size:11px;font-weight:600;border:1px solid}
.b-ok{color:#116329;background:#dafbe1;border-color:#aceebb}
.b-comp{color:#7d4e00;background:#fff8c5;border-color:#eac54f}
.b-nc{color:#a40e26;background:#ffebe9;border-color:#ffcecb}
.b-unr{color:#424a53;background:#eaeef2;border-color:#d1d9e0}
.b-sing{color:#6639ba;background:#fbefff;border-color:#e6ccff}
.b-nconv{color:#953800;background:#fff1e5;border-color:#ffd8b5}
footer{margin-top:36px;padding-top:12px;border-top:1px solid var(--line);color:var(--muted);font-size:12px}
footer p{margin:4px 0}
@media (max-width:1100px){.maps,.maps.four{grid-template-columns:minmax(0,1fr)}.kpis{grid-template-columns:repeat(3,minmax(0,1fr))}.two,.meta{grid-template-columns:minmax(0,1fr)}}
@media print{@page{size:A4 landscape;margin:10mm}body{font-size:10pt}main{max-width:none;padding:0}.scroll{max-height:none;overflow:visible;border:0}.holes thead th{position:static}table{font-size:8pt}.holes{font-size:6.4pt}th,td,.holes th,.holes td{padding:1px 3px}.holes .c0,.holes .c1{position:static}h2{break-after:avoid}.card,.panel,.kpi{break-inside:avoid}tbody tr:hover td{background:inherit}}
)CSS";

/// Sorting (click a head; again to reverse; numbers numerically, an em dash last) and the
/// "not conforming only" filter. Inline, no network; the page reads fully without it.
const char* const kTableScript = R"JS(
(function(){
var t=document.getElementById('holetable');if(!t)return;
var cb=document.getElementById('failonly');
cb.addEventListener('change',function(){t.classList.toggle('fonly',cb.checked);});
var ths=t.tHead.rows[0].cells,dir={};
function key(r,i,txt){var c=r.cells[i];if(!c)return txt?'':Infinity;var s=c.textContent;
 if(txt)return s;var v=parseFloat(s);return isNaN(v)?Infinity:v;}
for(var i=0;i<ths.length;i++)(function(i){ths[i].addEventListener('click',function(){
 var txt=ths[i].getAttribute('data-t')==='1',b=t.tBodies[0],rows=Array.prototype.slice.call(b.rows);
 var d=dir[i]=-(dir[i]||-1);
 var k=rows.map(function(r,n){return [key(r,i,txt),n,r];});
 k.sort(function(a,c){if(a[0]<c[0])return -d;if(a[0]>c[0])return d;return a[1]-c[1];});
 var f=document.createDocumentFragment();k.forEach(function(x){f.appendChild(x[2]);});b.appendChild(f);
 for(var j=0;j<ths.length;j++)ths[j].removeAttribute('aria-sort');
 ths[i].setAttribute('aria-sort',d>0?'ascending':'descending');});})(i);
})();
)JS";

/// Large jobs: the rows live in ROPREC_ROWS (one "<tr>…</tr>" string each); the DOM holds one
/// page. Sorting (by the clicked column's text, numbers numerically) and the filter act on all.
const char* const kPagedTableScript = R"JS(
(function(){
var R=window.ROPREC_ROWS,t=document.getElementById('holetable');if(!t||!R)return;
var b=t.tBodies[0],cb=document.getElementById('failonly'),pg=document.getElementById('pager');
var P=200,page=0,order=R.map(function(_,i){return i;}),dir={},keys={};
function cell(s,i){var p=s.split('\x1f')[i]||'';if(i>0)p=p.slice(p.indexOf('>')+1);return p.replace(/<[^>]*>/g,'');}
function rows(){return cb.checked?order.filter(function(i){return R[i].lastIndexOf('<tr class="pass"',0)!==0;}):order;}
function draw(){var r=rows(),n=Math.max(1,Math.ceil(r.length/P));if(page>=n)page=n-1;if(page<0)page=0;
 b.innerHTML=r.slice(page*P,page*P+P).map(function(i){return R[i].split('\x1f').join('</td><td');}).join('');
 pg.querySelector('span').textContent='rows '+(r.length?page*P+1:0)+'\u2013'+Math.min(r.length,page*P+P)+' of '+r.length;}
pg.querySelector('.prev').addEventListener('click',function(){page--;draw();});
pg.querySelector('.next').addEventListener('click',function(){page++;draw();});
cb.addEventListener('change',function(){page=0;draw();});
var ths=t.tHead.rows[0].cells;
for(var i=0;i<ths.length;i++)(function(i){ths[i].addEventListener('click',function(){
 var txt=ths[i].getAttribute('data-t')==='1';
 if(!keys[i])keys[i]=R.map(function(s){var c=cell(s,i);if(txt)return c;var v=parseFloat(c);return isNaN(v)?Infinity:v;});
 var k=keys[i],d=dir[i]=-(dir[i]||-1);
 order=R.map(function(_,n){return n;});
 order.sort(function(a,c){if(k[a]<k[c])return -d;if(k[a]>k[c])return d;return a-c;});
 for(var j=0;j<ths.length;j++)ths[j].removeAttribute('aria-sort');
 ths[i].setAttribute('aria-sort',d>0?'ascending':'descending');page=0;draw();});})(i);
draw();
})();
)JS";

}  // namespace roprec::report
