// The toolpath in 3D: rapids dashed in one colour, feeds coloured by workingstep, the tool at
// the current segment, markers for verify findings. Orbit (left drag), pan (right drag), zoom
// (wheel), keyboard (arrows pan when the canvas has focus), fit to the part.
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

export const RAPID_COLOR = 0xd62728; // red, never used for a workingstep
// Workingstep colours: distinct, none of them red, all readable on the light background.
export const WORKINGSTEP_COLORS = [
  0x1f77b4, 0x2ca02c, 0x9467bd, 0x8c564b, 0xe377c2, 0x17becf, 0xbcbd22, 0x7f7f7f, 0xff7f0e, 0x393b79,
];
const DIMMED = new THREE.Color(0xd0d0d0);
export const STOCK_COLOR = 0x6b6b6b; // the workpiece's BLOCK, thin grey edges
const OUTSIDE_WORKINGSTEP = 0x555555;

// A growable buffer of line pieces (2 vertices each) that goes to the GPU piece by piece: a
// geometry is made once per capacity, and each flush uploads only what was added since the
// last (re-uploading everything a few times a second stalls the main thread on large programs).
class PieceBuffer {
  constructor(withColor, withDistance) {
    this.withColor = withColor;
    this.withDistance = withDistance;
    this.allocate(2 * 4096);
    this.vertices = 0;
    this.uploaded = 0;
    this.geometry = null;
  }
  allocate(capacity) {
    const grow = (old, size) => {
      const next = new Float32Array(size);
      if (old) next.set(old);
      return next;
    };
    this.capacity = capacity;
    this.positions = grow(this.positions, capacity * 3);
    if (this.withColor) this.colors = grow(this.colors, capacity * 3);
    // Dashes: each piece measures its own length from 0 (the pattern restarts per piece).
    if (this.withDistance) this.distances = grow(this.distances, capacity);
    this.geometry = null; // a new capacity needs a new geometry
  }
  push(x0, y0, z0, x1, y1, z1, color) {
    if (this.vertices + 2 > this.capacity) this.allocate(this.capacity * 2);
    const p = this.positions;
    const v = this.vertices;
    const i = v * 3;
    p[i] = x0; p[i + 1] = y0; p[i + 2] = z0;
    p[i + 3] = x1; p[i + 4] = y1; p[i + 5] = z1;
    if (this.withColor) {
      const c = this.colors;
      c[i] = c[i + 3] = color.r;
      c[i + 1] = c[i + 4] = color.g;
      c[i + 2] = c[i + 5] = color.b;
    }
    if (this.withDistance) {
      this.distances[v] = 0;
      this.distances[v + 1] = Math.hypot(x1 - x0, y1 - y0, z1 - z0);
    }
    this.vertices += 2;
  }
  // The geometry with everything pushed so far marked for upload; `fresh` says it is new.
  sync() {
    let fresh = false;
    const attributes = [["position", this.positions, 3]];
    if (this.withColor) attributes.push(["color", this.colors, 3]);
    if (this.withDistance) attributes.push(["lineDistance", this.distances, 1]);
    if (!this.geometry) {
      this.geometry = new THREE.BufferGeometry();
      for (const [name, array, size] of attributes) {
        this.geometry.setAttribute(name, new THREE.BufferAttribute(array, size).setUsage(THREE.DynamicDrawUsage));
      }
      this.uploaded = 0;
      fresh = true;
    } else if (this.vertices > this.uploaded) {
      for (const [name, , size] of attributes) {
        const attribute = this.geometry.getAttribute(name);
        attribute.clearUpdateRanges();
        attribute.addUpdateRange(this.uploaded * size, (this.vertices - this.uploaded) * size);
        attribute.needsUpdate = true;
      }
    }
    this.uploaded = this.vertices;
    this.geometry.setDrawRange(0, this.vertices);
    return fresh;
  }
  // After a change anywhere in the colours (highlighting): upload them all once.
  colorsChanged() {
    if (!this.geometry) return;
    const attribute = this.geometry.getAttribute("color");
    attribute.clearUpdateRanges();
    attribute.needsUpdate = true;
  }
}

export class ToolpathView {
  constructor(canvas) {
    this.canvas = canvas;
    // preserveDrawingBuffer: the browser test reads pixels back; antialias off keeps the
    // rapid and feed colours exact for that check.
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: false, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(1);
    this.renderer.setClearColor(0xffffff);
    this.scene = new THREE.Scene();
    this.scene.up = new THREE.Vector3(0, 0, 1);
    this.camera = new THREE.PerspectiveCamera(45, 1, 0.1, 1e6);
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(200, -200, 200);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.listenToKeyEvents(canvas);
    this.controls.addEventListener("change", () => this.requestRender());
    this.rapidMaterial = new THREE.LineDashedMaterial({ color: RAPID_COLOR, dashSize: 2, gapSize: 1.5 });
    this.feedMaterial = new THREE.LineBasicMaterial({ vertexColors: true });
    this.highlightMaterial = new THREE.LineBasicMaterial({ color: 0x000000 });
    this.markerMaterial = new THREE.MeshBasicMaterial({ color: 0xff00ff });
    this.stockMaterial = new THREE.LineBasicMaterial({ color: STOCK_COLOR });
    this.stock = new THREE.Group();
    this.scene.add(this.stock);
    this.tool = this.makeTool();
    this.scene.add(this.tool);
    this.markers = new THREE.Group();
    this.scene.add(this.markers);
    this.reset();
    this.warmUp();
    new ResizeObserver(() => this.resize()).observe(canvas.parentElement);
    this.resize();
  }

