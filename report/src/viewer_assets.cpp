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
svg.plot{width:100%;max-width:720px;height:auto;font-size:11px;display:block}
svg.colour-bar{width:165px;height:auto;font-size:11px}
svg .grid{stroke:#e4e6ea}svg .frame{fill:none;stroke:#444}svg .title{font-weight:bold;font-size:12px}
svg .line{fill:none;stroke-width:1.6}svg .band{fill:#2ca02c;fill-opacity:.14}svg .band-label{fill:#1d6b1d}
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
    var box = new THREE.Box3(), objects = [];
    data.objects.forEach(function (o) {
      var object = make_object(o);
      object.visible = o.visible;
      scene.add(object);
      objects.push(object);
      if (o.count > 0) box.expandByObject(object);
    });
    var sphere = box.isEmpty() ? new THREE.Sphere(new THREE.Vector3(), 1) : box.getBoundingSphere(new THREE.Sphere());
    var radius = Math.max(sphere.radius, 1e-6);
    var distance = 1.15 * radius / Math.sin(THREE.MathUtils ? THREE.MathUtils.degToRad(17.5) : 0.3054);
    camera.near = distance / 1000;
    camera.far = distance + 20 * radius;
    camera.position.copy(sphere.center).add(new THREE.Vector3(0.55, -0.75, 0.45).normalize().multiplyScalar(distance));
    camera.updateProjectionMatrix();
    var controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.target.copy(sphere.center);
    controls.screenSpacePanning = true;
    controls.update();
    controls.saveState();
    function render() { renderer.render(scene, camera); }
    controls.addEventListener('change', render);
    document.getElementById('conform-reset').addEventListener('click', function () { controls.reset(); render(); });
    Array.prototype.forEach.call(document.querySelectorAll('input[data-layer]'), function (box_input) {
      box_input.addEventListener('change', function () {
        objects[Number(box_input.getAttribute('data-layer'))].visible = box_input.checked;
        render();
      });
    });
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
