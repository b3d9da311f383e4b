#include "http/dashboard_page.hpp"

namespace railvsi::scheduler {

std::string_view dashboard_html() {
  static constexpr std::string_view kPage = R"html(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>railvsi studies</title>
<style>
body{font:15px/1.4 system-ui,sans-serif;margin:0;background:#f4f5f7;color:#1d2330}
header{background:#1d3557;color:#fff;padding:12px 20px}
header h1{font-size:20px;margin:0}
main{max-width:1200px;margin:0 auto;padding:16px}
section{background:#fff;border-radius:8px;box-shadow:0 1px 3px #0002;padding:14px;margin-bottom:16px}
h2{font-size:17px;margin:0 0 10px}
table{width:100%;border-collapse:collapse}
th,td{text-align:left;padding:8px 6px;border-bottom:1px solid #e3e6ea;vertical-align:middle}
th{font-size:13px;color:#5a6372}
.bar{background:#e3e6ea;border-radius:5px;height:14px;min-width:120px;overflow:hidden;display:flex}
.bar span{display:block;height:100%}
.done{background:#2a9d8f}.failed{background:#e63946}.running{background:#f4a261}.cancelled{background:#9aa1ab}
.verdict{font-weight:600;padding:2px 8px;border-radius:4px;white-space:nowrap}
.PASS{background:#d8f3dc;color:#1b4332}.FAIL{background:#ffd6d9;color:#8d0801}
.INCOMPLETE,.NOT{background:#fff1c1;color:#7a5800}
.links a{margin-right:10px;white-space:nowrap}
.small{font-size:12px;color:#5a6372}
form{display:flex;flex-wrap:wrap;gap:10px;align-items:center}
#msg{white-space:pre-wrap}.err{color:#b00020}
@media (max-width:700px){
 thead{display:none} table,tbody,tr,td{display:block;width:auto} tr{border-bottom:2px solid #e3e6ea;padding:6px 0}
 td{border:0;padding:3px 2px;display:flex;gap:8px;align-items:center}
 td[data-label]::before{content:attr(data-label);flex:0 0 64px;font-weight:600;color:#5a6372;font-size:13px}
 td>*{flex:1} td>.verdict{flex:0 0 auto} td[data-label="Study"]::before{content:none} td[data-label="Study"]{font-weight:600}
}
</style></head><body>
<header><h1>railvsi &mdash; studies</h1></header>
<main>
<section><h2>Submit a study</h2>
<form id="submit"><input type="file" id="file" accept=".json,application/json">
<button type="submit">Submit</button>
<label class="small">Token <input type="password" id="token" size="12" autocomplete="off"></label></form>
<div id="msg" class="small"></div></section>
<section><h2>Studies</h2>
<table><thead><tr><th>Study</th><th>Progress</th><th>Jobs</th><th>ETA</th><th>Verdict</th><th>Results</th></tr></thead>
<tbody id="studies"><tr><td colspan="6" class="small">loading&hellip;</td></tr></tbody></table>
<div class="small" id="updated"></div></section>
</main>
<script>
"use strict";
const tokenBox = document.getElementById("token");
tokenBox.value = localStorage.getItem("vsiToken") || "";
tokenBox.addEventListener("change", () => { localStorage.setItem("vsiToken", tokenBox.value); refresh(); });
function headers() { return tokenBox.value ? {"Authorization": "Bearer " + tokenBox.value} : {}; }
function text(tag, value, cls) { const e = document.createElement(tag); e.textContent = value; if (cls) e.className = cls; return e; }
function duration(s) {
  if (s === null || s === undefined) return "\u2014";
  s = Math.round(s); if (s < 60) return s + " s";
  const m = Math.floor(s / 60); if (m < 60) return m + " min " + (s % 60) + " s";
  return Math.floor(m / 60) + " h " + (m % 60) + " min";
}
function cell(row, label, child) { const td = document.createElement("td"); td.dataset.label = label; td.append(child); row.append(td); return td; }
// A link to the API: with a token, fetched with its header and opened as a blob.
function apiLink(label, url) {
  const a = text("a", label); a.href = url;
  a.addEventListener("click", async ev => {
    if (!tokenBox.value) return;
    ev.preventDefault();
    const r = await fetch(url, {headers: headers()});
    window.open(URL.createObjectURL(await r.blob()), "_blank");
  });
  return a;
}
function studyRow(s) {
  const j = s.jobs, row = document.createElement("tr"); row.dataset.study = s.id;
  const name = document.createElement("div"); name.append(text("div", s.name || "(unnamed)"), text("div", s.id.slice(0, 12), "small"));
  cell(row, "Study", name);
  const bar = document.createElement("div"); bar.className = "bar"; bar.setAttribute("role", "progressbar");
  const finished = j.done + j.failed + j.cancelled;
  bar.setAttribute("aria-valuenow", finished); bar.setAttribute("aria-valuemax", j.total);
  for (const k of ["done", "failed", "cancelled", "running"]) {
    const part = document.createElement("span"); part.className = k;
    part.style.width = (j.total ? 100 * j[k] / j.total : 0) + "%"; bar.append(part);
  }
  const progress = document.createElement("div"); progress.append(bar, text("div", (j.total ? Math.floor(100 * finished / j.total) : 0) + " %", "small progress"));
  cell(row, "Progress", progress);
  cell(row, "Jobs", text("span", j.done + "/" + j.total + " done" + (j.running ? ", " + j.running + " running" : "") +
    (j.failed ? ", " + j.failed + " failed" : "") + (j.cancelled ? ", " + j.cancelled + " cancelled" : "")));
  cell(row, "ETA", text("span", j.queued + j.running > 0 ? duration(s.eta_s) : "finished"));
  cell(row, "Verdict", s.verdict ? text("span", s.verdict, "verdict " + s.verdict.split(" ")[0]) : text("span", "\u2014"));
  const links = document.createElement("div"); links.className = "links";
  const base = "/api/studies/" + s.id;
  links.append(apiLink("Envelopes", base + "/envelopes?format=table"), apiLink("CSV", base + "/envelopes?format=csv"),
               apiLink("Report", base + "/report"));
  cell(row, "Results", links);
  return row;
}
async function refresh() {
  try {
    const r = await fetch("/api/studies", {headers: headers()});
    const body = await r.json();
    const tbody = document.getElementById("studies");
    if (!r.ok) { tbody.replaceChildren(text("tr", body.error || r.statusText, "err")); return; }
    tbody.replaceChildren(...body.studies.map(studyRow));
    if (!body.studies.length) tbody.append(text("tr", "No studies yet: submit one above.", "small"));
    document.getElementById("updated").textContent = "updated " + new Date().toLocaleTimeString();
  } catch (e) { document.getElementById("updated").textContent = "server not reachable: " + e; }
}
document.getElementById("submit").addEventListener("submit", async ev => {
  ev.preventDefault();
  const msg = document.getElementById("msg"), file = document.getElementById("file").files[0];
  if (!file) { msg.textContent = "choose a study file (JSON) first"; return; }
  const r = await fetch("/api/studies", {method: "POST", headers: Object.assign({"Content-Type": "application/json"}, headers()), body: await file.text()});
  const body = await r.json().catch(() => ({error: r.statusText}));
  msg.className = r.ok ? "small" : "small err";
  msg.textContent = r.ok ? "study " + body.id.slice(0, 12) + ": " + body.jobs + " jobs, " + body.new_jobs + " new" : "error " + r.status + ": " + body.error;
  refresh();
});
refresh();
setInterval(refresh, 2000);
</script></body></html>
)html";
  return kPage;
}

}  // namespace railvsi::scheduler
