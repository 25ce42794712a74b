#include "compare/replay.hpp"

#include "compare/escape.hpp"
#include "compare/report.hpp"
#include "compare/results.hpp"
#include "core/error.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <sstream>

#ifndef GACOMPARE_THREE_JS
#define GACOMPARE_THREE_JS "/usr/share/javascript/three/three.min.js"
#endif

namespace gacompare::compare {

namespace {
using json = nlohmann::ordered_json;

std::string g17(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

// Text placed inside a <script> element: "</" could close it (a scene name
// "</script>" would), and "<\/" means the same in JSON and in JavaScript strings.
std::string script_safe(std::string text) {
  for (std::size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3)) text.replace(at, 2, "<\\/");
  return text;
}

std::string read_three_js() {
  const std::filesystem::path file = three_js_path();
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in || text.str().empty())
    throw run_error(file.string() + ": cannot read three.js for replay.html (scripts/install-deps.sh installs libjs-three)");
  return script_safe(text.str());
}

// The page's data: frame times, the bodies' meshes, particles and constraints
// (results.json's scene record), and per backend one flat array per frame:
// x, y, z, qw, qx, qy, qz per body, then x, y, z per particle.
json replay_data(const SceneResult& r, const std::vector<std::size_t>& frames) {
  const json scene = scene_json(r.scene, *r.model);
  json times = json::array();
  const auto& first = r.backends.empty() ? std::vector<core::Sample>{} : r.backends.front().run.samples;
  for (const std::size_t k : frames) times.push_back(first[k].t);
  json backends = json::array();
  for (const auto& b : r.backends) {
    json states = json::array();
    for (const std::size_t k : frames) {
      json flat = json::array();
      if (k < b.run.samples.size()) {
        const core::Sample& s = b.run.samples[k];
        for (const auto& body : s.bodies) {
          for (int i = 0; i < 3; ++i) flat.push_back(body.position[i]);
          for (int i = 0; i < 4; ++i) flat.push_back(body.orientation[i]);
        }
        for (const auto& p : s.particles)
          for (int i = 0; i < 3; ++i) flat.push_back(p.position[i]);
      }
      states.push_back(flat);  // empty after a run that stopped early: nothing drawn there
    }
    backends.push_back({{"name", b.run.backend}, {"frames", states}, {"error", b.run.error.value_or("")}});
  }
  return {{"scene", r.scene.name},
          {"times", times},
          {"samples", first.size()},
          {"bodies", scene["bodies"]},
          {"particles", scene["particles"]},
          {"constraints", scene["constraints"]},
          {"backends", backends}};
}

// The viewer: plain three.js (r111, Debian's libjs-three; no module build, no
// examples, so the camera's orbit is written here).
constexpr const char* kViewer = R"JS(
(function () {
  "use strict";
  const data = JSON.parse(document.getElementById("replay-data").textContent);
  const nb = data.bodies.length, np = data.particles.length, nf = data.times.length;
  if (!nf) {
    document.getElementById("views").textContent = "No samples were recorded: nothing to replay.";
    return;
  }
  const palette = [0xd1495b, 0x2e86ab, 0xedae49, 0x66a182, 0x8f5dc2, 0xf17f29, 0x00798c, 0xc2185b];
  const colour = (i) => palette[i % palette.length];

  // The box every backend's every frame of what moves fits in (static bodies
  // only where nothing moves: a slab or a wall would make a falling cube a
  // speck): the camera's target and distance.
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  const grow = (x, y, z, r) => {
    const p = [x, y, z];
    for (let i = 0; i < 3; ++i) { lo[i] = Math.min(lo[i], p[i] - r); hi[i] = Math.max(hi[i], p[i] + r); }
  };
  const moving = data.bodies.some((b) => !b.static) || np > 0;
  for (const b of data.backends)
    for (const f of b.frames) {
      if (!f.length) continue;
      for (let i = 0; i < nb; ++i)
        if (!moving || !data.bodies[i].static) grow(f[7 * i], f[7 * i + 1], f[7 * i + 2], data.bodies[i].radius);
      for (let i = 0; i < np; ++i) grow(f[7 * nb + 3 * i], f[7 * nb + 3 * i + 1], f[7 * nb + 3 * i + 2], 0);
    }
  if (!isFinite(lo[0])) { lo.fill(-1); hi.fill(1); }
  const centre = new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
  const size = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-3);
  const dot = size / 80;  // a particle's drawn radius

  const camera = { azimuth: -0.9, elevation: 0.45, distance: 1.5 * size, orbit: true };
  const views = [];
  const container = document.getElementById("views");

  function makeView(backend) {
    const figure = document.createElement("figure");
    figure.className = "view";
    figure.dataset.backend = backend.name;
    const canvas = document.createElement("canvas");
    const caption = document.createElement("figcaption");
    caption.textContent = backend.name + (backend.error ? " (stopped early: " + backend.error + ")" : "");
    figure.appendChild(canvas);
    figure.appendChild(caption);
    container.appendChild(figure);
    const renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: true, preserveDrawingBuffer: true });
    renderer.setClearColor(0xffffff, 1);
    const scene = new THREE.Scene();
    scene.add(new THREE.HemisphereLight(0xffffff, 0x777777, 0.75));
    const sun = new THREE.DirectionalLight(0xffffff, 0.55);
    scene.add(sun);
    const cam = new THREE.PerspectiveCamera(40, 1, size / 1000, size * 100);
    cam.up.set(0, 0, 1);
    const grid = new THREE.GridHelper(2 * size, 20, 0x999999, 0xdddddd);
    grid.rotation.x = Math.PI / 2;  // the x-y plane: z is up (gravity along −z)
    grid.position.set(centre.x, centre.y, lo[2]);
    scene.add(grid);
    const bodies = data.bodies.map((b, i) => {
      const g = new THREE.BufferGeometry();
      g.setAttribute("position", new THREE.Float32BufferAttribute(b.vertices.flat(), 3));
      g.setIndex(b.triangles.flat());
      g.computeVertexNormals();
      // Static bodies (walls, slabs) see-through, so they hide nothing that moves.
      const m = new THREE.Mesh(g, new THREE.MeshLambertMaterial({
        color: b.static ? 0xb0b0b0 : colour(i), flatShading: true, polygonOffset: true,
        polygonOffsetFactor: 1, polygonOffsetUnits: 1, transparent: b.static, opacity: b.static ? 0.18 : 1,
        depthWrite: !b.static }));
      m.add(new THREE.LineSegments(new THREE.EdgesGeometry(g, 1), new THREE.LineBasicMaterial({ color: 0x333333 })));
      scene.add(m);
      return m;
    });
    const sphere = new THREE.SphereBufferGeometry(dot, 16, 12);
    const particles = data.particles.map((p, i) => {
      const m = new THREE.Mesh(sphere, new THREE.MeshLambertMaterial({ color: colour(i) }));
      scene.add(m);
      return m;
    });
    // Each particle's recorded path over the whole run, faint.
    for (let i = 0; i < np; ++i) {
      const pts = [];
      for (const f of backend.frames)
        if (f.length) pts.push(f[7 * nb + 3 * i], f[7 * nb + 3 * i + 1], f[7 * nb + 3 * i + 2]);
      const g = new THREE.BufferGeometry();
      g.setAttribute("position", new THREE.Float32BufferAttribute(pts, 3));
      scene.add(new THREE.Line(g, new THREE.LineBasicMaterial({ color: colour(i), transparent: true, opacity: 0.35 })));
    }
    // Rods: a distance constraint between two particles or to a fixed point.
    const index = new Map(data.particles.map((n, i) => [n, i]));
    const rods = data.constraints.filter((c) => c.type === "distance" || c.type === "distance_to_point");
    const rodGeometry = new THREE.BufferGeometry();
    rodGeometry.setAttribute("position", new THREE.Float32BufferAttribute(new Array(6 * rods.length).fill(0), 3));
    scene.add(new THREE.LineSegments(rodGeometry, new THREE.LineBasicMaterial({ color: 0x444444 })));
    const view = { backend: backend.name, canvas, renderer, scene, cam, sun, bodies, particles };
    view.place = function (k) {
      const f = backend.frames[k];
      const shown = f.length > 0;
      bodies.forEach((m, i) => {
        m.visible = shown;
        if (!shown) return;
        m.position.set(f[7 * i], f[7 * i + 1], f[7 * i + 2]);
        m.quaternion.set(f[7 * i + 4], f[7 * i + 5], f[7 * i + 6], f[7 * i + 3]).normalize();  // three.js: x, y, z, w
      });
      const at = (n) => 7 * nb + 3 * index.get(n);
      particles.forEach((m, i) => {
        m.visible = shown;
        if (shown) m.position.set(f[7 * nb + 3 * i], f[7 * nb + 3 * i + 1], f[7 * nb + 3 * i + 2]);
      });
      const pos = rodGeometry.attributes.position;
      rods.forEach((c, j) => {
        if (!shown) return;
        const a = at(c.particles[0]);
        pos.setXYZ(2 * j, f[a], f[a + 1], f[a + 2]);
        if (c.type === "distance") {
          const b = at(c.particles[1]);
          pos.setXYZ(2 * j + 1, f[b], f[b + 1], f[b + 2]);
        } else {
          pos.setXYZ(2 * j + 1, c.point[0], c.point[1], c.point[2]);
        }
      });
      pos.needsUpdate = true;
    };
    views.push(view);
    return view;
  }
  data.backends.forEach(makeView);

  const slider = document.getElementById("frame"), clock = document.getElementById("clock");
  const play = document.getElementById("play"), orbit = document.getElementById("orbit");
  slider.max = String(nf - 1);
  let frame = 0, playing = nf > 1, simTime = 0, last = null;

  function resize() {
    for (const v of views) {
      const w = v.canvas.clientWidth, h = v.canvas.clientHeight;
      if (v.canvas.width !== w || v.canvas.height !== h) {
        v.renderer.setSize(w, h, false);
        v.cam.aspect = w / h;
        v.cam.updateProjectionMatrix();
      }
    }
  }
  function draw() {
    resize();
    const ce = Math.cos(camera.elevation), se = Math.sin(camera.elevation);
    for (const v of views) {
      v.cam.position.set(centre.x + camera.distance * ce * Math.cos(camera.azimuth),
                         centre.y + camera.distance * ce * Math.sin(camera.azimuth),
                         centre.z + camera.distance * se);
      v.cam.lookAt(centre);
      v.sun.position.copy(v.cam.position);
      v.place(frame);
      v.renderer.render(v.scene, v.cam);
    }
    slider.value = String(frame);
    clock.textContent = "t = " + data.times[frame].toFixed(3) + " s (sample " + (frame + 1) + " of " + nf + ")";
  }
  function show(k) {
    frame = Math.max(0, Math.min(nf - 1, k | 0));
    simTime = data.times[frame];
    draw();
  }
  function pause() { playing = false; play.textContent = "play"; }
  function frameAt(t) {  // the last frame at or before t
    let a = 0, b = nf - 1;
    while (a < b) { const m = (a + b + 1) >> 1; if (data.times[m] <= t) a = m; else b = m - 1; }
    return a;
  }
  play.onclick = () => {
    playing = !playing;
    play.textContent = playing ? "pause" : "play";
    if (playing && frame === nf - 1) show(0);
    last = null;
  };
  slider.oninput = () => { pause(); show(Number(slider.value)); };
  orbit.onchange = () => { camera.orbit = orbit.checked; };
  let drag = null;
  container.addEventListener("pointerdown", (e) => { drag = [e.clientX, e.clientY]; camera.orbit = orbit.checked = false; });
  window.addEventListener("pointerup", () => { drag = null; });
  window.addEventListener("pointermove", (e) => {
    if (!drag) return;
    camera.azimuth -= (e.clientX - drag[0]) * 0.01;
    camera.elevation = Math.max(-1.5, Math.min(1.5, camera.elevation + (e.clientY - drag[1]) * 0.01));
    drag = [e.clientX, e.clientY];
    draw();
  });
  container.addEventListener("wheel", (e) => {
    e.preventDefault();
    camera.distance *= Math.exp(e.deltaY * 0.001);
    draw();
  }, { passive: false });
  function tick(now) {
    if (last !== null) {
      const dt = (now - last) / 1000;
      if (camera.orbit) camera.azimuth += 0.25 * dt;
      if (playing) {
        simTime += dt * Number(document.getElementById("speed").value);
        if (simTime >= data.times[nf - 1]) { simTime = data.times[nf - 1]; pause(); }
        frame = frameAt(simTime);
      }
      if (playing || camera.orbit) draw();
    }
    last = now;
    requestAnimationFrame(tick);
  }
  const hash = /#t=([0-9.eE+-]+)/.exec(location.hash);
  if (hash) { pause(); camera.orbit = orbit.checked = false; show(frameAt(Number(hash[1]))); } else show(0);
  if (!playing) play.textContent = "play";
  requestAnimationFrame(tick);
  window.replay = { frames: nf, times: data.times, views: views, show: show, pause: pause,
                    stopOrbit: () => { camera.orbit = orbit.checked = false; } };
})();
)JS";

