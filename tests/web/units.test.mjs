// The page's pure modules under `node --test`: trace lines to segments (straight moves, arcs
// and helices in each plane, cycles, workingsteps) and the bounded line diff.
import assert from "node:assert/strict";
import test from "node:test";
import { LineSplitter, MotionLines, TraceReader } from "../../web/src/trace.js";
import { MAX_EDITS, lineDiff } from "../../web/src/diff.js";

function read(lines, how = "line") {
  const pieces = [];
  const segments = [];
  const workingsteps = [];
  const reader = new TraceReader({
    emit: (...p) => pieces.push(p),
    onSegment: (s) => segments.push(s),
    onWorkingstep: (w) => workingsteps.push(w),
  });
  for (const line of lines) reader[how](line);
  return { pieces, segments, workingsteps };
}

const close = (a, b) => assert.ok(Math.abs(a - b) < 1e-6, `${a} != ${b}`);

test("straight moves are one segment each, rapids marked", () => {
  const { pieces, segments } = read([
    "    1 STRAIGHT_TRAVERSE(10.0000, 0.0000, 5.0000)",
    "    2 STRAIGHT_FEED(10.0000, 20.0000, -1.0000)",
    "    3 COMMENT(\"STRAIGHT_FEED(1, 2, 3)\")",
  ]);
  assert.equal(segments.length, 2);
  assert.deepEqual(segments.map((s) => s.rapid), [true, false]);
  assert.deepEqual(pieces[1], [10, 0, 5, 10, 20, -1, false]);
  assert.deepEqual(segments[1].end, [10, 20, -1]);
  assert.equal(segments[1].traceLine, 2);
});

test("an XY arc ends at its end point on its circle, counterclockwise for rotation 1", () => {
  const { pieces, segments } = read([
    "    1 STRAIGHT_FEED(10.0000, 0.0000, 0.0000)",
    "    2 ARC_FEED(0.0000, 10.0000, 0.0000, 0.0000, 1, -2.0000)",
  ]);
  assert.equal(segments.length, 2);
  const arc = pieces.slice(1);
  assert.ok(arc.length >= 10);
  for (const p of arc) {
    close(Math.hypot(p[3], p[4]), 10);
    assert.ok(p[3] >= -1e-9 && p[4] >= -1e-9, "a quarter turn through the first quadrant");
  }
  const last = arc[arc.length - 1];
  assert.deepEqual(last.slice(3, 6), [0, 10, -2]);
  assert.equal(arc.length % 2, 0);
  close(arc[arc.length / 2 - 1][5], -1); // the helix descends evenly: half way, half deep
});

test("a clockwise arc and two turns go the other way round, longer", () => {
  const cw = read(["    1 STRAIGHT_FEED(10, 0, 0)", "    2 ARC_FEED(0, 10, 0, 0, -1, 0)"]).pieces.slice(1);
  assert.ok(cw.some((p) => p[3] < -5), "clockwise from +X to +Y passes through -X");
  const two = read(["    1 STRAIGHT_FEED(10, 0, 0)", "    2 ARC_FEED(0, 10, 0, 0, 2, 0)"]).pieces.slice(1);
  const once = read(["    1 STRAIGHT_FEED(10, 0, 0)", "    2 ARC_FEED(0, 10, 0, 0, 1, 0)"]).pieces.slice(1);
  assert.ok(two.length > 4 * once.length);
});

test("XZ and YZ planes map first/second/axis as rs274 does", () => {
  const xz = read(["    1 SELECT_PLANE(CANON_PLANE_XZ)", "    2 STRAIGHT_FEED(0, 3, 10)",
    "    3 ARC_FEED(0, 10, 0, 0, 1, 3)"]).pieces;
  assert.deepEqual(xz[xz.length - 1].slice(3, 6), [10, 3, 0]);
  for (const p of xz.slice(1)) close(Math.hypot(p[3], p[5]), 10);
  const yz = read(["    1 SELECT_PLANE(CANON_PLANE_YZ)", "    2 STRAIGHT_FEED(4, 10, 0)",
    "    3 ARC_FEED(0, 10, 0, 0, 1, 4)"]).pieces;
  assert.deepEqual(yz[yz.length - 1].slice(3, 6), [4, 0, 10]);
});

