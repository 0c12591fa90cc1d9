// Argil's session viewer: the page `argil view` writes. It reads the data
// embedded in the page (data.js), shows the surfaces (scene_view.js) before or
// at a frame of the timeline, coloured by signed deviation (colours.js), with
// the tool, its path, the contacts and the force plot (force_plot.js) in
// sync, and tells what a click picked. window.argilView is the test hook.

import * as THREE from "three";
import { loadViewData } from "./data.js";
import { deviationColour, legendGradient, mm, NEUTRAL } from "./colours.js";
import { ForcePlot } from "./force_plot.js";
import { SceneView } from "./scene_view.js";

const STYLE = `
body { margin: 0; font: 13px system-ui, sans-serif; color: #222; overflow: hidden; }
#view { position: absolute; inset: 0 0 140px 0; }
#panel { position: absolute; top: 8px; left: 8px; background: #fffd; padding: 8px 10px;
  border-radius: 6px; max-width: 330px; box-shadow: 0 1px 4px #0003; }
#panel h1 { font-size: 14px; margin: 0 0 6px; }
#panel label { display: block; margin: 2px 0; }
#legend { margin-top: 6px; }
#legend .bar { height: 10px; border-radius: 3px; }
#legend .ticks { display: flex; justify-content: space-between; font-size: 11px; }
#pick { position: absolute; top: 8px; right: 8px; background: #fffd; padding: 8px 10px;
  border-radius: 6px; width: 330px; box-shadow: 0 1px 4px #0003; font-size: 12px; }
#pick pre { white-space: pre-wrap; margin: 4px 0; font-size: 11px; }
#pick textarea { width: 100%; height: 64px; font-size: 11px; }
#bottom { position: absolute; left: 0; right: 0; bottom: 0; height: 140px; background: #1d2026;
  color: #ddd; display: flex; flex-direction: column; }
#timeline { display: flex; align-items: center; gap: 8px; padding: 4px 8px; }
#timeline input[type=range] { flex: 1; }
#frame-label { min-width: 300px; font-variant-numeric: tabular-nums; }
#force { flex: 1; width: 100%; }
`;

function element(tag, attributes = {}, parent = null) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attributes)) {
    if (k === "text") e.textContent = v;
    else e.setAttribute(k, v);
  }
  if (parent) parent.appendChild(e);
  return e;
}

function fixed(x, digits = 6) {
  return Number(x.toPrecision(digits));
}

class Viewer {
  constructor(data) {
    this.data = data;
    element("style", { text: STYLE }, document.head);
    const view = element("div", { id: "view" }, document.body);
    this.view = new SceneView(view, data);
    this.buildPanel();
    this.buildPick();
    this.buildTimeline();
    this.resolveFrames();
    this.deviations = this.computeDeviations();
    this.frame = Math.max(0, data.frames.length - 1);
    this.before = false;
    this.view.renderer.domElement.addEventListener("pointerdown", (e) => (this.down = e));
    this.view.renderer.domElement.addEventListener("pointerup", (e) => {
      // A click, not the end of an orbit drag.
      if (this.down && Math.hypot(e.clientX - this.down.clientX, e.clientY - this.down.clientY) < 4) {
        this.pick(e.clientX, e.clientY);
      }
    });
    this.update();
  }

  buildPanel() {
    const d = this.data;
    const panel = element("div", { id: "panel" }, document.body);
    element("h1", { text: d.title }, panel);
    element("div", {
      text: (d.run ? `eps ${mm(d.tolerance_mm)} · ` : "") + `${d.faces.length} faces · mm, Z up`,
    }, panel);
    const toggle = (id, text, checked, onChange) => {
      const label = element("label", {}, panel);
      const box = element("input", { type: "checkbox", id }, label);
      box.checked = checked;
      label.appendChild(document.createTextNode(" " + text));
      box.addEventListener("change", () => onChange(box.checked));
      return box;
    };
    if (d.frames.length) {
      this.beforeBox = toggle("before", "before (as loaded)", false, (on) => {
        this.before = on;
        this.update();
      });
    }
    this.colourBox = toggle("deviation", "signed deviation colours", true, () => this.update());
    if (!d.frames.length) this.colourBox.parentElement.style.display = "none";
    if (d.run) {
      toggle("show-path", "device path (orange: engaged)", true, (on) => {
        this.view.setVisible("path", on);
        this.view.render();
      });
      toggle("show-tool", "tool and contacts", true, (on) => {
        this.view.setVisible("tool", on);
        this.view.setVisible("contacts", on);
        this.view.render();
      });
    }
    const scaleLabel = element("label", { text: "scale [mm], empty = auto: " }, panel);
    this.scaleInput = element("input", { id: "scale", size: 7 }, scaleLabel);
    if (d.scale_mm) this.scaleInput.value = String(d.scale_mm);
    this.scaleInput.addEventListener("change", () => this.update());
    if (!d.frames.length) scaleLabel.style.display = "none";
    const legend = element("div", { id: "legend" }, panel);
    if (!d.frames.length) legend.style.display = "none";
    element("div", { class: "bar", style: `background: ${legendGradient()}` }, legend);
    const ticks = element("div", { class: "ticks" }, legend);
    this.legendLow = element("span", {}, ticks);
    element("span", { text: "0" }, ticks);
    this.legendHigh = element("span", {}, ticks);
    this.legendNote = element("div", { style: "font-size: 11px" }, legend);
    const fitButton = element("button", { text: "fit view" }, panel);
    fitButton.addEventListener("click", () => {
      this.view.fit();
      this.view.render();
    });
    if (d.frames.length) {
      const changeButton = element("button", { id: "focus-change", text: "zoom on the change" }, panel);
      changeButton.addEventListener("click", () => {
        const box = this.changedBox();
        if (box) this.view.fit(box);
        this.view.render();
      });
    }
  }