constexpr const char* kStyle =
    "body{font-family:sans-serif;margin:1em 2em;color:#222}#views{display:flex;gap:1em;flex-wrap:wrap}"
    ".view{flex:1 1 300px;margin:0}.view canvas{width:100%;height:60vh;min-height:320px;display:block;"
    "border:1px solid #ccc;touch-action:none}figcaption{text-align:center;font-weight:bold;margin:.3em}"
    "#controls{display:flex;gap:1em;align-items:center;margin:1em 0}#frame{flex:1}";

}  // namespace

std::filesystem::path three_js_path() { return GACOMPARE_THREE_JS; }

std::vector<std::size_t> replay_frames(std::size_t samples, std::size_t max_frames) {
  std::vector<std::size_t> out;
  if (samples == 0) return out;
  // ⌈(n − 1) / (max − 2)⌉: at most max − 1 frames on the stride, and the last.
  const std::size_t stride = samples <= max_frames || max_frames < 3 ? 1 : (samples - 2) / (max_frames - 2) + 1;
  for (std::size_t k = 0; k < samples; k += stride) out.push_back(k);
  if (out.back() != samples - 1) out.push_back(samples - 1);
  return out;
}

std::string trajectories_csv(const SceneResult& r) {
  std::ostringstream o;
  o << "t,backend,kind,name,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
  for (const auto& b : r.backends)
    for (const auto& s : b.run.samples) {
      const std::string head = g17(s.t) + "," + csv_field(b.run.backend) + ",";
      for (std::size_t i = 0; i < s.bodies.size(); ++i) {
        const auto& x = s.bodies[i];
        o << head << "body," << csv_field(r.scene.bodies[i].name);
        for (int k = 0; k < 3; ++k) o << "," << g17(x.position[k]);
        for (int k = 0; k < 4; ++k) o << "," << g17(x.orientation[k]);
        for (int k = 0; k < 3; ++k) o << "," << g17(x.velocity[k]);
        for (int k = 0; k < 3; ++k) o << "," << g17(x.angular_velocity[k]);
        o << "\n";
      }
      for (std::size_t i = 0; i < s.particles.size(); ++i) {
        const auto& x = s.particles[i];
        o << head << "particle," << csv_field(r.scene.particles[i].name);
        for (int k = 0; k < 3; ++k) o << "," << g17(x.position[k]);
        o << ",,,,";
        for (int k = 0; k < 3; ++k) o << "," << g17(x.velocity[k]);
        o << ",,,\n";
      }
    }
  return o.str();
}