test("workingsteps number the segments inside them; cycles are one segment", () => {
  const { segments, workingsteps } = read([
    "    1 WORKINGSTEP_BEGIN(#10, MACHINING_WORKINGSTEP, \"WS, with \\\"comma\\\"\")",
    "    2 DRILL_CYCLE(5.0000, 6.0000, 10.0000, 2.0000, -8.0000, 100.0000, 0.0000)",
    "    3 WORKINGSTEP_END(#10, MACHINING_WORKINGSTEP, \"WS, with \\\"comma\\\"\")",
    "    4 STRAIGHT_TRAVERSE(0, 0, 50)",
  ]);
  assert.equal(workingsteps.length, 1);
  assert.equal(workingsteps[0].id, 10);
  assert.equal(segments.length, 2);
  assert.equal(segments[0].workingstep, 0);
  assert.equal(segments[1].workingstep, -1);
  assert.deepEqual(segments[0].end, [5, 6, 10]);
});

test("a workingstep marker with output options keeps its name and gives the options", () => {
  const { workingsteps } = read([
    "    1 WORKINGSTEP_BEGIN(#4, CL_OPERATION, \"ROUGH_NONUM, \\\"x\\\"\", block_numbers=off, subprogram=on)",
    "    2 WORKINGSTEP_BEGIN(#9, CL_OPERATION, \"PLAIN\")",
  ]);
  assert.equal(workingsteps.length, 2);
  assert.equal(workingsteps[0].id, 4);
  assert.equal(workingsteps[0].type, "CL_OPERATION");
  assert.equal(workingsteps[0].name, "ROUGH_NONUM, \\\"x\\\"");
  assert.deepEqual(workingsteps[0].options, { block_numbers: "off", subprogram: "on" });
  assert.equal(workingsteps[1].name, "PLAIN");
  assert.deepEqual(workingsteps[1].options, {});
});

test("the line splitter joins lines across chunks and drops CR", () => {
  const lines = [];
  const splitter = new LineSplitter((l) => lines.push(l));
  const bytes = new TextEncoder().encode("ab\r\ncd\nef");
  splitter.push(bytes.slice(0, 3));
  splitter.push(bytes.slice(3));
  splitter.end();
  assert.deepEqual(lines, ["ab", "cd", "ef"]);
});

test("line diff: same, changed, added, removed, in order", () => {
  const rows = lineDiff(["a", "b", "c", "d"], ["a", "x", "c", "d", "e"]);
  assert.deepEqual(rows.map((r) => r.kind), ["same", "changed", "same", "same", "added"]);
  assert.deepEqual(rows.map((r) => r.left ?? null), ["a", "b", "c", "d", null]);
  assert.deepEqual(rows.map((r) => r.right ?? null), ["a", "x", "c", "d", "e"]);
  const run = lineDiff(["a", "b1", "b2", "c"], ["a", "x1", "x2", "x3", "c"]);
  assert.deepEqual(run.map((r) => r.kind), ["same", "changed", "changed", "added", "same"]);
  assert.deepEqual(run.map((r) => [r.leftLine ?? 0, r.rightLine ?? 0]), [[1, 1], [2, 2], [3, 3], [0, 4], [4, 5]]);
  const removed = lineDiff(["a", "b", "c"], ["a", "c"]);
  assert.deepEqual(removed.map((r) => r.kind), ["same", "removed", "same"]);
});

test("line diff stays bounded when every line differs", () => {
  const n = MAX_EDITS * 2;
  const a = Array.from({ length: n }, (_, i) => `N${i} A`);
  const b = Array.from({ length: n }, (_, i) => `N${i} B`);
  const started = Date.now();
  const rows = lineDiff(a, b);
  assert.ok(Date.now() - started < 5000);
  assert.equal(rows.filter((r) => r.kind === "changed").length, n);
});