  buildPick() {
    const pick = element("div", { id: "pick" }, document.body);
    element("b", { text: "Click a surface" }, pick);
    this.pickText = element("pre", { id: "pick-text", text: "to read its face, (u, v), point and normal." }, pick);
    element("div", { text: "script keyframe (tool touching there):" }, pick);
    this.keyframeText = element("textarea", { id: "keyframe", readonly: "" }, pick);
    const copy = element("button", { text: "copy" }, pick);
    copy.addEventListener("click", () => this.copyKeyframe());
  }

  buildTimeline() {
    const bottom = element("div", { id: "bottom" }, document.body);
    if (!this.data.frames.length) {
      // A model file: no run to replay, the view takes the whole page.
      bottom.style.display = "none";
      document.getElementById("view").style.bottom = "0";
      this.view.resize();
      this.view.fit();
    }
    const bar = element("div", { id: "timeline" }, bottom);
    const frames = this.data.frames.length;
    this.play = element("button", { id: "play", text: "play" }, bar);
    this.slider = element("input", { id: "frame", type: "range", min: 0, max: Math.max(0, frames - 1), step: 1 }, bar);
    this.label = element("span", { id: "frame-label" }, bar);
    this.slider.disabled = frames === 0;
    this.play.disabled = frames < 2;
    this.slider.addEventListener("input", () => {
      this.frame = Number(this.slider.value);
      this.before = false;
      if (this.beforeBox) this.beforeBox.checked = false;
      this.update();
    });
    this.play.addEventListener("click", () => this.togglePlay());
    const canvas = element("canvas", { id: "force" }, bottom);
    if (this.data.run) {
      canvas.width = window.innerWidth;
      canvas.height = 104;
      this.forcePlot = new ForcePlot(canvas, this.data.run);
    }
  }

  togglePlay() {
    if (this.timer) {
      clearInterval(this.timer);
      this.timer = null;
      this.play.textContent = "play";
      return;
    }
    if (this.frame >= this.data.frames.length - 1) this.frame = 0;
    this.before = false;
    this.play.textContent = "pause";
    this.timer = setInterval(() => {
      this.frame += 1;
      if (this.frame >= this.data.frames.length - 1) {
        this.frame = this.data.frames.length - 1;
        this.togglePlay();
      }
      this.update();
    }, 80);
  }

  /// positions[f] of frame k for every face: a frame lists only the faces
  /// that changed since the one before it.
  resolveFrames() {
    let current = this.data.faces.map((f) => f.positions);
    this.framePositions = this.data.frames.map((frame) => {
      current = current.slice();
      for (const [key, positions] of Object.entries(frame.faces)) current[Number(key)] = positions;
      return current;
    });
  }

  /// Signed displacement of every vertex at every frame, along the outward
  /// normal before: (p - p_before) . n_before [mm]; and the largest |d|.
  computeDeviations() {
    let largest = 0;
    const perFrame = this.framePositions.map((faces) =>
      faces.map((positions, f) => {
        const face = this.data.faces[f];
        if (positions === face.positions) return null;
        const d = new Float32Array(positions.length / 3);
        for (let i = 0; i < d.length; ++i) {
          let s = 0;
          for (let c = 0; c < 3; ++c) s += (positions[3 * i + c] - face.positions[3 * i + c]) * face.normals[3 * i + c];
          d[i] = s;
          largest = Math.max(largest, Math.abs(s));
        }
        return d;
      })
    );
    this.largest = largest;
    return perFrame;
  }

