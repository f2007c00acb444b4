// index.html for `lumis compare`: one file with inline CSS and JS, images referenced by relative file name in the
// same folder, no external resources. The script marks <body data-ready="1"> once it has built the viewer, which
// the end-to-end test checks in headless Chromium.
#include <cstdio>
#include <sstream>

#include "app/compare.h"

namespace lumis {

namespace {

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

// JSON inside <script>: "</" would end the element early.
std::string script_safe(const std::string& json) {
  std::string out;
  for (size_t i = 0; i < json.size(); ++i) {
    if (json[i] == '<' && i + 1 < json.size() && json[i + 1] == '/') out += "<\\";
    else out += json[i];
  }
  return out;
}

std::string num(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

constexpr const char* kStyle = R"CSS(
body { background: #181818; color: #e8e8e8; font: 14px/1.4 system-ui, sans-serif; margin: 16px; }
h1 { font-size: 18px; margin: 0 0 8px; }
#buttons button { background: #2a2a2a; color: #e8e8e8; border: 1px solid #555; padding: 4px 10px; margin: 0 4px 4px 0;
  cursor: pointer; font: inherit; }
#buttons button.active { background: #3b528b; border-color: #9ab; }
#viewer { position: relative; width: 100%; height: 70vh; overflow: hidden; background: #000; cursor: grab;
  border: 1px solid #444; }
#viewer img { position: absolute; left: 0; top: 0; transform-origin: 0 0; image-rendering: pixelated;
  user-select: none; -webkit-user-drag: none; }
#status { margin: 6px 0; color: #aaa; }
table { border-collapse: collapse; margin: 12px 0; }
th, td { border: 1px solid #444; padding: 3px 8px; text-align: right; }
th:first-child, td:first-child { text-align: left; }
tr.active td { background: #2d3a55; }
.figures img { max-width: 100%; margin: 8px 8px 0 0; image-rendering: pixelated; }
kbd { background: #333; border: 1px solid #555; border-radius: 3px; padding: 0 4px; }
)CSS";

constexpr const char* kScript = R"JS(
(function () {
  const data = JSON.parse(document.getElementById('report-data').textContent);
  const views = data.variants.map(v => ({ name: v.name, png: v.png, error: v.error_png, info: v }));
  views.push({ name: 'reference', png: data.reference.png, error: null, info: null });
  const viewer = document.getElementById('viewer'), img = document.getElementById('view-image');
  const buttons = document.getElementById('buttons'), status = document.getElementById('status');
  const list = document.getElementById('variant-list');
  const p = (x, d) => (typeof x === 'number' ? x.toPrecision(d) : 'n/a');
  let current = 0, showError = false, scale = 1, tx = 0, ty = 0, fitted = false;

  function apply() { img.style.transform = 'translate(' + tx + 'px,' + ty + 'px) scale(' + scale + ')'; }
  function fit() {
    const w = img.naturalWidth || data.width, h = img.naturalHeight || data.height;
    scale = Math.max(1, Math.floor(Math.min(viewer.clientWidth / w, viewer.clientHeight / h))) || 1;
    tx = (viewer.clientWidth - w * scale) / 2; ty = (viewer.clientHeight - h * scale) / 2; apply();
  }
  function show(i) {
    current = (i + views.length) % views.length;
    const v = views[current];
    img.src = showError && v.error ? v.error : v.png;
    buttons.querySelectorAll('button').forEach((b, k) => b.classList.toggle('active', k === current));
    document.querySelectorAll('#metrics tbody tr')
        .forEach(r => r.classList.toggle('active', r.dataset.variant === v.name));
    let text = v.name + (showError && v.error ? ' (|error|, shared scale 0..' + p(data.error_scale, 3) + ')' : '');
    if (v.info) text += ' - ' + v.info.spp + ' spp, ' + p(v.info.seconds, 3) + ' s, relMSE ' + p(v.info.relmse, 4);
    status.textContent = text;
  }
  views.forEach((v, i) => {
    const b = document.createElement('button');
    b.textContent = (i < 9 ? (i + 1) + ': ' : '') + v.name;
    b.addEventListener('click', () => show(i));
    buttons.appendChild(b);
    const li = document.createElement('li');
    li.dataset.variant = v.name; li.textContent = v.name;
    list.appendChild(li);
  });
  img.addEventListener('load', () => { if (!fitted) { fitted = true; fit(); } });
  viewer.addEventListener('wheel', e => {
    e.preventDefault();
    const r = viewer.getBoundingClientRect(), mx = e.clientX - r.left, my = e.clientY - r.top;
    const f = e.deltaY < 0 ? 1.25 : 0.8, s = Math.min(256, Math.max(0.05, scale * f));
    tx = mx - (mx - tx) * s / scale; ty = my - (my - ty) * s / scale; scale = s; apply();
  }, { passive: false });
  let drag = null;
  viewer.addEventListener('mousedown', e => { drag = { x: e.clientX - tx, y: e.clientY - ty }; e.preventDefault(); });
  window.addEventListener('mousemove', e => {
    if (drag) { tx = e.clientX - drag.x; ty = e.clientY - drag.y; apply(); }
  });
  window.addEventListener('mouseup', () => { drag = null; });
  viewer.addEventListener('dblclick', fit);
  window.addEventListener('keydown', e => {
    if (e.key >= '1' && e.key <= '9' && +e.key <= views.length) show(+e.key - 1);
    else if (e.key === 'r' || e.key === '0') show(views.length - 1);
    else if (e.key === 'ArrowRight' || e.key === ' ') show(current + 1);
    else if (e.key === 'ArrowLeft') show(current - 1);
    else if (e.key === 'e') { showError = !showError; show(current); }
    else if (e.key === 'f') fit();
    else return;
    e.preventDefault();
  });
  show(0);
  document.body.dataset.ready = '1';
  document.body.dataset.views = views.length;
})();
)JS";

}  // namespace

std::string report_html(const CompareReport& r) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>lumis compare: "
    << html_escape(r.scene) << "</title>\n<style>" << kStyle << "</style></head>\n<body data-ready=\"0\">\n";
  h << "<h1>lumis compare: " << html_escape(r.scene) << "</h1>\n<p>" << r.width << "x" << r.height << ", "
    << (r.equal_time ? "equal time, " + num("%g", r.time_budget) + " s per variant"
                     : "equal samples, " + std::to_string(r.spp) + " spp")
    << "; reference: " << html_escape(r.reference_source);
  if (r.reference_spp) h << " (nee_mis, " << r.reference_spp << " spp)";
  if (r.reference_grey) h << " (grey: its Y is used as R, G and B)";
  h << ".</p>\n<p>Settings: " << html_escape(settings_summary(r)) << ".</p>\n";
  h << "<p>Keys: <kbd>1</kbd>-<kbd>9</kbd> variant, <kbd>r</kbd> reference, <kbd>&larr;</kbd>/<kbd>&rarr;</kbd> "
       "cycle, <kbd>e</kbd> error view, <kbd>f</kbd> fit. Mouse wheel zooms, drag pans, double-click fits.</p>\n";
  h << "<div id=\"buttons\"></div>\n<div id=\"status\"></div>\n<div id=\"viewer\"><img id=\"view-image\" alt=\"\" "
       "draggable=\"false\"></div>\n";
  h << "<table id=\"metrics\"><thead><tr><th>variant</th><th>spp</th><th>time (s)</th><th>samples/s</th>"
       "<th>rays/s</th><th>MSE</th><th>relMSE</th><th>efficiency</th></tr></thead><tbody>\n";
  for (const VariantResult& v : r.variants)
    h << "<tr data-variant=\"" << html_escape(v.name) << "\"><td>" << html_escape(v.name) << "</td><td>" << v.spp
      << "</td><td>" << num("%.3f", v.seconds) << "</td><td>" << num("%.3g", v.samples_per_second()) << "</td><td>"
      << num("%.3g", v.rays_per_second()) << "</td><td>" << num("%.4g", v.mse) << "</td><td>"
      << num("%.4g", v.rel_mse) << "</td><td>" << num("%.4g", v.efficiency()) << "</td></tr>\n";
  h << "</tbody></table>\n<p>efficiency = 1 / (relMSE &times; time); relMSE = mean of (x &minus; ref)&sup2; / "
       "(ref&sup2; + 0.01).</p>\n<ul id=\"variant-list\" hidden></ul>\n<div class=\"figures\">\n<img src=\""
    << html_escape(r.montage) << "\" alt=\"montage\">\n";
  if (!r.convergence_png.empty()) h << "<img src=\"" << html_escape(r.convergence_png) << "\" alt=\"convergence\">\n";
  h << "</div>\n<script type=\"application/json\" id=\"report-data\">" << script_safe(report_json(r).dump())
    << "</script>\n<script>" << kScript << "</script>\n</body></html>\n";
  return h.str();
}

}  // namespace lumis