  // Compiles every shader once at start-up: the first compile takes hundreds of ms with a
  // software GL, and it would otherwise fall into the first frame of a program being loaded.
  warmUp() {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(6), 3));
    geometry.setAttribute("color", new THREE.BufferAttribute(new Float32Array(6), 3));
    geometry.setAttribute("lineDistance", new THREE.BufferAttribute(new Float32Array(2), 1));
    const probes = [this.rapidMaterial, this.feedMaterial, this.highlightMaterial, this.stockMaterial].map((material) => new THREE.LineSegments(geometry, material));
    const sphere = new THREE.Mesh(new THREE.SphereGeometry(1), this.markerMaterial);
    const group = new THREE.Group();
    group.add(...probes, sphere);
    this.scene.add(group);
    this.tool.visible = true;
    this.renderer.compile(this.scene, this.camera);
    this.renderer.render(this.scene, this.camera);
    this.tool.visible = false;
    this.scene.remove(group);
    sphere.geometry.dispose();
    geometry.dispose();
  }

  makeTool() {
    const geometry = new THREE.ConeGeometry(2, 8, 16);
    geometry.rotateX(-Math.PI / 2); // tip along -Z
    geometry.translate(0, 0, 4);
    const tool = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({ color: 0xffa500, transparent: true, opacity: 0.8 }));
    tool.visible = false;
    return tool;
  }

  reset() {
    for (const object of [this.rapidLines, this.feedLines, this.highlightLines, this.workingstepLines]) {
      if (object) {
        this.scene.remove(object);
        object.geometry.dispose();
      }
    }
    this.rapids = new PieceBuffer(false, true);
    this.feeds = new PieceBuffer(true, false);
    // Per segment: which buffer and where its pieces are, so a segment can be highlighted.
    this.segmentStart = [];
    this.segmentCount = [];
    this.segmentRapid = [];
    this.segmentWorkingstep = [];
    this.segmentEnd = [];
    this.box = new THREE.Box3();
    this.rapidLines = this.feedLines = this.highlightLines = this.workingstepLines = null;
    this.tool.visible = false;
    this.markers.clear();
    for (const box of this.stock.children) box.geometry.dispose();
    this.stock.clear();
    this.selectedWorkingstep = -1;
    this.requestRender();
  }

  workingstepColor(index) {
    return new THREE.Color(index < 0 ? OUTSIDE_WORKINGSTEP : WORKINGSTEP_COLORS[index % WORKINGSTEP_COLORS.length]);
  }

  // One motion call's pieces, in order; `rapid` pieces go to the dashed set.
  addSegment(pieces, rapid, workingstep, end) {
    const buffer = rapid ? this.rapids : this.feeds;
    const color = rapid ? null : this.workingstepColor(workingstep);
    this.segmentStart.push(buffer.vertices);
    this.segmentRapid.push(rapid);
    this.segmentWorkingstep.push(workingstep);
    this.segmentEnd.push(end);
    for (let i = 0; i < pieces.length; i += 7) {
      const target = pieces[i + 6] ? this.rapids : this.feeds;
      target.push(pieces[i], pieces[i + 1], pieces[i + 2], pieces[i + 3], pieces[i + 4], pieces[i + 5],
        target === this.feeds ? (color || this.workingstepColor(workingstep)) : null);
      const { min, max } = this.box;
      min.x = Math.min(min.x, pieces[i + 3]); max.x = Math.max(max.x, pieces[i + 3]);
      min.y = Math.min(min.y, pieces[i + 4]); max.y = Math.max(max.y, pieces[i + 4]);
      min.z = Math.min(min.z, pieces[i + 5]); max.z = Math.max(max.z, pieces[i + 5]);
    }
    this.segmentCount.push(buffer.vertices - this.segmentStart[this.segmentStart.length - 1]);
  }

  get segments() {
    return this.segmentStart.length;
  }

  // Puts the pieces gathered so far on screen (called about once a second while loading).
  flush() {
    const show = (buffer, material, old) => {
      if (!buffer.sync() && old) return old;
      if (old) {
        this.scene.remove(old);
        old.geometry.dispose();
      }
      const lines = new THREE.LineSegments(buffer.geometry, material);
      lines.frustumCulled = false;
      this.scene.add(lines);
      return lines;
    };
    this.rapidLines = show(this.rapids, this.rapidMaterial, this.rapidLines);
    this.feedLines = show(this.feeds, this.feedMaterial, this.feedLines);
    this.scaleDashes();
    this.requestRender();
  }

  scaleDashes() {
    const size = this.box.isEmpty() ? 100 : this.box.getSize(new THREE.Vector3()).length();
    this.rapidMaterial.dashSize = size / 150;
    this.rapidMaterial.gapSize = size / 200;
  }

  fit() {
    if (this.box.isEmpty()) return;
    const centre = this.box.getCenter(new THREE.Vector3());
    const radius = Math.max(this.box.getSize(new THREE.Vector3()).length() / 2, 1);
    const distance = radius / Math.sin((this.camera.fov * Math.PI) / 360);
    const direction = new THREE.Vector3(1, -1.4, 1.1).normalize();
    this.camera.position.copy(centre).addScaledVector(direction, distance);
    this.camera.near = distance / 1000;
    this.camera.far = distance * 10;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(centre);
    this.controls.update();
    const toolScale = radius / 40;
    this.tool.scale.setScalar(toolScale);
    this.markerSize = radius / 30;
    this.requestRender();
  }

  // Feeds of one workingstep in their colour, the rest grey; -1 shows all in colour again.
  // Returns how many segments are highlighted.
  highlightWorkingstep(index) {
    this.selectedWorkingstep = index;
    const colors = this.feeds.colors;
    let count = 0;
    for (let s = 0; s < this.segments; s++) {
      const own = this.segmentWorkingstep[s];
      if (own === index) count++;
      if (this.segmentRapid[s]) continue;
      const color = index < 0 || own === index ? this.workingstepColor(own) : DIMMED;
      const from = this.segmentStart[s] * 3;
      const to = from + this.segmentCount[s] * 3;
      for (let i = from; i < to; i += 3) {
        colors[i] = color.r;
        colors[i + 1] = color.g;
        colors[i + 2] = color.b;
      }
    }
    this.feeds.colorsChanged();
    this.workingstepLines = this.replaceOverlay(this.workingstepLines,
      index < 0 ? [] : this.segmentWorkingstep.flatMap((own, s) => (own === index ? [s] : [])));
    this.requestRender();
    return count;
  }

  // Replaces an overlay (black lines over the given segments); returns the new one or null.
  replaceOverlay(old, segments) {
    if (old) {
      this.scene.remove(old);
      old.geometry.dispose();
    }
    if (segments.length === 0) return null;
    let vertices = 0;
    for (const s of segments) vertices += this.segmentCount[s];
    const positions = new Float32Array(vertices * 3);
    let at = 0;
    for (const s of segments) {
      const buffer = this.segmentRapid[s] ? this.rapids : this.feeds;
      const from = this.segmentStart[s] * 3;
      positions.set(buffer.positions.subarray(from, from + this.segmentCount[s] * 3), at);
      at += this.segmentCount[s] * 3;
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
    const lines = new THREE.LineSegments(geometry, this.highlightMaterial);
    lines.frustumCulled = false;
    this.scene.add(lines);
    return lines;
  }

  // Draws segment `s` in black and puts the tool at its end.
  markSegment(s) {
    const valid = s >= 0 && s < this.segments;
    this.highlightLines = this.replaceOverlay(this.highlightLines, valid ? [s] : []);
    if (!valid) {
      this.tool.visible = false;
      this.requestRender();
      return;
    }
    const end = this.segmentEnd[s];
    this.tool.position.set(end[0], end[1], end[2]);
    this.tool.visible = true;
    this.requestRender();
  }

  // The stock: each box's twelve edges from its eight corners (corner k is the origin plus x if
  // k & 1, y if k & 2, z if k & 4: the JSON trace's "stock"). Part of what Fit frames.
  showStock(boxes) {
    for (const box of boxes) {
      const c = box.corners;
      const positions = [];
      for (let k = 0; k < 8; k++) {
        for (const bit of [1, 2, 4]) {
          if (k & bit) continue;
          positions.push(...c[k], ...c[k | bit]);
        }
      }
      for (const p of c) this.box.expandByPoint(new THREE.Vector3(p[0], p[1], p[2]));
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute("position", new THREE.Float32BufferAttribute(positions, 3));
      this.stock.add(new THREE.LineSegments(geometry, this.stockMaterial));
    }
    this.requestRender();
  }

  // Verify findings where they are: a sphere per finding with a position.
  showFindings(points) {
    this.markers.clear();
    const size = this.markerSize || 2;
    const geometry = new THREE.SphereGeometry(size, 12, 8);
    for (const p of points) {
      const marker = new THREE.Mesh(geometry, this.markerMaterial);
      marker.position.set(p[0], p[1], p[2]);
      this.markers.add(marker);
    }
    this.requestRender();
  }

  resize() {
    const parent = this.canvas.parentElement;
    const width = Math.max(parent.clientWidth, 1);
    const height = Math.max(parent.clientHeight, 1);
    this.renderer.setSize(width, height, false);
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  requestRender() {
    if (this.renderPending) return;
    this.renderPending = true;
    requestAnimationFrame(() => {
      this.renderPending = false;
      this.renderer.render(this.scene, this.camera);
      this.canvas.dataset.frames = String(Number(this.canvas.dataset.frames || 0) + 1);
    });
  }
}