  scale() {
    const fixedScale = parseFloat(this.scaleInput.value);
    return fixedScale > 0 ? fixedScale : this.largest;
  }

  update() {
    const d = this.data;
    const showing = this.before || !d.frames.length ? null : this.frame;
    const eps = d.tolerance_mm;
    const scale = this.scale();
    const colour = this.colourBox.checked && showing !== null && this.largest > eps;
    this.view.meshes.forEach((mesh, f) => {
      const face = d.faces[f];
      const positions = showing === null ? face.positions : this.framePositions[showing][f];
      const geometry = mesh.geometry;
      const position = geometry.getAttribute("position");
      if (mesh.userData.shown !== positions) {
        position.array.set(positions);
        position.needsUpdate = true;
        if (positions === face.positions) {
          geometry.getAttribute("normal").array.set(face.normals);
          geometry.getAttribute("normal").needsUpdate = true;
        } else {
          geometry.computeVertexNormals();
        }
        // Raycasting skips a mesh whose box the ray misses: keep it the frame's.
        geometry.computeBoundingBox();
        geometry.computeBoundingSphere();
        mesh.userData.shown = positions;
      }
      const deviation = showing === null ? null : this.deviations[showing][f];
      const colours = geometry.getAttribute("color");
      for (let i = 0; i < colours.count; ++i) {
        const rgb = colour && deviation ? deviationColour(deviation[i], scale, eps) : NEUTRAL;
        colours.setXYZ(i, rgb[0], rgb[1], rgb[2]);
      }
      colours.needsUpdate = true;
    });
    this.legendLow.textContent = colour ? "-" + mm(scale) + " (in)" : "";
    this.legendHigh.textContent = colour ? "+" + mm(scale) + " (out)" : "";
    this.legendNote.textContent =
      !d.frames.length ? "a model file: no run to compare"
      : this.largest <= eps ? `no change: no point moved more than eps (largest ${mm(this.largest)})`
      : `largest movement along the normal: ${mm(this.largest)}; within eps: uncoloured`;
    if (d.frames.length) {
      const frame = d.frames[this.frame];
      this.slider.value = String(this.frame);
      this.label.textContent = this.before
        ? "before: the surfaces as loaded"
        : `frame ${this.frame + 1}/${d.frames.length} · tick ${frame.tick} · t = ${fixed(frame.time, 4)} s · ${frame.kind}` +
          (d.tools.length > 1 ? ` · tool ${d.tools[d.run.tool[frame.tick]].name}` : "");
      this.view.showTick(frame.tick, frame.contacts);
      if (this.forcePlot) this.forcePlot.draw(frame.tick);
    }
    this.view.render();
  }

  /// What a click at (clientX, clientY) picked, shown in the pick panel; null
  /// when it missed every surface.
  pick(clientX, clientY) {
    const hit = this.view.hit(clientX, clientY);
    if (!hit) {
      this.pickText.textContent = "no surface there";
      this.lastPick = null;
      return null;
    }
    const face = this.data.faces[hit.face];
    const w = [hit.weights.x, hit.weights.y, hit.weights.z];
    const uv = [0, 1].map((c) => hit.vertices.reduce((s, v, i) => s + w[i] * face.uv[2 * v + c], 0));
    const normals = this.view.meshes[hit.face].geometry.getAttribute("normal").array;
    const n = [0, 1, 2].map((c) => hit.vertices.reduce((s, v, i) => s + w[i] * normals[3 * v + c], 0));
    const length = Math.hypot(...n) || 1;
    const normal = n.map((x) => x / length);
    const point = [hit.point.x, hit.point.y, hit.point.z];
    const model = this.data.models[face.model];
    this.lastPick = { model: model.name, face: face.face, faceIndex: hit.face, triangle: hit.triangle, name: face.name, u: uv[0], v: uv[1], point, normal };
    this.pickText.textContent =
      `model ${model.name}, face ${face.face} (${face.name})\n` +
      `(u, v) = (${fixed(uv[0])}, ${fixed(uv[1])})\n` +
      `point [mm] = (${point.map((x) => fixed(x)).join(", ")})\n` +
      `normal = (${normal.map((x) => fixed(x, 4)).join(", ")})`;
    // The tool held at the frame shown.
    const run = this.data.run;
    const held = run && this.data.frames.length ? run.tool[this.data.frames[this.frame].tick] : 0;
    const tool = this.data.tools[held];
    const reach = tool && tool.type === "sphere" ? tool.radius : 0;
    const at = point.map((x, c) => fixed(x + reach * normal[c]));
    const keyframe = { t: 0, position: at, event: "engage" };
    const command = this.data.script
      ? `argil script ${this.data.script.scene} my.json --model ${model.name} --face ${face.face} --uv "${fixed(uv[0])},${fixed(uv[1])}"` +
        (tool ? ` --tool ${tool.name}` : "")
      : "";
    this.keyframeText.value = JSON.stringify(keyframe) + (command ? "\n" + command : "");
    return this.lastPick;
  }

