// Reads the canonical trace into motion segments for the 3D view: the JSON trace (docs/canon.md,
// "The JSON trace"; POST /v1/traces?format=json), one record at a time, which is what the page
// uses, or the text trace line by line. Pure: no DOM, no three.js, so that a test can use it.
//
// A segment is one motion call (STRAIGHT_TRAVERSE, STRAIGHT_FEED, ARC_FEED, ARC_FEED_3D,
// NURBS_FEED or a cycle); an arc or cycle is drawn as several line pieces but stays one segment,
// so "segments drawn" can be compared with the motion calls of `ncpost trace`.

export const MOTION_CALLS = new Set([
  "STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED", "ARC_FEED_3D", "NURBS_FEED",
  "DRILL_CYCLE", "PECK_DRILL_CYCLE", "TAP_CYCLE", "BORE_CYCLE", "REAM_CYCLE",
]);

const LINE = /^\s*(\d+) ([A-Z0-9_]+)\((.*)\)\s*$/;
// #id, TYPE, "name" and, on a WORKINGSTEP_BEGIN, the output options the shop's operation-name
// rules selected (", block_numbers=off, subprogram=on"; docs/canon.md).
const MARKER = /^#(\d+|\$), ([^,]*), "(.*)"((?:, [a-z_]+=[a-z]+)*)$/;

// ", block_numbers=off, subprogram=on" → {block_numbers: "off", subprogram: "on"}.
function markerOptions(text) {
  const options = {};
  for (const pair of text.split(", ").filter((p) => p !== "")) {
    const [key, value] = pair.split("=");
    options[key] = value;
  }
  return options;
}

// How finely arcs are drawn: at most this angle per piece, and at most this many pieces.
export const ARC_STEP_RADIANS = Math.PI / 36;
export const ARC_MAX_PIECES = 720;

function numbers(args) {
  return args.split(", ").map(Number);
}

export class TraceReader {
  // emit(piece) receives each line piece of a segment: {x0,y0,z0,x1,y1,z1,rapid}.
  // onSegment(segment) once per motion call after its pieces:
  //   {index, rapid, workingstep, traceLine, end: [x,y,z]}.
  // onWorkingstep(ws) for each WORKINGSTEP_BEGIN: {index, id, type, name, options, traceLine}.
  constructor({ emit, onSegment, onWorkingstep }) {
    this.emit = emit;
    this.onSegment = onSegment;
    this.onWorkingstep = onWorkingstep;
    this.position = [0, 0, 0];
    this.plane = "CANON_PLANE_XY";
    this.workingstep = -1; // index into the workingsteps seen, -1 outside any
    this.workingsteps = 0;
    this.segments = 0;
    this.calls = 0;
  }

  // The calls that change the reader's state rather than draw, read the same from either form
  // of the trace: `marker()` gives a WORKINGSTEP_BEGIN's {id, type, name, options}, `plane()`
  // a SELECT_PLANE's plane. True when `name` was one of them.
  state(name, traceLine, marker, plane) {
    if (name === "WORKINGSTEP_BEGIN") {
      this.workingstep = this.workingsteps++;
      this.onWorkingstep({ index: this.workingstep, ...marker(), traceLine });
      return true;
    }
    if (name === "WORKINGSTEP_END") {
      this.workingstep = -1;
      return true;
    }
    if (name === "SELECT_PLANE") {
      this.plane = plane();
      return true;
    }
    return false;
  }

  // One record of the JSON trace: the header ({format, version, stock}) and the end record
  // ({end, ok, diagnostics}) are the caller's; a call ({n, call, ...}) is read here.
  record(r) {
    const name = r.call;
    if (!name) return;
    this.calls += 1;
    const traceLine = r.n;
    const marker = () => ({ id: r.id ?? 0, type: r.type ?? "", name: r.name, options: r.options ?? {} });
    if (this.state(name, traceLine, marker, () => r.plane)) return;
    if (!MOTION_CALLS.has(name)) return;
    const rapid = name === "STRAIGHT_TRAVERSE";
    if (name === "STRAIGHT_TRAVERSE" || name === "STRAIGHT_FEED") this.straight(r.x, r.y, r.z, rapid);
    else if (name === "ARC_FEED") this.arc([r.x, r.y, r.z], r.centre, r.normal, r.turns);
    else if (name === "NURBS_FEED") for (const p of r.points) this.straight(p[0], p[1], p[2], false);
    else this.cycle([r.x, r.y, r.safe_z, r.r_z, r.bottom_z]);
    this.segmentDone(rapid, traceLine);
  }