// The page reads the JSON trace; the same program as text lines gives the same drawing.
test("JSON records draw what the text trace draws", () => {
  const text = [
    "    1 WORKINGSTEP_BEGIN(#10, MACHINING_WORKINGSTEP, \"WS 1\")",
    "    2 STRAIGHT_TRAVERSE(10.0000, 0.0000, 5.0000)",
    "    3 STRAIGHT_FEED(10.0000, 0.0000, 0.0000)",
    "    4 ARC_FEED(0.0000, 10.0000, 0.0000, 0.0000, -1, -2.0000)",
    "    5 SELECT_PLANE(CANON_PLANE_XZ)",
    "    6 ARC_FEED(10.0000, 0.0000, 0.0000, 0.0000, 1, 10.0000)",
    "    7 ARC_FEED_3D(0.0000, 10.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.7071, 0.7071, 1)",
    "    8 NURBS_FEED(2, [(0.0000, 10.0000, 0.0000, 1.0000), (5.0000, 12.0000, 0.0000, 0.5000), (9.0000, 9.0000, 1.0000, 1.0000)], [0.0000, 0.0000, 0.0000, 1.0000, 1.0000, 1.0000])",
    "    9 WORKINGSTEP_END(#10, MACHINING_WORKINGSTEP, \"WS\")",
    "   10 PECK_DRILL_CYCLE(5.0000, 5.0000, 20.0000, 2.0000, -8.0000, 100.0000, 0.0000, 3.0000, 0.0000, 0.5000)",
  ];
  // ncpost trace --format json of the same calls: an arc always in its 3D form.
  const records = [
    { n: 1, call: "WORKINGSTEP_BEGIN", id: 10, type: "MACHINING_WORKINGSTEP", name: "WS 1" },
    { n: 2, call: "STRAIGHT_TRAVERSE", x: 10, y: 0, z: 5 },
    { n: 3, call: "STRAIGHT_FEED", x: 10, y: 0, z: 0 },
    { n: 4, call: "ARC_FEED", x: 0, y: 10, z: -2, centre: [0, 0, -2], normal: [0, 0, 1], turns: -1 },
    { n: 5, call: "SELECT_PLANE", plane: "CANON_PLANE_XZ" },
    { n: 6, call: "ARC_FEED", x: 0, y: 10, z: 10, centre: [0, 10, 0], normal: [0, 1, 0], turns: 1 },
    { n: 7, call: "ARC_FEED", x: 0, y: 10, z: 0, centre: [0, 0, 0], normal: [0, 0.7071, 0.7071], turns: 1 },
    { n: 8, call: "NURBS_FEED", degree: 2, points: [[0, 10, 0, 1], [5, 12, 0, 0.5], [9, 9, 1, 1]], knots: [0, 0, 0, 1, 1, 1] },
    { n: 9, call: "WORKINGSTEP_END", id: 10, type: "MACHINING_WORKINGSTEP", name: "WS" },
    { n: 10, call: "PECK_DRILL_CYCLE", x: 5, y: 5, safe_z: 20, r_z: 2, bottom_z: -8, feed: 100, dwell: 0, peck: 3, peck_retract: 0, peck_clearance: 0.5 },
  ];
  const fromText = read(text);
  const fromJson = read(records, "record");
  assert.equal(fromJson.segments.length, 7);
  assert.deepEqual(fromJson.segments, fromText.segments);
  assert.deepEqual(fromJson.workingsteps, fromText.workingsteps);
  assert.equal(fromJson.pieces.length, fromText.pieces.length);
  fromJson.pieces.forEach((p, k) => p.slice(0, 6).forEach((v, i) => close(v, fromText.pieces[k][i])));
  // Header and end records are not calls.
  const none = read([{ format: "ncpost-trace", version: 1, stock: [] }, { end: true, ok: true }], "record");
  assert.equal(none.segments.length + none.pieces.length, 0);
});

test("a block's line gives the motion whose text holds it", () => {
  const lines = new MotionLines([[3, 3], null, [4, 6], [7, 7], null, [10, 10]]);
  assert.deepEqual([1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11].map((l) => lines.at(l)), [-1, -1, 0, 2, 2, 2, 3, -1, -1, 5, -1]);
  assert.equal(new MotionLines([]).at(1), -1);
});
