// swarmplan report: interactive 3-D view of a plan, drawn on a canvas with no library.
// Drag to rotate, wheel to zoom, checkboxes to show or hide UAVs. The scene comes from the
// JSON block with id "scene". After each frame the canvas carries data-drawn = number of
// primitives drawn, which tests read.
(function () {
  "use strict";
  var errors = [];
  window.addEventListener("error", function (e) {
    errors.push(String(e.message));
    document.body.setAttribute("data-errors", errors.join(" | "));
  });
  var scene = JSON.parse(document.getElementById("scene").textContent);
  var canvas = document.getElementById("view3d");
  var ctx = canvas.getContext("2d");
  var state = { yaw: -0.6, pitch: 0.9, zoom: 1.0, hidden: {} };
  var t = scene.terrain;
  var cx = (scene.box.x[0] + scene.box.x[1]) / 2;
  var cy = (scene.box.y[0] + scene.box.y[1]) / 2;
  var cz = (t.min + t.max) / 2;
  var span = Math.max(scene.box.x[1] - scene.box.x[0], scene.box.y[1] - scene.box.y[0]);
  var zExaggeration = 1.0;

  function project(x, y, z) {
    var px = x - cx, py = y - cy, pz = (z - cz) * zExaggeration;
    var c = Math.cos(state.yaw), s = Math.sin(state.yaw);
    var rx = c * px - s * py, ry = s * px + c * py;
    var cp = Math.cos(state.pitch), sp = Math.sin(state.pitch);
    var depth = ry * cp + pz * sp;
    var up = pz * cp - ry * sp;
    var scale = 0.8 * Math.min(canvas.width, canvas.height) / span * state.zoom;
    return [canvas.width / 2 + rx * scale, canvas.height / 2 - up * scale, depth];
  }

  function heightColor(h) {
    var f = (h - t.min) / Math.max(1e-9, t.max - t.min);
    var r = Math.round(60 + 150 * f), g = Math.round(120 + 80 * (1 - Math.abs(f - 0.5) * 2)), b = Math.round(70 + 40 * (1 - f));
    return "rgb(" + r + "," + g + "," + b + ")";
  }

  function draw() {
    var drawn = 0;
    ctx.fillStyle = "#f4f6f8";
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    // Terrain quads, far to near (painter's algorithm).
    var quads = [];
    for (var j = 0; j + 1 < t.ny; j++) {
      for (var i = 0; i + 1 < t.nx; i++) {
        var k = j * t.nx + i;
        var hs = [t.z[k], t.z[k + 1], t.z[k + t.nx + 1], t.z[k + t.nx]];
        var xs = [t.x0 + i * t.dx, t.x0 + (i + 1) * t.dx, t.x0 + (i + 1) * t.dx, t.x0 + i * t.dx];
        var ys = [t.y0 + j * t.dy, t.y0 + j * t.dy, t.y0 + (j + 1) * t.dy, t.y0 + (j + 1) * t.dy];
        var pts = [], d = 0;
        for (var q = 0; q < 4; q++) {
          var p = project(xs[q], ys[q], hs[q]);
          pts.push(p);
          d += p[2];
        }
        quads.push({ pts: pts, depth: d / 4, h: (hs[0] + hs[1] + hs[2] + hs[3]) / 4 });
      }
    }
    quads.sort(function (a, b) { return b.depth - a.depth; });
    for (var n = 0; n < quads.length; n++) {
      var qd = quads[n];
      ctx.beginPath();
      ctx.moveTo(qd.pts[0][0], qd.pts[0][1]);
      for (var m = 1; m < 4; m++) ctx.lineTo(qd.pts[m][0], qd.pts[m][1]);
      ctx.closePath();
      ctx.fillStyle = heightColor(qd.h);
      ctx.fill();
      ctx.strokeStyle = "rgba(0,0,0,0.08)";
      ctx.stroke();
      drawn++;
    }
    // Threat cylinders as wireframes from the ground to their drawn height above it.
    scene.threats.forEach(function (th) {
      ctx.strokeStyle = "rgba(200,30,30,0.8)";
      var base = th.ground, top = th.ground + th.z;
      [base, top].forEach(function (z) {
        ctx.beginPath();
        for (var a = 0; a <= 36; a++) {
          var ang = a / 36 * 2 * Math.PI;
          var p = project(th.x + th.r * Math.cos(ang), th.y + th.r * Math.sin(ang), z);
          if (a === 0) ctx.moveTo(p[0], p[1]); else ctx.lineTo(p[0], p[1]);
        }
        ctx.stroke();
      });
      for (var a = 0; a < 12; a++) {
        var ang = a / 12 * 2 * Math.PI;
        var p0 = project(th.x + th.r * Math.cos(ang), th.y + th.r * Math.sin(ang), base);
        var p1 = project(th.x + th.r * Math.cos(ang), th.y + th.r * Math.sin(ang), top);
        ctx.beginPath(); ctx.moveTo(p0[0], p0[1]); ctx.lineTo(p1[0], p1[1]); ctx.stroke();
      }
      drawn++;
    });
    // Ground nodes.
    scene.ground.forEach(function (g) {
      var p = project(g.x, g.y, g.z);
      ctx.fillStyle = "#222";
      ctx.fillRect(p[0] - 4, p[1] - 4, 8, 8);
      ctx.fillText(g.name, p[0] + 6, p[1] - 6);
      drawn++;
    });
    // Paths.
    scene.paths.forEach(function (path, idx) {
      if (state.hidden[idx]) return;
      ctx.strokeStyle = path.color;
      ctx.fillStyle = path.color;
      ctx.lineWidth = 2.5;
      ctx.beginPath();
      path.points.forEach(function (pt, k) {
        var p = project(pt[0], pt[1], pt[2]);
        if (k === 0) ctx.moveTo(p[0], p[1]); else ctx.lineTo(p[0], p[1]);
      });
      ctx.stroke();
      (path.waypoints || path.points).forEach(function (pt) {
        var p = project(pt[0], pt[1], pt[2]);
        ctx.beginPath(); ctx.arc(p[0], p[1], 3, 0, 2 * Math.PI); ctx.fill();
      });
      ctx.lineWidth = 1;
      drawn++;
    });
    canvas.setAttribute("data-drawn", String(drawn));
  }

  var controls = document.getElementById("uav-toggles");
  scene.paths.forEach(function (path, idx) {
    var label = document.createElement("label");
    var box = document.createElement("input");
    box.type = "checkbox";
    box.checked = true;
    box.addEventListener("change", function () { state.hidden[idx] = !box.checked; draw(); });
    label.appendChild(box);
    var swatch = document.createElement("span");
    swatch.style.color = path.color;
    swatch.textContent = " \u25A0 " + path.name + "  ";
    label.appendChild(swatch);
    controls.appendChild(label);
  });
  var dragging = null;
  canvas.addEventListener("mousedown", function (e) { dragging = [e.clientX, e.clientY]; });
  window.addEventListener("mouseup", function () { dragging = null; });
  window.addEventListener("mousemove", function (e) {
    if (!dragging) return;
    state.yaw += (e.clientX - dragging[0]) * 0.01;
    state.pitch = Math.max(0.05, Math.min(1.55, state.pitch + (e.clientY - dragging[1]) * 0.01));
    dragging = [e.clientX, e.clientY];
    draw();
  });
  canvas.addEventListener("wheel", function (e) {
    e.preventDefault();
    state.zoom = Math.max(0.2, Math.min(8, state.zoom * (e.deltaY < 0 ? 1.1 : 1 / 1.1)));
    draw();
  }, { passive: false });
  var exag = document.getElementById("z-exaggeration");
  if (exag) exag.addEventListener("input", function () { zExaggeration = Number(exag.value); draw(); });
  draw();
})();