  segmentDone(rapid, traceLine) {
    this.onSegment({
      index: this.segments++,
      rapid,
      workingstep: this.workingstep,
      traceLine,
      end: this.position.slice(),
    });
  }

  line(text) {
    const m = LINE.exec(text);
    if (!m) return;
    this.calls += 1;
    const traceLine = Number(m[1]);
    const name = m[2];
    const args = m[3];
    const marker = () => {
      const m = MARKER.exec(args);
      return {
        id: m && m[1] !== "$" ? Number(m[1]) : 0,
        type: m ? m[2] : "",
        name: m ? m[3] : args,
        options: m ? markerOptions(m[4]) : {},
      };
    };
    if (this.state(name, traceLine, marker, () => args.trim())) return;
    if (!MOTION_CALLS.has(name)) return;
    const rapid = name === "STRAIGHT_TRAVERSE";
    switch (name) {
      case "STRAIGHT_TRAVERSE":
      case "STRAIGHT_FEED": {
        const v = numbers(args);
        this.straight(v[0], v[1], v[2], rapid);
        break;
      }
      case "ARC_FEED":
        this.planeArc(numbers(args));
        break;
      case "ARC_FEED_3D": {
        const v = numbers(args);
        this.arc([v[0], v[1], v[2]], [v[3], v[4], v[5]], [v[6], v[7], v[8]], v[9]);
        break;
      }
      case "NURBS_FEED":
        this.nurbs(args);
        break;
      default:
        this.cycle(numbers(args));
    }
    this.segmentDone(rapid, traceLine);
  }

  straight(x, y, z, rapid) {
    const [x0, y0, z0] = this.position;
    this.emit(x0, y0, z0, x, y, z, rapid);
    this.position = [x, y, z];
  }

  // rs274's plane form: first/second are the plane's coordinates, the axis is the third.
  planeArc(v) {
    const [fe, se, fa, sa, rotation, axisEnd] = v;
    let end;
    let centre;
    let normal;
    if (this.plane === "CANON_PLANE_YZ") {
      end = [axisEnd, fe, se];
      centre = [axisEnd, fa, sa];
      normal = [1, 0, 0];
    } else if (this.plane === "CANON_PLANE_XZ") {
      end = [se, axisEnd, fe];
      centre = [sa, axisEnd, fa];
      normal = [0, 1, 0];
    } else {
      end = [fe, se, axisEnd];
      centre = [fa, sa, axisEnd];
      normal = [0, 0, 1];
    }
    this.arc(end, centre, normal, rotation);
  }

