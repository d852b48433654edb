#include "shellspace/render/html_viewer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>

#include "shellspace/io/frame_set_check.h"
#include "shellspace/render/color_ramp.h"

namespace shellspace {
namespace {

std::string Base64(const void* data, size_t size) {
  static const char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < size; i += 3) {
    const uint32_t v = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
    out += kAlphabet[v >> 18];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i < size) {
    uint32_t v = bytes[i] << 16;
    if (i + 1 < size) v |= bytes[i + 1] << 8;
    out += kAlphabet[v >> 18];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < size ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

// `text` safe inside an HTML element (and inside a <script> element: no
// "</" that could end it).
std::string Escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// The JSON text inside <script type="application/json">: "</" would end the
// element, so '<' is written as the JSON escape \u003c.
std::string ScriptSafeJson(const std::string& json) {
  std::string out;
  for (const char c : json) {
    if (c == '<') {
      out += "\\u003c";
    } else {
      out += c;
    }
  }
  return out;
}

// `value` with 17 significant digits.
std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

const char kStyle[] = R"(
html,body{margin:0;height:100%;font:14px/1.4 sans-serif;background:#f4f4f2;color:#222}
body{display:flex}
#view{flex:1;min-width:0;position:relative}
canvas{width:100%;height:100%;display:block;cursor:grab;background:#fff}
#panel{width:270px;padding:12px 14px;box-sizing:border-box;overflow:auto;border-left:1px solid #ccc}
h1{font-size:15px;margin:0 0 8px;word-break:break-all}
table{border-collapse:collapse;margin:8px 0}
td{padding:1px 8px 1px 0;vertical-align:top}
td:first-child{color:#555}
#controls{display:flex;gap:8px;align-items:center;margin:8px 0}
#frame{flex:1}
#ramp{height:10px;margin-top:4px}
#rampLabels{display:flex;justify-content:space-between;font-size:12px;color:#555}
#error{color:#b00;white-space:pre-wrap}
.hint{font-size:12px;color:#666}
)";

// The page's script: decodes the frames, draws them with WebGL 1, and wires
// the slider, the play button and the mouse. Everything it needs is in the
// page.
const char kScript[] = R"(
(function () {
  'use strict';
  var t0 = performance.now();
  var body = document.body;
  var shownError = document.getElementById('error');
  function fail(message) {
    body.setAttribute('data-status', 'error');
    shownError.textContent = message;
  }
  function decode(id, Type) {
    var text = atob(document.getElementById(id).textContent.trim());
    var bytes = new Uint8Array(text.length);
    for (var i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
    return new Type(bytes.buffer);
  }
  var meta = document.getElementById('mesh');
  var n = +meta.getAttribute('data-vertices');
  var frameCount = +meta.getAttribute('data-frames');
  var all = decode('positions', Float32Array);
  var indices = decode('faces', Uint32Array);


  // The numbers of the run.
  var rows = [];
  function row(name, value) { rows.push([name, value]); }
  function num(v) { return typeof v === 'number' ? +v.toPrecision(6) + '' : String(v); }
  var summary = {};
  try { summary = JSON.parse(document.getElementById('summary').textContent || '{}'); }
  catch (e) { summary = {'summary': 'unreadable'}; }
  if ('summary' in summary) row('summary', summary.summary);
  if ('path_energy' in summary) row('E_K (path energy)', num(summary.path_energy));
  if ('spline_energy' in summary) row('F_K (spline energy)', num(summary.spline_energy));
  if ('regression_energy' in summary) row('regression energy', num(summary.regression_energy));
  if ('converged' in summary) row('converged', String(summary.converged));
  if ('iterations' in summary) row('iterations', num(summary.iterations));
  var material = summary.material;
  if (material && typeof material === 'object') {
    ['mu', 'lambda', 'eta'].forEach(function (key) {
      if (key in material) row(key === 'mu' ? '\u03bc' : key === 'lambda' ? '\u03bb' : '\u03b7', num(material[key]));
    });
  }
  row('frames', frameCount);
  row('vertices', n);
  row('faces', indices.length / 3);
  var table = document.getElementById('numbers');
  rows.forEach(function (r) {
    var tr = document.createElement('tr');
    var a = document.createElement('td'); a.textContent = r[0];
    var b = document.createElement('td'); b.textContent = r[1];
    tr.appendChild(a); tr.appendChild(b); table.appendChild(tr);
  });

  // Per frame (made when it is first shown): positions, normals, colours
  // (distance from frame 0 over the largest such distance of all frames,
  // through the ramp of the film strips, given as stops 0-255).
  function frame(k) { return all.subarray(3 * n * k, 3 * n * (k + 1)); }
  var maxDistance = +meta.getAttribute('data-max-distance');
  document.getElementById('rampMax').textContent = num(maxDistance);
  var ramp = meta.getAttribute('data-ramp').split(';').map(function (stop) {
    return stop.split(',').map(Number);
  });
  document.getElementById('ramp').style.background = 'linear-gradient(90deg,' +
    ramp.map(function (c) { return 'rgb(' + c.join(',') + ')'; }).join(',') + ')';
  function colours(k) {
    var p = frame(k), p0 = frame(0), c = new Float32Array(3 * n);
    for (var i = 0; i < n; ++i) {
      var dx = p[3 * i] - p0[3 * i], dy = p[3 * i + 1] - p0[3 * i + 1], dz = p[3 * i + 2] - p0[3 * i + 2];
      var d = Math.sqrt(dx * dx + dy * dy + dz * dz);
      var t = maxDistance > 0 ? Math.min(d / maxDistance, 1) * (ramp.length - 1) : 0;
      var j = Math.min(Math.floor(t), ramp.length - 2), f = t - j;
      for (var e = 0; e < 3; ++e) c[3 * i + e] = (ramp[j][e] * (1 - f) + ramp[j + 1][e] * f) / 255;
    }
    return c;
  }
  function normals(p) {
    var m = new Float32Array(3 * n);
    for (var f = 0; f < indices.length; f += 3) {
      var a = 3 * indices[f], b = 3 * indices[f + 1], c = 3 * indices[f + 2];
      var ux = p[b] - p[a], uy = p[b + 1] - p[a + 1], uz = p[b + 2] - p[a + 2];
      var vx = p[c] - p[a], vy = p[c + 1] - p[a + 1], vz = p[c + 2] - p[a + 2];
      var nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
      for (var s = 0; s < 3; ++s) {
        var v = 3 * indices[f + s];
        m[v] += nx; m[v + 1] += ny; m[v + 2] += nz;
      }
    }
    return m;
  }

  // The camera: the bounding box of all frames, its centre and half its
  // diagonal.
  var centre = meta.getAttribute('data-centre').split(',').map(Number);
  var radius = +meta.getAttribute('data-radius') || 1;
  var yaw = 0.5, pitch = 0.35, distance = 2.8 * radius;

  var canvas = document.getElementById('canvas');
  var gl = canvas.getContext('webgl', {antialias: true, preserveDrawingBuffer: true});
  if (!gl) { fail('This browser has no WebGL: the page cannot draw the shapes.'); return; }
  if (!gl.getExtension('OES_element_index_uint')) { fail('WebGL without 32-bit indices (OES_element_index_uint).'); return; }
  function shader(type, source) {
    var s = gl.createShader(type);
    gl.shaderSource(s, source); gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    return s;
  }
  var program = gl.createProgram();
  gl.attachShader(program, shader(gl.VERTEX_SHADER,
    'attribute vec3 position; attribute vec3 normal; attribute vec3 colour;' +
    'uniform mat4 view; uniform mat4 projection; varying vec3 n; varying vec3 c;' +
    'void main() { n = mat3(view) * normal; c = colour; gl_Position = projection * view * vec4(position, 1.0); }'));
  gl.attachShader(program, shader(gl.FRAGMENT_SHADER,
    'precision mediump float; varying vec3 n; varying vec3 c;' +
    'void main() { vec3 m = normalize(n); if (!gl_FrontFacing) m = -m;' +
    ' float light = 0.3 + 0.7 * max(dot(m, normalize(vec3(0.3, 0.5, 1.0))), 0.0);' +
    ' gl_FragColor = vec4(c * light, 1.0); }'));
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) { fail(gl.getProgramInfoLog(program)); return; }
  gl.useProgram(program);
  function attribute(name) {
    var buffer = gl.createBuffer(), location = gl.getAttribLocation(program, name);
    gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    gl.enableVertexAttribArray(location);
    gl.vertexAttribPointer(location, 3, gl.FLOAT, false, 0, 0);
    return buffer;
  }
  var positionBuffer = attribute('position'), normalBuffer = attribute('normal'), colourBuffer = attribute('colour');
  var indexBuffer = gl.createBuffer();
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, indexBuffer);
  gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, indices, gl.STATIC_DRAW);
  gl.enable(gl.DEPTH_TEST);
  var viewLocation = gl.getUniformLocation(program, 'view');
  var projectionLocation = gl.getUniformLocation(program, 'projection');

  function perspective(aspect) {
    var f = 1 / Math.tan(0.35), near = 0.01 * radius, far = 100 * radius;
    return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, 2 * far * near / (near - far), 0];
  }
  function view() {  // column-major: rotate by yaw about y, pitch about x, then back by distance
    var cy = Math.cos(yaw), sy = Math.sin(yaw), cp = Math.cos(pitch), sp = Math.sin(pitch);
    var r = [cy, sp * sy, -cp * sy, 0, 0, cp, sp, 0, sy, -sp * cy, cp * cy, 0];
    var t = [0, 1, 2].map(function (row) {
      return -(r[row] * centre[0] + r[4 + row] * centre[1] + r[8 + row] * centre[2]);
    });
    return [r[0], r[1], r[2], 0, r[4], r[5], r[6], 0, r[8], r[9], r[10], 0, t[0], t[1], t[2] - distance, 1];
  }
  var current = -1;
  function draw() {
    var w = canvas.clientWidth * (window.devicePixelRatio || 1), h = canvas.clientHeight * (window.devicePixelRatio || 1);
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(1, 1, 1, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.uniformMatrix4fv(viewLocation, false, new Float32Array(view()));
    gl.uniformMatrix4fv(projectionLocation, false, new Float32Array(perspective(canvas.width / Math.max(canvas.height, 1))));
    gl.drawElements(gl.TRIANGLES, indices.length, gl.UNSIGNED_INT, 0);
  }
  var slider = document.getElementById('frame');
  var label = document.getElementById('frameLabel');
  slider.max = frameCount - 1;
  function show(k) {
    k = Math.max(0, Math.min(frameCount - 1, k | 0));
    if (k !== current) {
      var p = frame(k);
      gl.bindBuffer(gl.ARRAY_BUFFER, positionBuffer); gl.bufferData(gl.ARRAY_BUFFER, p, gl.DYNAMIC_DRAW);
      gl.bindBuffer(gl.ARRAY_BUFFER, normalBuffer); gl.bufferData(gl.ARRAY_BUFFER, normals(p), gl.DYNAMIC_DRAW);
      gl.bindBuffer(gl.ARRAY_BUFFER, colourBuffer); gl.bufferData(gl.ARRAY_BUFFER, colours(k), gl.DYNAMIC_DRAW);
      current = k;
    }
    slider.value = k;
    label.textContent = 'frame ' + k + ' of ' + (frameCount - 1);
    draw();
  }
  slider.addEventListener('input', function () { stop(); show(+slider.value); });
  var timer = null, play = document.getElementById('play');
  function stop() { if (timer) { clearInterval(timer); timer = null; play.textContent = 'play'; } }
  play.addEventListener('click', function () {
    if (timer) { stop(); return; }
    play.textContent = 'pause';
    timer = setInterval(function () { show((current + 1) % frameCount); }, 250);
  });
  var dragging = null;
  canvas.addEventListener('mousedown', function (e) { dragging = [e.clientX, e.clientY]; });
  window.addEventListener('mouseup', function () { dragging = null; });
  window.addEventListener('mousemove', function (e) {
    if (!dragging) return;
    yaw += 0.01 * (e.clientX - dragging[0]);
    pitch = Math.max(-1.55, Math.min(1.55, pitch + 0.01 * (e.clientY - dragging[1])));
    dragging = [e.clientX, e.clientY];
    draw();
  });
  canvas.addEventListener('wheel', function (e) {
    e.preventDefault();
    distance *= Math.exp(0.001 * e.deltaY);
    draw();
  }, {passive: false});
  window.addEventListener('resize', draw);
  var wanted = /frame=(\w+)/.exec(location.hash);
  show(wanted ? (wanted[1] === 'last' ? frameCount - 1 : +wanted[1]) : 0);
  body.setAttribute('data-load-ms', Math.round(performance.now() - t0));
  body.setAttribute('data-status', 'ready');
})();
)";

}  // namespace

std::string EncodeHtmlViewer(const std::vector<Positions>& frames,
                             const Faces& faces, const std::string& title,
                             const std::string& summary_json) {
  CheckFrameSet(frames, faces, "viewer page");
  const Eigen::Index n = frames[0].rows();
  std::vector<float> positions(static_cast<size_t>(3 * n) * frames.size());
  size_t at = 0;
  for (const Positions& frame : frames) {
    for (Eigen::Index i = 0; i < frame.size(); ++i) {
      positions[at++] = static_cast<float>(frame.data()[i]);
    }
  }
  std::vector<uint32_t> indices(static_cast<size_t>(faces.size()));
  for (Eigen::Index i = 0; i < faces.size(); ++i) {
    indices[i] = static_cast<uint32_t>(faces.data()[i]);
  }
  std::string page;
  page.reserve(positions.size() * 6 + indices.size() * 6 + 20000);
  page += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  page += "<title>" + Escaped(title) + "</title>\n<style>" + kStyle +
          "</style>\n</head>\n<body data-status=\"loading\">\n";
  page += "<div id=\"view\"><canvas id=\"canvas\"></canvas></div>\n";
  page += "<div id=\"panel\">\n<h1>" + Escaped(title) + "</h1>\n";
  page += "<div id=\"controls\"><button id=\"play\">play</button>"
          "<input id=\"frame\" type=\"range\" min=\"0\" value=\"0\" step=\"1\">"
          "</div>\n<div id=\"frameLabel\"></div>\n";
  page += "<table id=\"numbers\"></table>\n";
  page += "<div>distance from frame 0</div><div id=\"ramp\"></div>"
          "<div id=\"rampLabels\"><span>0</span><span id=\"rampMax\"></span>"
          "</div>\n";
  page += "<p class=\"hint\">Drag to orbit, scroll to zoom.</p>\n";
  page += "<div id=\"error\"></div>\n</div>\n";
  // The film strips' ramp (color_ramp.h) at kRampStops points, linear in
  // between as RampColor is.
  constexpr int kRampStops = 9;
  std::string ramp;
  for (int j = 0; j < kRampStops; ++j) {
    const Eigen::Vector3d c = RampColor(j / (kRampStops - 1.0));
    for (int e = 0; e < 3; ++e) {
      ramp += std::to_string(static_cast<int>(std::lround(255 * c[e])));
      ramp += e < 2 ? "," : j + 1 < kRampStops ? ";" : "";
    }
  }
  // The camera's box and the colours' scale over all frames.
  Eigen::RowVector3d lo = frames[0].colwise().minCoeff();
  Eigen::RowVector3d hi = frames[0].colwise().maxCoeff();
  double max_distance = 0;
  for (const Positions& frame : frames) {
    lo = lo.cwiseMin(frame.colwise().minCoeff());
    hi = hi.cwiseMax(frame.colwise().maxCoeff());
    max_distance = std::max(
        max_distance, (frame - frames[0]).rowwise().norm().maxCoeff());
  }
  const Eigen::RowVector3d centre = 0.5 * (lo + hi);
  page += "<div id=\"mesh\" hidden data-vertices=\"" + std::to_string(n) +
          "\" data-frames=\"" + std::to_string(frames.size()) +
          "\" data-ramp=\"" + ramp + "\" data-centre=\"" +
          Number(centre(0)) + "," + Number(centre(1)) + "," +
          Number(centre(2)) + "\" data-radius=\"" +
          Number(0.5 * (hi - lo).norm()) + "\" data-max-distance=\"" +
          Number(max_distance) + "\"></div>\n";
  page += "<script type=\"application/json\" id=\"summary\">" +
          ScriptSafeJson(summary_json) + "</script>\n";
  page += "<script type=\"application/octet-stream\" id=\"positions\">";
  page += Base64(positions.data(), positions.size() * sizeof(float));
  page += "</script>\n<script type=\"application/octet-stream\" id=\"faces\">";
  page += Base64(indices.data(), indices.size() * sizeof(uint32_t));
  page += "</script>\n<script>";
  page += kScript;
  page += "</script>\n</body>\n</html>\n";
  return page;
}

}  // namespace shellspace
