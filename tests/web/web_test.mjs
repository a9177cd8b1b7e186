// The front end in a real browser (issue 21): Debian's chromium, headless, through
// playwright-core, against the real ncpostd on 127.0.0.1. Every expected figure comes from
// `ncpost` or from the server's own JSON, never from the page.
//   node web_test.mjs --ncpostd BIN --ncpost BIN --source DIR --out DIR
import assert from "node:assert/strict";
import { existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { createRequire } from "node:module";
import os from "node:os";
import path from "node:path";
import {
  LONG_TASK_PROBE, corpusFile, launchBrowser, loadPlaywright, parseArgs, run, runAllowingFailure, startServer,
} from "./harness.mjs";

const args = parseArgs(process.argv.slice(2));
const source = args.source;
const out = args.out;
const PROFILE = "fanuc-0i";
const MOTION = /^\s*\d+ (STRAIGHT_TRAVERSE|STRAIGHT_FEED|ARC_FEED|ARC_FEED_3D|NURBS_FEED|DRILL_CYCLE|PECK_DRILL_CYCLE|TAP_CYCLE|BORE_CYCLE|REAM_CYCLE)\(/;

const playwright = loadPlaywright(source);
const ex1e = corpusFile(source, "p21/nist_toolkit_ex1E.stp");
const webRoot = path.join(source, "web");
if (!existsSync(path.join(webRoot, "index.html"))) {
  console.log("FAIL: web/index.html is not built (npm ci --prefix web && npm run --prefix web build)");
  process.exit(1);
}
mkdirSync(out, { recursive: true });

// ---- expectations from the command line -----------------------------------------------------
const postLines = run(args.ncpost, ["post", "--profile", PROFILE, ex1e]).replace(/\n$/, "").split("\n").length;
const traceLines = run(args.ncpost, ["trace", ex1e]).split("\n");
const motions = traceLines.filter((l) => MOTION.test(l)).length;
// The JSON form of the same trace (what the page draws): the same motions, in the same order.
const MOTION_CALLS = new Set(["STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED", "NURBS_FEED", "DRILL_CYCLE",
  "PECK_DRILL_CYCLE", "TAP_CYCLE", "BORE_CYCLE", "REAM_CYCLE"]);
function jsonTrace(file) {
  const records = run(args.ncpost, ["trace", "--format", "json", file]).trim().split("\n").map((l) => JSON.parse(l));
  return { header: records[0], end: records[records.length - 1],
    motions: records.filter((r) => MOTION_CALLS.has(r.call)) };
}
const ex1eJson = jsonTrace(ex1e);
assert.equal(ex1eJson.motions.length, motions, "the JSON trace has the text trace's motions");
assert.equal(ex1eJson.end.ok, true);
// Motions per workingstep, and how many motions come before each.
const workingsteps = [];
let current = null;
let seen = 0;
for (const line of traceLines) {
  if (/^\s*\d+ WORKINGSTEP_BEGIN\(/.test(line)) {
    current = { before: seen, motions: 0 };
    workingsteps.push(current);
  } else if (/^\s*\d+ WORKINGSTEP_END\(/.test(line)) {
    current = null;
  } else if (MOTION.test(line)) {
    seen++;
    if (current) current.motions++;
  }
}
assert.ok(motions > 100 && workingsteps.length >= 2, "ex1E has motions in several workingsteps");

// A broken copy: one instance line cut in half, so the reader reports it at a known place.
const text = readFileSync(ex1e, "latin1").split("\n");
const victim = text.findIndex((l, i) => i > 40 && /^#\d+=/.test(l));
text[victim] = text[victim].slice(0, Math.floor(text[victim].length / 2)) + "((;";
// Written outside the project (the corpus is never copied into it) and removed at the end.
const scratch = mkdtempSync(path.join(os.tmpdir(), "ncpost-web-"));
const broken = path.join(scratch, "broken-ex1E.stp");
writeFileSync(broken, text.join("\n"), "latin1");

// A copy of ex1E whose first milling technology asks for a feed above linuxcnc's limit
// (10,000 mm/min; a warning there): a renderer diagnostic that names an output block. (A
// spindle speed out of reach would not do: the units check reads an absurd rev/s as rpm.)
const fast = readFileSync(ex1e, "latin1").replace(/(MILLING_TECHNOLOGY\()[0-9.]+/, "$10.200");
assert.notEqual(fast, readFileSync(ex1e, "latin1"));
const fastFile = path.join(scratch, "fast-ex1E.stp");
writeFileSync(fastFile, fast, "latin1");

// Waits until line `line` of a code view is its current line and lies wholly inside the view's
// visible box. Checked in one evaluation in the page: the view re-renders its rows as it
// scrolls, so element handles taken from outside can go stale between two reads.
async function currentLineShown(page, view, line, what) {
  try {
    await page.waitForFunction(([selector, n]) => {
      const box = document.querySelector(selector).getBoundingClientRect();
      const row = document.querySelector(`${selector} .code-line.current[data-line="${n}"]`);
      if (!row) return false;
      const r = row.getBoundingClientRect();
      return r.top >= box.top && r.bottom <= box.bottom && r.height > 0;
    }, [view, line], { timeout: 5000 });
  } catch {
    assert.fail(what);
  }
}

const server = await startServer(args.ncpostd, webRoot);
const browser = await launchBrowser(playwright);
let failed = false;
try {
  const page = await browser.newPage({ viewport: { width: 1600, height: 900 } });
  page.on("pageerror", (error) => {
    failed = true;
    console.log(`page error: ${error.message}`);
  });
  await page.addInitScript(LONG_TASK_PROBE);
  await page.goto(`${server.url}/`);
  await page.waitForSelector(`#profile option[value="${PROFILE}"]`, { state: "attached" });

  // -- drag and drop: a file dropped on the page is the one to post
  const dropped = await page.evaluateHandle((text) => {
    const transfer = new DataTransfer();
    transfer.items.add(new File([text], "dropped-ex1E.stp"));
    return transfer;
  }, readFileSync(ex1e, "latin1"));
  await page.dispatchEvent("#drop", "drop", { dataTransfer: dropped });
  assert.match(await page.textContent("#file-name"), /^dropped-ex1E\.stp /);

  // -- post ex1E, wait for the stream and the 3D view to finish
  await page.setInputFiles("#file", ex1e);
  await page.selectOption("#profile", PROFILE);
  await page.waitForTimeout(500); // let the page's start-up task end before measuring
  await page.evaluate(() => { window.__longestTask = 0; });
  await page.click("button[type=submit]");
  await page.waitForSelector("#view3d[data-complete=true]", { timeout: 60000 });
  const loadingTask = await page.evaluate(() => window.__longestTask);
  const shown = await page.$eval("#output", (e) => Number(e.dataset.lines));
  assert.equal(shown, postLines, "output lines = ncpost post's lines");
  const drawn = await page.$eval("#view3d", (e) => ({ segments: Number(e.dataset.segments), stride: Number(e.dataset.stride) }));
  assert.equal(drawn.stride, 1, "a small program is not decimated");
  assert.equal(drawn.segments, motions, "drawn segments = motion calls of ncpost trace");
  console.log(`ok: ${shown} output lines, ${drawn.segments} segments drawn; longest main-thread task while loading ${loadingTask.toFixed(0)} ms`);

  // -- the canvas: not blank, and rapids (dashed, red) differ in colour from feeds
  await page.waitForTimeout(300);
  const pixels = await page.$eval("#canvas", (canvas) => {
    const copy = document.createElement("canvas");
    copy.width = canvas.width;
    copy.height = canvas.height;
    const context = copy.getContext("2d");
    context.drawImage(canvas, 0, 0);
    const data = context.getImageData(0, 0, copy.width, copy.height).data;
    let ink = 0;
    const colours = new Map();
    for (let i = 0; i < data.length; i += 4) {
      if (data[i] > 245 && data[i + 1] > 245 && data[i + 2] > 245) continue;
      ink++;
      const key = `${data[i] >> 4},${data[i + 1] >> 4},${data[i + 2] >> 4}`;
      colours.set(key, (colours.get(key) || 0) + 1);
    }
    return { ink, total: data.length / 4, colours: [...colours.entries()].sort((a, b) => b[1] - a[1]) };
  });
  assert.ok(pixels.ink > 1000, `the canvas is not blank (${pixels.ink} drawn pixels)`);
  // 0xd62728 quantised to 4 bits per channel: 13,2,2.
  const rapid = pixels.colours.filter(([k]) => k === "13,2,2").reduce((s, [, n]) => s + n, 0);
  const feeds = pixels.colours.filter(([k]) => {
    const [r, g, b] = k.split(",").map(Number);
    return !(r === 13 && g === 2 && b === 2) && Math.max(r, g, b) - Math.min(r, g, b) >= 3;
  }).reduce((s, [, n]) => s + n, 0);
  assert.ok(rapid > 50, `rapids are drawn in their colour (${rapid} px)`);
  assert.ok(feeds > 200, `feeds are drawn in other colours (${feeds} px)`);
  console.log(`ok: canvas ${pixels.ink} px drawn, ${rapid} rapid px, ${feeds} feed px`);
  await page.screenshot({ path: path.join(out, "post.png") });

  // -- click a workingstep: highlight and code scroll
  const form = new FormData();
  form.append("file", new Blob([readFileSync(ex1e)]), "ex1E.stp");
  const mapped = await (await fetch(`${server.url}/v1/posts?profile=${PROFILE}&motions=true`, {
    method: "POST", body: form, headers: { Accept: "application/json" } })).json();
  // The first workingstep after the first with several motions (a real cut, visible in 3D).
  const pick = workingsteps.findIndex((w, i) => i > 0 && w.motions >= 5);
  const firstLine = mapped.workingsteps[pick].first_line;
  await page.click(`#workingsteps button[data-index="${pick}"]`);
  assert.equal(await page.$eval(`#workingsteps button[data-index="${pick}"]`, (b) => b.getAttribute("aria-pressed")), "true");
  assert.equal(await page.$eval("#view3d", (e) => Number(e.dataset.highlighted)), workingsteps[pick].motions,
    "the workingstep's motions are highlighted");
  await currentLineShown(page, "#output", firstLine, "the code view scrolled to the workingstep's first block");
  console.log(`ok: workingstep ${pick} highlights ${workingsteps[pick].motions} motions, code at line ${firstLine}`);
  await page.screenshot({ path: path.join(out, "workingstep.png") });

  // -- click blocks in the code: each marks its own motion in 3D. Expected: the motion whose
  // lines the server's block map gives for that block, inside the workingstep, and whose end
  // point (JSON trace) is where the block's X, Y, Z words go (fanuc-0i has no setup transform;
  // a word left out is modal).
  const lines = await page.$$eval("#output .code-line", (rows) => rows.map((r) => [Number(r.dataset.line), r.textContent]));
  const blocks = lines.filter(([n, t]) => n > firstLine && / [XYZ]-?[0-9.]/.test(t)).slice(0, 6);
  assert.ok(blocks.length >= 3, "blocks with coordinates after the workingstep's first line");
  const ws = workingsteps[pick];
  for (const [n, textOfBlock] of blocks) {
    await page.click(`#output .code-line[data-line="${n}"]`);
    const marked = await page.$eval("#view3d", (e) => Number(e.dataset.marked));
    const expected = mapped.motions.findIndex((m) => m && m[0] <= n && n <= m[1]);
    assert.equal(marked, expected, `block ${n} marks the motion the block map gives (${expected})`);
    assert.ok(marked >= ws.before && marked < ws.before + ws.motions, `block ${n} lies in its workingstep`);
    const end = ex1eJson.motions[marked];
    for (const [, axis, value] of textOfBlock.matchAll(/ ([XYZ])(-?[0-9.]+)/g)) {
      assert.ok(Math.abs(Number(value) - end[axis.toLowerCase()]) < 1e-3,
        `block ${n}: ${axis}${value} is motion ${marked}'s end (${end[axis.toLowerCase()]})`);
    }
  }
  console.log(`ok: ${blocks.length} blocks (lines ${blocks[0][0]}–${blocks[blocks.length - 1][0]}) each mark their own motion`);
  await page.screenshot({ path: path.join(out, "block.png") });

  // -- the tabs: arrow keys move between them (WAI-ARIA tab pattern)
  await page.focus("#tab-output");
  // (The Input tab reads the upload first: the switch completes asynchronously.)
  await page.keyboard.press("ArrowRight");
  await page.waitForFunction(() => document.activeElement.id === "tab-input" &&
    document.getElementById("tab-input").getAttribute("aria-selected") === "true" && !document.getElementById("input").hidden,
  null, { timeout: 5000 });
  await page.keyboard.press("ArrowLeft");
  await page.waitForFunction(() => document.activeElement.id === "tab-output" &&
    document.getElementById("tab-output").getAttribute("aria-selected") === "true" && document.getElementById("input").hidden,
  null, { timeout: 5000 });
  console.log("ok: arrow keys move between the Output and Input tabs");

  // -- verify a program of the project's own golden cases that gouges and leaves floor uncut:
  // every finding with a position, and every uncovered sample, gets its marker in 3D
  const faulty = path.join(source, "tests", "golden", "verify", "cases", "l-pocket-uncovered.stp");
  const report = JSON.parse(runAllowingFailure(args.ncpost, ["verify", "--format", "json", faulty]));
  const markers = report.diagnostics.filter((d) => d.position).length +
    report.features.filter((f) => f.coverage && f.coverage.uncovered_sample).length;
  assert.ok(markers >= 2, "the case has a finding and an uncovered sample");
  await page.setInputFiles("#file", faulty);
  await page.click("button[type=submit]");
  await page.waitForSelector("#view3d[data-complete=true]");
  // Its workpiece has a BLOCK: the stock the JSON trace gives is drawn.
  const stock = jsonTrace(faulty).header.stock;
  assert.ok(stock.length >= 1, "the case's workpiece has a BLOCK");
  assert.equal(await page.$eval("#view3d", (e) => Number(e.dataset.stock)), stock.length, "the stock boxes are drawn");
  await page.click("#verify");
  await page.waitForSelector("#findings-section:not([hidden])");
  const verifyStatus = await page.textContent("#status");
  assert.match(verifyStatus, /^Verify: FAIL/);
  assert.equal(await page.$eval("#view3d", (e) => Number(e.dataset.findings)), markers, "a marker per located finding");
  await page.screenshot({ path: path.join(out, "verify.png") });
  console.log(`ok: ${verifyStatus}`);

  // -- a broken file: the diagnostic jumps to its line in the input
  const brokenForm = new FormData();
  brokenForm.append("file", new Blob([readFileSync(broken)]), "broken-ex1E.stp");
  const problem = await (await fetch(`${server.url}/v1/posts?profile=${PROFILE}`, { method: "POST", body: brokenForm })).json();
  const diagnosticLine = problem.diagnostics.find((d) => d.line > 0).line;
  await page.setInputFiles("#file", broken);
  await page.click("button[type=submit]");
  const diagnostic = await page.waitForSelector(`#diagnostics button[data-line="${diagnosticLine}"]`);
  await diagnostic.click();
  await currentLineShown(page, "#input", diagnosticLine, "the input view shows the diagnostic's line");
  assert.equal(await page.$eval(`#input .code-line[data-line="${diagnosticLine}"]`, (r) => r.textContent.includes("((;")), true);
  console.log(`ok: diagnostic jumps to input line ${diagnosticLine}`);
  await page.screenshot({ path: path.join(out, "diagnostic.png") });

  // -- a renderer diagnostic (a feed above linuxcnc's limit) jumps to its output line
  const fastForm = new FormData();
  fastForm.append("file", new Blob([readFileSync(fastFile)]), "fast-ex1E.stp");
  const fastMap = await (await fetch(`${server.url}/v1/posts?profile=linuxcnc&motions=true`, {
    method: "POST", body: fastForm, headers: { Accept: "application/json" } })).json();
  const warning = fastMap.diagnostics.find((d) => d.code === "RENDER-001" && d.output_line > 0);
  assert.ok(warning, "the server names the output line of the renderer's warning");
  const fastLines = fastMap.program.split("\n");
  assert.match(fastLines[warning.output_line - 1], /F12000/, "that line holds the feed");
  await page.setInputFiles("#file", fastFile);
  await page.selectOption("#profile", "linuxcnc");
  await page.click("button[type=submit]");
  await page.waitForSelector("#view3d[data-complete=true]");
  await (await page.waitForSelector(`#diagnostics button[data-output-line="${warning.output_line}"]`)).click();
  await currentLineShown(page, "#output", warning.output_line, "the output view shows the renderer diagnostic's line");
  console.log(`ok: renderer diagnostic jumps to output line ${warning.output_line}`);
  await page.screenshot({ path: path.join(out, "render-diagnostic.png") });

  // -- the other readers: a G-code program read with fanuc-0i's dialect, and a CL file, each
  // posted for linuxcnc: the lines of `ncpost post`, the motions of `ncpost trace`
  const motionCount = (text) => text.split("\n").filter((l) => MOTION.test(l)).length;
  const lineCount = (text) => text.replace(/\n$/, "").split("\n").length;
  const gcode = path.join(source, "tests", "golden", "gcode", "fanuc-0i", "zigzag-pocket.nc");
  const cl = corpusFile(source, "cls/steptools_STEPNode_simple_block.cls");
  for (const [file, dialect, cliArgs] of [[gcode, "fanuc-0i", ["--dialect", "fanuc-0i"]], [cl, "", []]]) {
    const expectedLines = lineCount(run(args.ncpost, ["post", "--profile", "linuxcnc", ...(dialect ? ["--from", dialect] : []), file]));
    const expectedMotions = motionCount(run(args.ncpost, ["trace", ...cliArgs, file]));
    await page.setInputFiles("#file", file);
    await page.selectOption("#profile", "linuxcnc");
    await page.selectOption("#dialect", dialect);
    await page.click("button[type=submit]");
    await page.waitForSelector("#view3d[data-complete=true]");
    assert.equal(await page.$eval("#output", (e) => Number(e.dataset.lines)), expectedLines, `${file}: the lines of ncpost post`);
    assert.equal(await page.$eval("#view3d", (e) => Number(e.dataset.segments)), expectedMotions, `${file}: the motions of ncpost trace`);
    console.log(`ok: ${path.basename(file)}${dialect ? ` (${dialect} G-code)` : ""}: ${expectedLines} lines, ${expectedMotions} motions drawn`);
  }
  await page.screenshot({ path: path.join(out, "cl.png") });
  await page.selectOption("#dialect", "");

  // -- accessibility: axe-core's rules (WCAG 2 A and AA: labels, contrast, roles) in the page
  const axeSource = readFileSync(createRequire(path.resolve(source, "tests", "package.json")).resolve("axe-core/axe.min.js"), "utf8");
  await page.evaluate(axeSource);
  const axeOptions = { runOnly: { type: "tag", values: ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa"] } };
  // Violations as "rule: nodes (first node)", and how many rules passed (so that a run that
  // checked nothing cannot pass).
  const axeRun = (o) => window.axe.run(document, o).then((r) => ({
    violations: r.violations.map((v) => `${v.id}: ${v.nodes.length} (${v.nodes[0].target})`),
    passes: r.passes.length,
  }));
  const postAxe = await page.evaluate(axeRun, axeOptions);
  assert.deepEqual(postAxe.violations, [], "axe-core: no violations on the Post page");
  assert.ok(postAxe.passes >= 10, `axe-core checked the Post page (${postAxe.passes} rules passed)`);

  // -- profiles: the table and a side-by-side diff
  await page.setInputFiles("#file", ex1e);
  await page.click("#nav-page-profiles");
  const profiles = (await (await fetch(`${server.url}/v1/profiles`)).json()).profiles.length;
  await page.waitForFunction((n) => document.querySelectorAll("#profile-table tbody tr").length === n, profiles);
  await page.selectOption("#diff-a", "fanuc-0i");
  await page.selectOption("#diff-b", "haas-ngc");
  await page.click("#compare");
  await page.waitForSelector("#diff-table:not([hidden])");
  const diffRows = await page.$$eval("#diff-table tbody tr", (rows) => rows.length);
  const haasLines = run(args.ncpost, ["post", "--profile", "haas-ngc", ex1e]).replace(/\n$/, "").split("\n").length;
  // Every line of both programs has its row; a changed row holds one of each.
  assert.ok(diffRows >= Math.max(postLines, haasLines) && diffRows <= postLines + haasLines,
    `the diff shows every line (${diffRows} rows)`);
  await page.screenshot({ path: path.join(out, "profiles.png") });
  const profilesAxe = await page.evaluate(axeRun, axeOptions);
  assert.deepEqual(profilesAxe.violations, [], "axe-core: no violations on the Profiles page");
  console.log(`ok: axe-core (WCAG 2.1 A/AA) finds no violation on either page (${postAxe.passes} and ${profilesAxe.passes} rules passed)`);
  await page.$eval("#diff-status", (e) => e.scrollIntoView());
  await page.screenshot({ path: path.join(out, "diff.png") });
  console.log(`ok: ${profiles} profiles listed, diff of ${diffRows} rows`);

} catch (error) {
  failed = true;
  console.log(`FAIL: ${error.stack || error}`);
  console.log(server.log());
} finally {
  await browser.close();
  await server.stop();
  rmSync(scratch, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