std::string replay_html(const SceneResult& r) {
  const std::size_t samples = r.backends.empty() ? 0 : r.backends.front().run.samples.size();
  const auto frames = replay_frames(samples);
  const std::string three = read_three_js();
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" << html_escape(r.scene.name)
    << " — replay</title>\n<style>" << kStyle << "</style></head><body>\n<h1>" << html_escape(r.scene.name)
    << ": the recorded motion</h1>\n<p>" << html_escape(r.scene.description) << "</p>\n<p>Each backend's run as "
    << "results.json samples it (every " << r.scene.output_every << " s; " << frames.size() << " of " << samples
    << " samples shown" << (frames.size() < samples ? ", every " + std::to_string(frames[1]) + "th and the last" : "")
    << "), side by side from one camera: drag to turn it, scroll to zoom. Samples are shown as recorded, not "
       "interpolated. <a href=\"report.html\">The report</a> · <code>trajectories.csv</code> holds every sample.</p>\n"
    << "<div id=\"controls\"><button id=\"play\">pause</button><input id=\"frame\" type=\"range\" min=\"0\" value=\"0\" "
       "step=\"1\"><span id=\"clock\"></span><label>speed <select id=\"speed\"><option value=\"0.25\">¼×</option>"
       "<option value=\"1\" selected>1×</option><option value=\"4\">4×</option></select></label>"
       "<label><input id=\"orbit\" type=\"checkbox\" checked> orbit</label></div>\n<div id=\"views\"></div>\n"
    << "<script>" << three << "</script>\n<script type=\"application/json\" id=\"replay-data\">"
    << json_for_script(replay_data(r, frames).dump()) << "</script>\n<script>" << kViewer << "</script>\n</body></html>\n";
  return o.str();
}

}  // namespace gacompare::compare
