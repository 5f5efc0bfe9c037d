// The page's stylesheet and the script of its 3D view (written for conform; uses three.js r111 and its
// OrbitControls, both from Debian's libjs-three).

#include "report_detail.h"

namespace conform::html::detail {

const char* page_css() {
  return R"css(
body{font-family:"DejaVu Sans",Arial,Helvetica,sans-serif;font-size:14px;color:#222;background:#fff;margin:0 auto;
  max-width:1180px;padding:12px 20px 40px}
h1{font-size:22px;margin:6px 0 4px}h2{font-size:17px;margin:22px 0 8px;border-bottom:1px solid #ccd;padding-bottom:3px}
h3{font-size:14px;margin:12px 0 4px}
.verdict{font-size:16px;font-weight:bold;padding:7px 12px;border-radius:4px;margin:8px 0}
.verdict.ok{background:#e3f4e3;color:#145214;border-left:6px solid #2ca02c}
.verdict.check{background:#fff4d6;color:#6b4a00;border-left:6px solid #e6a400}
.verdict.fail{background:#fde2e1;color:#8a1010;border-left:6px solid #d62728}
table{border-collapse:collapse;margin:4px 0 10px}
td,th{border:1px solid #d4d8de;padding:3px 9px;text-align:left;vertical-align:top}
th{background:#f0f2f5}td.num{text-align:right;font-variant-numeric:tabular-nums}
table.meta td:first-child{color:#555}
ul.warnings{background:#fff4d6;padding:6px 6px 6px 28px;margin:6px 0}
.viewer{display:flex;gap:12px;align-items:flex-start}
.view{position:relative;flex:1;height:560px;border:1px solid #ccd;background:#f4f6f9;min-width:300px}
.side{width:170px;font-size:13px}.side label{display:block;margin:2px 0}
.side button{margin:4px 0 8px;padding:3px 10px}
.swatch{display:inline-block;width:12px;height:12px;border:1px solid #667;vertical-align:-2px;margin-right:4px}
.readout{position:absolute;left:6px;bottom:6px;max-width:calc(100% - 24px);background:rgba(255,255,255,.92);
  border:1px solid #99a;border-radius:3px;padding:4px 8px;font-size:13px;font-variant-numeric:tabular-nums;display:none;z-index:2}
.callouts{position:absolute;left:0;top:0;width:100%;height:100%;pointer-events:none;overflow:hidden;z-index:1}
.callout{position:absolute;background:#fff;border:1px solid #333;border-radius:3px;padding:0 4px;font-size:12px;
  white-space:nowrap;font-variant-numeric:tabular-nums}
svg.plot{width:100%;max-width:720px;height:auto;font-size:11px;display:block}
svg.colour-bar{width:150px;height:auto;font-size:11px;display:block}
svg .grid{stroke:#e4e6ea}svg .frame{fill:none;stroke:#444}svg .title{font-weight:bold;font-size:12px}
svg .line{fill:none;stroke-width:1.6}svg .band{fill:#2ca02c;fill-opacity:.14}svg .band-label{fill:#1d6b1d}
svg .band.reject{fill:#d62728;fill-opacity:.13}svg .band-label.reject{fill:#8a1010}
svg .bar.overflow{stroke:#222;stroke-width:1.2;stroke-dasharray:3 2}svg .overflow-label{fill:#333;font-size:11px}
svg .mark{stroke:#555;stroke-dasharray:4 3}
.note{color:#555;font-size:12px;margin:3px 0}
pre{background:#f6f7f9;border:1px solid #dde;padding:8px;overflow:auto;max-height:420px;font-size:12px}
@media print{.side button,.side input{display:none}.view{height:420px}body{max-width:none}details{display:none}}
)css";
}

const char* viewer_js() {
  return R"js(
(function () {
  'use strict';
  var body = document.body;
  var t0 = window.performance ? performance.now() : 0;
  function fill_json() {
    var text = document.getElementById('conform-result').textContent;
    document.getElementById('conform-json-text').textContent = JSON.stringify(JSON.parse(text), null, 2);
  }
  function bytes_of(b64) {
    var s = atob(b64), out = new Uint8Array(s.length);
    for (var i = 0; i < s.length; ++i) out[i] = s.charCodeAt(i);
    return out.buffer;
  }
  function set_attr(g, name, attr) {
    if (g.setAttribute) g.setAttribute(name, attr); else g.addAttribute(name, attr);
  }
  function rgb(c) { return new THREE.Color(c[0] / 255, c[1] / 255, c[2] / 255); }

  function make_object(o) {
    var g = new THREE.BufferGeometry();
    var pos = new Float32Array(bytes_of(o.positions));
    var colours = o.colours ? new Uint8Array(bytes_of(o.colours)) : null;
    if (o.kind === 'arrows') {
      var dir = new Float32Array(bytes_of(o.directions)), seg = new Float32Array(pos.length * 2);
      for (var i = 0; i < pos.length / 3; ++i) {
        for (var k = 0; k < 3; ++k) {
          seg[6 * i + k] = pos[3 * i + k];
          seg[6 * i + 3 + k] = pos[3 * i + k] + o.length * dir[3 * i + k];
        }
      }
      set_attr(g, 'position', new THREE.BufferAttribute(seg, 3));
      var group = new THREE.Group();
      group.add(new THREE.LineSegments(g, new THREE.LineBasicMaterial({color: rgb(o.colour)})));
      var dots = new THREE.BufferGeometry();
      set_attr(dots, 'position', new THREE.BufferAttribute(pos, 3));
      group.add(new THREE.Points(dots, new THREE.PointsMaterial({color: rgb(o.colour), size: 4, sizeAttenuation: false})));
      return group;
    }
    set_attr(g, 'position', new THREE.BufferAttribute(pos, 3));
    if (colours) set_attr(g, 'color', new THREE.BufferAttribute(colours, 3, true));
    var vertex_colours = THREE.VertexColors !== undefined ? THREE.VertexColors : true;
    var common = colours ? {vertexColors: vertex_colours} : {color: rgb(o.colour)};
    if (o.kind === 'points') {
      common.size = o.size_px;
      common.sizeAttenuation = false;
      return new THREE.Points(g, new THREE.PointsMaterial(common));
    }
    if (o.kind === 'polyline') {
      var line_material = new THREE.LineBasicMaterial(common);
      if (o.pieces) return new THREE.LineSegments(g, line_material);
      return o.closed ? new THREE.LineLoop(g, line_material) : new THREE.Line(g, line_material);
    }
    g.setIndex(new THREE.BufferAttribute(new Uint32Array(bytes_of(o.indices)), 1));
    g.computeVertexNormals();
    common.side = THREE.DoubleSide;
    common.transparent = o.opacity < 1;
    common.opacity = o.opacity;
    common.depthWrite = o.opacity >= 1;
    return new THREE.Mesh(g, new THREE.MeshLambertMaterial(common));
  }

  // The camera direction (Z up, a three-quarter view; a flat part is seen along its thin axis, tilted a little) and
  // the target and distance at which the drawn vertices (`points`, flat xyz arrays, sampled) fill `fill` of the
  // canvas in width or in height.
  function frame(camera, box, points, aspect, fill) {
    var size = box.getSize(new THREE.Vector3()), centre = box.getCenter(new THREE.Vector3());
    var e = [size.x, size.y, size.z], big = Math.max(e[0], e[1], e[2], 1e-6), d = [0.55, -0.75, 0.45];
    var thin = e.indexOf(Math.min(e[0], e[1], e[2]));
    if (e[thin] < 0.2 * big) {
      for (var k = 0; k < 3; ++k) d[k] = k === thin ? 1 : 0.35 * d[k];
    }
    var back = new THREE.Vector3(d[0], d[1], d[2]).normalize();
    var forward = back.clone().negate(), right = new THREE.Vector3().crossVectors(forward, camera.up);
    if (right.lengthSq() < 1e-12) right.set(1, 0, 0);
    right.normalize();
    var up = new THREE.Vector3().crossVectors(right, forward).normalize();
    var total = 0;
    points.forEach(function (a) { total += a.length / 3; });
    if (total === 0) {  // nothing shown when the page opens: the box's corners
      var corners = [];
      for (var c = 0; c < 8; ++c) {
        corners.push(c & 1 ? box.max.x : box.min.x, c & 2 ? box.max.y : box.min.y, c & 4 ? box.max.z : box.min.z);
      }
      points = [corners];
      total = 8;
    }
    var stride = Math.max(1, Math.ceil(total / 60000)), xyz = [], x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    var q = new THREE.Vector3();
    points.forEach(function (a) {
      for (var i = 0; i + 2 < a.length; i += 3 * stride) {
        q.set(a[i], a[i + 1], a[i + 2]).sub(centre);
        var x = q.dot(right), y = q.dot(up);
        xyz.push(x, y, q.dot(back));
        x0 = Math.min(x0, x), x1 = Math.max(x1, x), y0 = Math.min(y0, y), y1 = Math.max(y1, y);
      }
    });
    var mx = 0.5 * (x0 + x1), my = 0.5 * (y0 + y1);
    var tan_v = Math.tan(camera.fov * Math.PI / 360) * fill, tan_h = tan_v * aspect, distance = 1e-6 * big;
    for (var j = 0; j < xyz.length; j += 3) {
      distance = Math.max(distance, xyz[j + 2] + Math.abs(xyz[j] - mx) / tan_h, xyz[j + 2] + Math.abs(xyz[j + 1] - my) / tan_v,
                          xyz[j + 2] + 1e-6 * big);
    }
    var target = centre.clone().add(right.multiplyScalar(mx)).add(up.multiplyScalar(my));
    return {centre: target, position: target.clone().add(back.multiplyScalar(distance)), distance: distance,
            radius: Math.max(0.5 * size.length(), 1e-6)};
  }

  function signed(v, digits) { return isNaN(v) ? 'unmatched' : (v >= 0 ? '+' : '') + v.toFixed(digits); }

  function start() {
    var data = JSON.parse(document.getElementById('conform-scene').textContent);
    var view = document.getElementById('conform-view');
    var renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setSize(view.clientWidth, view.clientHeight);
    renderer.setClearColor(0xf4f6f9, 1);
    view.appendChild(renderer.domElement);
    var scene = new THREE.Scene();
    var camera = new THREE.PerspectiveCamera(35, view.clientWidth / view.clientHeight, 0.01, 1e7);
    camera.up.set(0, 0, 1);
    scene.add(new THREE.AmbientLight(0xffffff, 0.55));
    var light = new THREE.DirectionalLight(0xffffff, 0.6);
    light.position.set(0.3, 0.4, 1);
    camera.add(light);
    scene.add(camera);
    var box = new THREE.Box3(), objects = [], pickables = [];
    data.objects.forEach(function (o, index) {
      var object = make_object(o);
      object.visible = o.visible;
      scene.add(object);
      objects.push(object);
      if (o.count > 0) box.expandByObject(object);
      pickables.push({index: index, name: o.name, pos: new Float32Array(bytes_of(o.positions)),
                      values: o.values ? new Float32Array(bytes_of(o.values)) : null, label: o.value_label});
    });
    if (box.isEmpty()) box.setFromCenterAndSize(new THREE.Vector3(), new THREE.Vector3(1, 1, 1));
    var drawn = pickables.filter(function (p) { return objects[p.index].visible && data.objects[p.index].count > 0; });
    var framed = frame(camera, box, drawn.map(function (p) { return p.pos; }), view.clientWidth / view.clientHeight, 0.9);
    camera.near = framed.distance / 1000;
    camera.far = framed.distance + 20 * framed.radius;
    camera.position.copy(framed.position);
    camera.updateProjectionMatrix();
    var controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.target.copy(framed.centre);
    controls.screenSpacePanning = true;
    controls.update();
    controls.saveState();

    // The picked point: a dark mark drawn over everything, and the readout under the view's lower left corner.
    var mark_geometry = new THREE.BufferGeometry();
    set_attr(mark_geometry, 'position', new THREE.BufferAttribute(new Float32Array(3), 3));
    var mark = new THREE.Points(mark_geometry, new THREE.PointsMaterial(
        {color: 0x111111, size: 10, sizeAttenuation: false, depthTest: false}));
    mark.renderOrder = 1000;
    mark.visible = false;
    scene.add(mark);
    var readout = document.getElementById('conform-readout');

    // Callouts: a dot at the point, a leader and the label, placed over the canvas at every render.
    var callouts = [], callout_layer = document.createElement('div');
    callout_layer.className = 'callouts';
    callout_layer.innerHTML = '<svg width="100%" height="100%"></svg>';  // the parser gives it SVG's namespace
    var leaders = callout_layer.firstChild, svg_ns = leaders.namespaceURI;
    (data.callouts || []).forEach(function (c) {
      var label = document.createElement('div'), line = document.createElementNS(svg_ns, 'line');
      var dot = document.createElementNS(svg_ns, 'circle');
      label.className = 'callout';
      label.textContent = c.label;
      line.setAttribute('stroke', '#222');
      dot.setAttribute('r', '4');
      dot.setAttribute('fill', 'none');
      dot.setAttribute('stroke', '#111');
      dot.setAttribute('stroke-width', '1.5');
      leaders.appendChild(line);
      leaders.appendChild(dot);
      callout_layer.appendChild(label);
      callouts.push({at: new THREE.Vector3(c.at[0], c.at[1], c.at[2]), label: label, line: line, dot: dot});
    });
    view.appendChild(callout_layer);
    var callout_box = document.getElementById('conform-callouts');

    function place_callouts() {
      callout_layer.style.display = callout_box && !callout_box.checked ? 'none' : '';
      var w = view.clientWidth, h = view.clientHeight, placed = [];
      callouts.forEach(function (c) {
        var p = c.at.clone().project(camera);
        var inside = p.z < 1 && Math.abs(p.x) <= 1 && Math.abs(p.y) <= 1;
        c.label.style.display = inside ? '' : 'none';
        c.line.style.display = c.dot.style.display = inside ? '' : 'none';
        if (!inside) return;
        c.x = (p.x + 1) * 0.5 * w;
        c.y = (1 - p.y) * 0.5 * h;
        placed.push(c);
      });
      // Labels up and to the right of their points, moved apart vertically where they would overlap.
      placed.sort(function (a, b) { return a.y - b.y; });
      var last = -1e9;
      placed.forEach(function (c) {
        var width = c.label.offsetWidth, height = c.label.offsetHeight + 3;
        c.ly = Math.max(c.y - 30, last + height, 2);
        last = c.ly;
        c.lx = Math.min(c.x + 24, w - width - 2);
        if (c.lx < c.x + 6 && c.lx + width > c.x - 6) c.lx = Math.max(2, c.x - 24 - width);
        c.label.style.left = Math.round(c.lx) + 'px';
        c.label.style.top = Math.round(c.ly) + 'px';
        var join_x = c.lx > c.x ? c.lx : c.lx + width;
        c.line.setAttribute('x1', c.x.toFixed(1));
        c.line.setAttribute('y1', c.y.toFixed(1));
        c.line.setAttribute('x2', join_x.toFixed(1));
        c.line.setAttribute('y2', (c.ly + height / 2).toFixed(1));
        c.dot.setAttribute('cx', c.x.toFixed(1));
        c.dot.setAttribute('cy', c.y.toFixed(1));
      });
    }

    function render() {
      renderer.render(scene, camera);
      place_callouts();
    }

    // The drawn vertex nearest to (client_x, client_y) within 10 pixels, among the visible layers; a layer with
    // values (e.g. the deviation) before one without.
    function nearest(client_x, client_y) {
      var rect = renderer.domElement.getBoundingClientRect(), px = client_x - rect.left, py = client_y - rect.top;
      camera.updateMatrixWorld();
      var m = new THREE.Matrix4().multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse).elements;
      var best = null;
      pickables.forEach(function (p) {
        if (!objects[p.index].visible) return;
        var a = p.pos, rank = p.values ? 0 : 1e6;
        for (var i = 0; i + 2 < a.length; i += 3) {
          var x = a[i], y = a[i + 1], z = a[i + 2], cw = m[3] * x + m[7] * y + m[11] * z + m[15];
          if (cw <= 0) continue;
          var dx = ((m[0] * x + m[4] * y + m[8] * z + m[12]) / cw + 1) * 0.5 * rect.width - px;
          var dy = (1 - (m[1] * x + m[5] * y + m[9] * z + m[13]) / cw) * 0.5 * rect.height - py;
          var d2 = dx * dx + dy * dy;
          if (d2 > 100) continue;
          if (!best || rank + d2 < best.key) best = {key: rank + d2, pickable: p, i: i / 3};
        }
      });
      return best;
    }

    function show_pick(client_x, client_y) {
      var hit = nearest(client_x, client_y);
      if (!hit) {
        mark.visible = false;
        readout.style.display = 'none';
        render();
        return;
      }
      var p = hit.pickable, a = p.pos, i = hit.i, o = data.origin;
      mark.geometry.attributes.position.array.set([a[3 * i], a[3 * i + 1], a[3 * i + 2]]);
      mark.geometry.attributes.position.needsUpdate = true;
      mark.visible = true;
      var text = p.name + ': x ' + (o[0] + a[3 * i]).toFixed(3) + ', y ' + (o[1] + a[3 * i + 1]).toFixed(3) +
                 ', z ' + (o[2] + a[3 * i + 2]).toFixed(3) + ' mm';
      if (p.values) text += '; ' + p.label + ' ' + signed(p.values[i], 4);
      readout.textContent = text;
      readout.style.display = 'block';
      render();
    }

    var down = null;
    renderer.domElement.addEventListener('pointerdown', function (e) { down = [e.clientX, e.clientY]; });
    renderer.domElement.addEventListener('pointerup', function (e) {
      if (down && Math.abs(e.clientX - down[0]) + Math.abs(e.clientY - down[1]) < 5) show_pick(e.clientX, e.clientY);
      down = null;
    });
    // For a page's own checks (and the browser test): where a layer's i-th drawn vertex is, in client pixels.
    window.conform_view = {
      client_of: function (name, i) {
        var p = pickables.filter(function (q) { return q.name === name; })[0];
        if (!p || 3 * i + 2 >= p.pos.length) return null;
        var v = new THREE.Vector3(p.pos[3 * i], p.pos[3 * i + 1], p.pos[3 * i + 2]).project(camera);
        var rect = renderer.domElement.getBoundingClientRect();
        return [rect.left + (v.x + 1) * 0.5 * rect.width, rect.top + (1 - v.y) * 0.5 * rect.height];
      }
    };

    controls.addEventListener('change', render);
    document.getElementById('conform-reset').addEventListener('click', function () { controls.reset(); render(); });
    Array.prototype.forEach.call(document.querySelectorAll('input[data-layer]'), function (box_input) {
      box_input.addEventListener('change', function () {
        objects[Number(box_input.getAttribute('data-layer'))].visible = box_input.checked;
        render();
      });
    });
    if (callout_box) callout_box.addEventListener('change', render);
    window.addEventListener('resize', function () {
      renderer.setSize(view.clientWidth, view.clientHeight);
      camera.aspect = view.clientWidth / view.clientHeight;
      camera.updateProjectionMatrix();
      render();
    });
    render();
    var r = renderer.domElement.getBoundingClientRect();
    body.setAttribute('data-view-rect', [Math.round(r.left + window.scrollX), Math.round(r.top + window.scrollY),
                                         Math.round(r.width), Math.round(r.height)].join(','));
    body.setAttribute('data-scene-drawn', String(objects.length));
    if (window.performance) body.setAttribute('data-render-ms', String(Math.round(performance.now() - t0)));
  }

  try { fill_json(); } catch (e) { body.setAttribute('data-json-error', String(e)); }
  if (!document.getElementById('conform-scene')) return;
  try {
    start();
  } catch (e) {
    body.setAttribute('data-scene-error', String(e && e.message || e));
    var view = document.getElementById('conform-view');
    view.textContent = '3D view unavailable: ' + (e && e.message || e) + ' (it needs WebGL)';
  }
})();
)js";
}

}  // namespace conform::html::detail