  // An arc or helix about `normal` through `centre`; turns > 0 counterclockwise seen from the
  // normal's tip, |turns| - 1 extra full turns. The axial move is spread evenly (a helix).
  arc(end, centre, normal, turns) {
    const start = this.position;
    const len = Math.hypot(normal[0], normal[1], normal[2]) || 1;
    const n = [normal[0] / len, normal[1] / len, normal[2] / len];
    const rel = (p) => [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]];
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const s = rel(start);
    const e = rel(end);
    const sAxial = dot(s, n);
    const eAxial = dot(e, n);
    const sPlane = [s[0] - sAxial * n[0], s[1] - sAxial * n[1], s[2] - sAxial * n[2]];
    const ePlane = [e[0] - eAxial * n[0], e[1] - eAxial * n[1], e[2] - eAxial * n[2]];
    const radius = Math.hypot(...sPlane);
    if (!(radius > 1e-9) || turns === 0) {
      this.straight(end[0], end[1], end[2], false);
      return;
    }
    const u = sPlane.map((c) => c / radius);
    const w = [n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]];
    let sweep = Math.atan2(dot(ePlane, w), dot(ePlane, u)); // (-pi, pi]
    const ccw = turns > 0;
    if (ccw && sweep <= 1e-12) sweep += 2 * Math.PI;
    if (!ccw && sweep >= -1e-12) sweep -= 2 * Math.PI;
    sweep += (ccw ? 1 : -1) * 2 * Math.PI * (Math.abs(turns) - 1);
    const endRadius = Math.hypot(...ePlane);
    const pieces = Math.min(ARC_MAX_PIECES, Math.max(2, Math.ceil(Math.abs(sweep) / ARC_STEP_RADIANS)));
    let previous = start;
    for (let k = 1; k <= pieces; k++) {
      const t = k / pieces;
      const a = sweep * t;
      const r = radius + (endRadius - radius) * t;
      const axial = sAxial + (eAxial - sAxial) * t;
      const c = Math.cos(a) * r;
      const sn = Math.sin(a) * r;
      const p = k === pieces ? end : [
        centre[0] + c * u[0] + sn * w[0] + axial * n[0],
        centre[1] + c * u[1] + sn * w[1] + axial * n[1],
        centre[2] + c * u[2] + sn * w[2] + axial * n[2],
      ];
      this.emit(previous[0], previous[1], previous[2], p[0], p[1], p[2], false);
      previous = p;
    }
    this.position = end.slice();
  }

  // Drawn through its control points (a display approximation, said in docs/web.md).
  nurbs(args) {
    const points = [...args.matchAll(/\(([^()]*)\)/g)].map((m) => numbers(m[1]));
    for (const p of points) this.straight(p[0], p[1], p[2], false);
  }

  // x, y, safe_z, r_z, bottom_z: rapid over the hole at safe_z, down to R, feed to the bottom,
  // back up to safe_z.
  cycle(v) {
    const [x, y, safeZ, rZ, bottomZ] = v;
    const z0 = this.position[2];
    this.straight(x, y, Math.max(z0, safeZ), true);
    this.straight(x, y, rZ, true);
    this.straight(x, y, bottomZ, false);
    this.straight(x, y, safeZ, true);
  }
}

// Splits a byte stream into lines without holding more than one partial line.
export class LineSplitter {
  constructor(onLine) {
    this.onLine = onLine;
    this.decoder = new TextDecoder();
    this.rest = "";
  }
  push(bytes) {
    this.text(this.decoder.decode(bytes, { stream: true }));
  }
  text(chunk) {
    const text = this.rest + chunk;
    let start = 0;
    for (;;) {
      const nl = text.indexOf("\n", start);
      if (nl < 0) break;
      const end = nl > start && text.charCodeAt(nl - 1) === 13 ? nl - 1 : nl;
      this.onLine(text.slice(start, end));
      start = nl + 1;
    }
    this.rest = text.slice(start);
  }
  end() {
    this.text(this.decoder.decode());
    if (this.rest.length) this.onLine(this.rest);
    this.rest = "";
  }
}

// The motions' output lines from the block map of POST /v1/posts (Accept: application/json):
// `motions[k]` is [first, last] for motion k, or null when it wrote no text. at(line) gives the
// motion whose text holds that line, or -1 (a line between motions: a feed, a tool change).
export class MotionLines {
  constructor(motions) {
    this.first = [];
    this.last = [];
    this.index = [];
    motions.forEach((m, k) => {
      if (!m) return;
      this.first.push(m[0]);
      this.last.push(m[1]);
      this.index.push(k);
    });
  }
  at(line) {
    // The last motion whose first line is at or before `line` (first lines do not decrease).
    let lo = 0;
    let hi = this.first.length - 1;
    let found = -1;
    while (lo <= hi) {
      const mid = (lo + hi) >> 1;
      if (this.first[mid] <= line) {
        found = mid;
        lo = mid + 1;
      } else {
        hi = mid - 1;
      }
    }
    return found >= 0 && this.last[found] >= line ? this.index[found] : -1;
  }
  firstLine(k) {
    const i = this.index.indexOf(k);
    return i >= 0 ? this.first[i] : 0;
  }
}