  /// The box of the vertices that moved by more than a tenth of the largest
  /// movement (and eps) at the last frame, grown by half; null if none did.
  changedBox() {
    const last = this.data.frames.length - 1;
    const floor = Math.max(0.1 * this.largest, this.data.tolerance_mm);
    const box = new THREE.Box3();
    this.deviations[last].forEach((d, f) => {
      if (!d) return;
      const p = this.framePositions[last][f];
      for (let i = 0; i < d.length; ++i) {
        if (Math.abs(d[i]) > floor) box.expandByPoint(new THREE.Vector3(p[3 * i], p[3 * i + 1], p[3 * i + 2]));
      }
    });
    if (box.isEmpty()) return null;
    return box.expandByScalar(0.5 * box.getSize(new THREE.Vector3()).length());
  }

  /// Face f's vertex positions as shown.
  shownPositions(f) {
    const showing = this.before || !this.data.frames.length ? null : this.frame;
    return showing === null ? this.data.faces[f].positions : this.framePositions[showing][f];
  }

  /// The vertex that moved in the most at the frame shown, or null.
  deepest() {
    if (this.before || !this.data.frames.length) return null;
    let best = null;
    this.deviations[this.frame].forEach((d, f) => {
      if (!d) return;
      for (let i = 0; i < d.length; ++i) {
        if (!best || d[i] < best.deviation) best = { face: f, index: i, deviation: d[i] };
      }
    });
    if (best) {
      const i = 3 * best.index;
      best.position = Array.from(this.shownPositions(best.face).subarray(i, i + 3));
      best.normal = Array.from(this.data.faces[best.face].normals.subarray(i, i + 3));
    }
    return best;
  }

  copyKeyframe() {
    this.keyframeText.select();
    if (navigator.clipboard) navigator.clipboard.writeText(this.keyframeText.value).catch(() => {});
    else document.execCommand("copy");
  }
}

function start() {
  try {
    const data = loadViewData(document.getElementById("argil-data"));
    const viewer = new Viewer(data);
    window.argilView = {
      ready: true,
      frameCount: () => data.frames.length,
      frame: () => viewer.frame,
      setFrame: (k) => {
        viewer.frame = k;
        viewer.before = false;
        viewer.update();
      },
      play: () => viewer.togglePlay(),
      playing: () => Boolean(viewer.timer),
      project: (p) => viewer.view.project(p),
      pick: (x, y) => viewer.pick(x, y),
      lastPick: () => viewer.lastPick || null,
      largestDeviation: () => viewer.largest,
      faces: () => data.faces.map((f) => ({ model: data.models[f.model].name, face: f.face, vertices: f.positions.length / 3 })),
      vertex: (f, i) => ({
        position: Array.from(viewer.shownPositions(f).subarray(3 * i, 3 * i + 3)),
        uv: [data.faces[f].uv[2 * i], data.faces[f].uv[2 * i + 1]],
      }),
      uvExtent: (f) => {
        const uv = data.faces[f].uv;
        const range = [0, 1].map((c) => {
          let lo = Infinity, hi = -Infinity;
          for (let i = c; i < uv.length; i += 2) {
            lo = Math.min(lo, uv[i]);
            hi = Math.max(hi, uv[i]);
          }
          return hi - lo;
        });
        return range;
      },
      size: () => viewer.view.size,
      eye: () => viewer.view.camera.position.toArray(),
      triangleCount: (f) => data.faces[f].indices.length / 3,
      triangle: (f, t) => {
        const corners = Array.from(data.faces[f].indices.subarray(3 * t, 3 * t + 3));
        const p = viewer.shownPositions(f);
        return {
          positions: corners.map((i) => Array.from(p.subarray(3 * i, 3 * i + 3))),
          uv: corners.map((i) => [data.faces[f].uv[2 * i], data.faces[f].uv[2 * i + 1]]),
        };
      },
      deepest: () => viewer.deepest(),
      fit: () => {
        viewer.view.fit();
        viewer.view.render();
      },
      lookAt: (point, normal) => {
        viewer.view.lookAt(point, normal);
        viewer.view.render();
      },
    };
  } catch (error) {
    document.body.textContent = "argil view: cannot show this page: " + error.message;
    window.argilView = { ready: false, error: String(error.message) };
  }
}

start();
