// The ncpost front end: post a program, see its toolpath in 3D, follow a workingstep or a
// diagnostic to its block, run verify, compare profiles. Everything it loads comes from
// ncpostd's own routes; the page is one self-contained file (web/build.mjs).
import { CodeView } from "./codeview.js";
import { LineSplitter, MotionLines, TraceReader } from "./trace.js";
import { ToolpathView } from "./view3d.js";
import { lineDiff } from "./diff.js";

const $ = (id) => document.getElementById(id);

// Above this many bytes of upload the 3D view draws one feed segment in k (decimation), k =
// upload bytes / this, rounded up: about 90,000 motions of a STEP-NC program with explicit
// toolpaths (NIST's ex1E: 200 bytes a motion), which a software-rendered WebGL still redraws
// in well under a second. The JSON trace is streamed, so its own size is not known in advance.
const DRAW_BUDGET_UPLOAD_BYTES = 16 << 20;
// Above this many bytes of upload the block map (the JSON post) is skipped: it is one JSON
// document that the browser can only parse in one long task.
const BLOCK_MAP_MAX_UPLOAD_BYTES = 2 << 20;
// Longest stretch of work between two yields to the event loop.
const SLICE_MS = 8;

let sliceStart = performance.now();
async function yieldSometimes() {
  if (performance.now() - sliceStart < SLICE_MS) return;
  await new Promise((resolve) => setTimeout(resolve, 0));
  sliceStart = performance.now();
}

// Feeds a response body (or a File stream) line by line to onLine, yielding now and then.
async function readLines(stream, onLine, onProgress, onBytes) {
  const reader = stream.getReader();
  const pending = [];
  const splitter = new LineSplitter((line) => pending.push(line));
  for (;;) {
    const { done, value } = await reader.read();
    if (done) splitter.end();
    else {
      splitter.push(value);
      if (onBytes) onBytes(value);
    }
    for (let i = 0; i < pending.length; i++) {
      onLine(pending[i]);
      if ((i & 63) === 63) await yieldSometimes();
    }
    pending.length = 0;
    if (onProgress) onProgress();
    await yieldSometimes();
    if (done) return;
  }
}

const state = {
  file: null,
  profiles: [],
  workingsteps: [], // from the trace: {index, id, name, traceLine, firstLine?, lastLine?, segments: []}
  motionSegment: [], // motion k (trace order) → its drawn segment, -1 when decimated away
  motionLines: null, // MotionLines from the block map: output line ↔ motion
  inputLoaded: null,
  run: 0, // increases with every post; a stale async step sees the difference and stops
};

const output = new CodeView($("output"), { label: "Posted program", onLineClick: outputLineClicked });
const input = new CodeView($("input"), { label: "Uploaded program", onLineClick: null });
const view = new ToolpathView($("canvas"));

function setStatus(text, isError = false) {
  $("status").textContent = text;
  $("status").classList.toggle("error", isError);
}

function showTab(name) {
  for (const tab of ["output", "input"]) {
    const selected = tab === name;
    $(`tab-${tab}`).setAttribute("aria-selected", String(selected));
    $(`tab-${tab}`).tabIndex = selected ? 0 : -1;
    $(tab).hidden = !selected;
  }
  (name === "output" ? output : input).render();
}

// ---- profiles -------------------------------------------------------------------------------

async function loadProfiles() {
  const response = await fetch("/v1/profiles");
  const body = await response.json();
  state.profiles = body.profiles;
  for (const select of [$("profile"), $("diff-a"), $("diff-b")]) {
    select.replaceChildren();
    for (const p of body.profiles) {
      const option = document.createElement("option");
      option.value = p.id;
      option.textContent = `${p.id} (${p.name})`;
      select.append(option);
    }
  }
  if (body.profiles.length > 1) $("diff-b").selectedIndex = 1;
  await showProfileTable(body.profiles);
  // The profiles whose dialect.json reads their controller's G-code (from=ID).
  for (const p of body.profiles) {
    const detail = await profileDetail(p.id);
    if (!detail || !detail.reads_gcode) continue;
    const option = document.createElement("option");
    option.value = p.id;
    option.textContent = `${p.id} G-code`;
    $("dialect").append(option);
  }
}

const profileDetails = new Map();
async function profileDetail(id) {
  if (!profileDetails.has(id)) {
    const response = await fetch(`/v1/profiles/${encodeURIComponent(id)}`);
    profileDetails.set(id, response.ok ? await response.json() : null);
  }
  return profileDetails.get(id);
}

function describe(value) {
  if (value === null || typeof value !== "object") return String(value);
  if (value.min !== undefined && value.max !== undefined && Object.keys(value).length === 2)
    return `${value.min} … ${value.max}`;
  return Object.entries(value).map(([k, v]) => `${k}: ${describe(v)}`).join("; ");
}

async function showProfileTable(profiles) {
  const body = $("profile-table").querySelector("tbody");
  body.replaceChildren();
  for (const p of profiles) {
    const detail = await profileDetail(p.id);
    const row = document.createElement("tr");
    const profile = detail ? detail.profile : {};
    const cells = [p.id, p.name, p.controller, detail ? detail.extension : "",
      describe(profile.limits ?? "—"), describe(profile.capabilities ?? "—")];
    for (const text of cells) {
      const cell = document.createElement("td");
      cell.textContent = text;
      row.append(cell);
    }
    body.append(row);
  }
}

// A G-code upload is read with the chosen profile's dialect: `from=` on every job route.
function jobQuery(first) {
  const dialect = $("dialect").value;
  return dialect ? `${first ? "?" : "&"}from=${encodeURIComponent(dialect)}` : "";
}

async function postText(profile) {
  const form = new FormData();
  form.append("file", state.file, state.file.name);
  const response = await fetch(`/v1/posts?profile=${encodeURIComponent(profile)}${jobQuery(false)}`, { method: "POST", body: form });
  if (!response.ok) throw new Error(`${profile}: ${response.status} ${(await response.json()).detail}`);
  return (await response.text()).split("\n");
}

async function compareProfiles() {
  if (!state.file) {
    $("diff-status").textContent = "Pick a program on the Post page first.";
    return;
  }
  const a = $("diff-a").value;
  const b = $("diff-b").value;
  $("diff-status").textContent = `Posting with ${a} and ${b}…`;
  try {
    const [left, right] = await Promise.all([postText(a), postText(b)]);
    const rows = lineDiff(left, right);
    renderDiff(rows, a, b);
    const changed = rows.filter((r) => r.kind !== "same").length;
    $("diff-status").textContent = `${left.length} and ${right.length} lines; ${changed} rows differ.`;
  } catch (error) {
    $("diff-status").textContent = String(error.message || error);
  }
}

const DIFF_ROWS_SHOWN = 20000;
function renderDiff(rows, a, b) {
  const table = $("diff-table");
  table.querySelector("thead").innerHTML = "";
  const head = document.createElement("tr");
  for (const text of ["#", a, "#", b]) {
    const th = document.createElement("th");
    th.textContent = text;
    head.append(th);
  }
  table.querySelector("thead").append(head);
  const body = table.querySelector("tbody");
  body.replaceChildren();
  for (const row of rows.slice(0, DIFF_ROWS_SHOWN)) {
    const tr = document.createElement("tr");
    tr.className = `diff-${row.kind}`;
    for (const text of [row.leftLine ?? "", row.left ?? "", row.rightLine ?? "", row.right ?? ""]) {
      const td = document.createElement("td");
      td.textContent = text;
      tr.append(td);
    }
    body.append(tr);
  }
  table.hidden = false;
}

// ---- diagnostics and findings ---------------------------------------------------------------

function diagnosticButton(d, onClick) {
  const item = document.createElement("li");
  const button = document.createElement("button");
  button.type = "button";
  button.className = `diagnostic ${d.severity}`;
  const where = d.line ? `${d.line}:${d.column ?? 0}` : "";
  button.textContent = `${where} ${d.severity} ${d.code}: ${d.message}`;
  button.dataset.line = String(d.line ?? 0);
  button.addEventListener("click", onClick);
  item.append(button);
  return item;
}

// Diagnostics name lines of the uploaded file; the renderer's (line 0) carry the output line
// of the block they are about (`output_line`, from the block map), the error marker's for an
// error that cut the program.
function showDiagnostics(list) {
  const target = $("diagnostics");
  target.replaceChildren();
  for (const d of list || []) {
    const button = diagnosticButton(d, () => (d.output_line ? jumpTo("output", d.output_line) : jumpTo("input", d.line)));
    if (d.output_line) {
      const b = button.querySelector("button");
      b.dataset.outputLine = String(d.output_line);
      b.textContent = `output ${d.output_line}: ${b.textContent.trim()}`;
    }
    target.append(button);
  }
  $("diagnostics-section").hidden = !list || list.length === 0;
}

async function jumpTo(which, line) {
  if (!line) return;
  if (which === "input") await loadInput();
  showTab(which);
  (which === "input" ? input : output).select(line, { scroll: true });
  (which === "input" ? input : output).element.focus();
}

async function loadInput() {
  if (state.inputLoaded) return state.inputLoaded;
  const run = state.run;
  state.inputLoaded = (async () => {
    input.clear();
    await readLines(state.file.stream(), (line) => {
      if (run === state.run) input.append(line);
    }, () => input.schedule());
    input.render();
  })();
  return state.inputLoaded;
}

// ---- workingsteps and linked views ----------------------------------------------------------

// A large program has tens of thousands of workingsteps: the list shows the first
// WORKINGSTEPS_LISTED (the 3D view and the code have them all), built in slices.
const WORKINGSTEPS_LISTED = 2000;
async function renderWorkingsteps() {
  const list = $("workingsteps");
  list.replaceChildren();
  const run = state.run;
  let fragment = document.createDocumentFragment();
  for (const ws of state.workingsteps.slice(0, WORKINGSTEPS_LISTED)) {
    if (run !== state.run) return;
    if ((ws.index & 255) === 255) {
      list.append(fragment);
      fragment = document.createDocumentFragment();
      await yieldSometimes();
    }
    const item = document.createElement("li");
    const button = document.createElement("button");
    button.type = "button";
    button.className = "workingstep";
    button.setAttribute("aria-pressed", "false");
    button.dataset.index = String(ws.index);
    const swatch = document.createElement("span");
    swatch.className = "swatch";
    swatch.style.background = `#${view.workingstepColor(ws.index).getHexString()}`;
    swatch.setAttribute("aria-hidden", "true");
    const label = document.createElement("span");
    label.textContent = `#${ws.id} ${ws.name} (${ws.motions} motions)`;
    button.append(swatch, label);
    button.addEventListener("click", () => selectWorkingstep(ws.index));
    item.append(button);
    fragment.append(item);
  }
  const more = state.workingsteps.length - WORKINGSTEPS_LISTED;
  if (more > 0) {
    const item = document.createElement("li");
    item.textContent = `… and ${more.toLocaleString()} more workingsteps (the list shows the first ${WORKINGSTEPS_LISTED})`;
    fragment.append(item);
  }
  list.append(fragment);
}

function selectWorkingstep(index) {
  const already = view.selectedWorkingstep === index;
  const chosen = already ? -1 : index;
  const highlighted = view.highlightWorkingstep(chosen);
  $("view3d").dataset.highlighted = String(chosen < 0 ? 0 : highlighted);
  for (const button of $("workingsteps").querySelectorAll("button")) {
    button.setAttribute("aria-pressed", String(Number(button.dataset.index) === chosen));
  }
  const ws = state.workingsteps[chosen];
  if (ws) {
    if (ws.firstLine) {
      showTab("output");
      output.mark(range(ws.firstLine, ws.lastLine));
      output.select(ws.firstLine, { scroll: true });
    }
    setStatus(`Workingstep #${ws.id} ${ws.name}: ${highlighted} motions highlighted` +
      (ws.firstLine ? `, output lines ${ws.firstLine}–${ws.lastLine}` : ""));
  } else {
    output.mark([]);
  }
}

function range(first, last) {
  const lines = [];
  for (let i = first; i <= last && lines.length < 100000; i++) lines.push(i);
  return lines;
}

// A block in the output → the motion whose text holds it (the block map's `motions`: the
// server rendered each motion on its own and noted its lines) → that motion's segment.
function outputLineClicked(line) {
  const motion = state.motionLines ? state.motionLines.at(line) : -1;
  const segment = motion >= 0 ? state.motionSegment[motion] ?? -1 : -1;
  view.markSegment(segment);
  $("view3d").dataset.marked = String(segment);
  $("view3d").dataset.markedMotion = String(motion);
  if (!state.motionLines) setStatus(`Line ${line}: no block map (large upload), no motion marked`);
  else if (motion < 0) setStatus(`Line ${line} is not a motion's block`);
  else if (segment < 0) setStatus(`Line ${line}: motion ${motion + 1}, not drawn (decimated for display)`);
  else setStatus(`Line ${line}: motion ${motion + 1}`);
}

// ---- posting --------------------------------------------------------------------------------

async function streamOutput(run, profile) {
  const form = new FormData();
  form.append("file", state.file, state.file.name);
  const response = await fetch(`/v1/posts?profile=${encodeURIComponent(profile)}${jobQuery(false)}`, { method: "POST", body: form });
  if (!response.ok) {
    const problem = await response.json();
    showDiagnostics(problem.diagnostics);
    throw new Error(`${response.status} ${problem.title}: ${problem.detail}`);
  }
  let last = performance.now();
  // The bytes as they came, for the download: a Blob of the pieces costs no join.
  const pieces = [];
  await readLines(response.body, (line) => {
    if (run === state.run) output.append(line);
  }, () => {
    if (performance.now() - last > 250) {
      last = performance.now();
      $("output").dataset.lines = String(output.lineCount);
      output.schedule();
    }
  }, (bytes) => pieces.push(bytes));
  // The stream ends with a newline; the splitter gives no empty last line for it.
  $("output").dataset.lines = String(output.lineCount);
  $("output").dataset.complete = "true";
  output.render();
  return new Blob(pieces, { type: "text/plain" });
}

// The toolpath from the JSON trace (POST /v1/traces?format=json: NDJSON, a header with the
// stock, one record per call, an end record), drawn as it arrives.
async function drawTrace(run) {
  const form = new FormData();
  form.append("file", state.file, state.file.name);
  const response = await fetch(`/v1/traces?format=json${jobQuery(false)}`, { method: "POST", body: form,
    headers: { Accept: "application/x-ndjson" } });
  if (!response.ok) return { motions: 0, drawn: 0, stride: 1, failed: true };
  const stride = Math.max(1, Math.ceil(state.file.size / DRAW_BUDGET_UPLOAD_BYTES));
  let pieces = [];
  let motions = 0;
  let pendingEnd = null;
  let end = null;
  const reader = new TraceReader({
    emit: (x0, y0, z0, x1, y1, z1, rapid) => pieces.push(x0, y0, z0, x1, y1, z1, rapid ? 1 : 0),
    onWorkingstep: (ws) => {
      state.workingsteps.push({ ...ws, motions: 0, segments: 0, segmentList: [] });
    },
    onSegment: (segment) => {
      motions++;
      const own = state.workingsteps[segment.workingstep];
      if (own) own.motions++;
      // Decimation: keep every rapid and every `stride`-th feed, the kept feed drawn straight
      // from where the last drawn piece ended.
      if (stride > 1 && !segment.rapid && motions % stride !== 0) {
        pendingEnd = pendingEnd || pieces.slice(0, 3);
        pieces = [];
        state.motionSegment.push(-1);
        return;
      }
      if (pendingEnd && pieces.length) {
        pieces = [pendingEnd[0], pendingEnd[1], pendingEnd[2], ...segment.end, segment.rapid ? 1 : 0];
        pendingEnd = null;
      }
      const index = view.segments;
      state.motionSegment.push(index);
      view.addSegment(pieces, segment.rapid, segment.workingstep, segment.end);
      const ws = state.workingsteps[segment.workingstep];
      if (ws) {
        ws.segments++;
        ws.segmentList.push(index);
      }
      pieces = [];
    },
  });
  let lastFlush = performance.now();
  let fitted = false;
  await readLines(response.body, (line) => {
    if (run !== state.run || !line) return;
    const record = JSON.parse(line);
    if (record.call) reader.record(record);
    else if (record.format) {
      view.showStock(record.stock || []);
      $("view3d").dataset.stock = String((record.stock || []).length);
    } else if (record.end) end = record;
  }, () => {
    if (performance.now() - lastFlush > 1000) {
      lastFlush = performance.now();
      view.flush();
      if (!fitted) view.fit();
      fitted = true;
      $("view3d").dataset.segments = String(view.segments);
    }
  });
  view.flush();
  view.fit();
  return { motions, drawn: view.segments, stride, whole: Boolean(end && end.ok) };
}

async function fetchBlockMap(profile) {
  const form = new FormData();
  form.append("file", state.file, state.file.name);
  const response = await fetch(`/v1/posts?profile=${encodeURIComponent(profile)}&motions=true${jobQuery(false)}`, {
    method: "POST", body: form, headers: { Accept: "application/json" } });
  // A post that failed in rendering answers 422 with its diagnostics, each renderer one with
  // the output line where it arose: shown so that they can be followed.
  const body = await response.json();
  return response.ok || response.status === 422 ? body : null;
}

// Trace workingsteps and block-map workingsteps come in the same order; the k-th occurrence of
// an id in one is the k-th in the other.
function attachBlockMap(mapped) {
  const seen = new Map();
  const byId = new Map();
  for (const w of mapped) {
    if (!byId.has(w.id)) byId.set(w.id, []);
    byId.get(w.id).push(w);
  }
  for (const ws of state.workingsteps) {
    const k = seen.get(ws.id) ?? 0;
    seen.set(ws.id, k + 1);
    const match = (byId.get(ws.id) || [])[k];
    if (match) {
      ws.firstLine = match.first_line;
      ws.lastLine = match.last_line;
    }
  }
}

function attachMap(map) {
  if (map.workingsteps) attachBlockMap(map.workingsteps);
  if (map.motions) state.motionLines = new MotionLines(map.motions);
  if (map.diagnostics && map.diagnostics.length) showDiagnostics(map.diagnostics);
}

async function post(event) {
  event.preventDefault();
  if (!state.file) {
    setStatus("Pick or drop a program first.", true);
    return;
  }
  const run = ++state.run;
  const profile = $("profile").value;
  state.workingsteps = [];
  state.motionSegment = [];
  state.motionLines = null;
  state.inputLoaded = null;
  output.clear();
  input.clear();
  view.reset();
  showDiagnostics([]);
  $("findings-section").hidden = true;
  $("workingsteps").replaceChildren();
  $("download").hidden = true;
  delete $("output").dataset.complete;
  for (const key of ["segments", "motions", "highlighted", "marked", "markedMotion", "complete", "stock"]) delete $("view3d").dataset[key];
  showTab("output");
  setStatus(`Posting ${state.file.name} for ${profile}…`);
  const started = performance.now();
  const trace = drawTrace(run);
  let program;
  try {
    program = await streamOutput(run, profile);
  } catch (error) {
    // Rejected before any output (problem+json, diagnostics listed), or cut after output
    // started (the profile's error marker is the last line shown).
    setStatus(String(error.message || error), true);
    await trace.catch(() => null);
    // Cut after output started (an error in rendering): the JSON post names the error's line.
    if (output.lineCount > 0 && state.file.size <= BLOCK_MAP_MAX_UPLOAD_BYTES) {
      const mapped = await fetchBlockMap(profile);
      if (mapped && run === state.run) attachMap(mapped);
    }
    $("output").dataset.lines = String(output.lineCount);
    output.render();
    $("view3d").dataset.complete = "failed";
    return;
  }
  const drawn = await trace;
  if (run !== state.run) return;
  const detail = await profileDetail(profile);
  const extension = detail ? detail.extension : ".nc";
  const link = $("download");
  link.href = URL.createObjectURL(program);
  link.download = state.file.name.replace(/\.[^.]*$/, "") + extension;
  link.textContent = `Download ${link.download}`;
  link.hidden = false;
  if (state.file.size <= BLOCK_MAP_MAX_UPLOAD_BYTES) {
    const mapped = await fetchBlockMap(profile);
    if (mapped && run === state.run) attachMap(mapped);
  }
  await renderWorkingsteps();
  const v = $("view3d");
  v.dataset.segments = String(drawn.drawn);
  v.dataset.motions = String(drawn.motions);
  v.dataset.stride = String(drawn.stride);
  v.dataset.complete = drawn.whole ? "true" : "partial";
  const seconds = ((performance.now() - started) / 1000).toFixed(1);
  const decimated = drawn.stride > 1
    ? ` Decimated for display: ${drawn.drawn} of ${drawn.motions} motions drawn (one feed in ${drawn.stride}).`
    : ` ${drawn.drawn} motions drawn.`;
  const mapNote = state.file.size > BLOCK_MAP_MAX_UPLOAD_BYTES ? " Block map skipped (large upload)." : "";
  setStatus(`${output.lineCount} lines for ${profile} in ${seconds} s.${decimated}${mapNote}`);
}

async function verify() {
  if (!state.file) {
    setStatus("Pick or drop a program first.", true);
    return;
  }
  setStatus("Verifying…");
  const form = new FormData();
  form.append("file", state.file, state.file.name);
  const response = await fetch(`/v1/verifications${jobQuery(true)}`, { method: "POST", body: form });
  const report = await response.json();
  const findings = report.diagnostics || [];
  const list = $("findings");
  list.replaceChildren();
  const points = [];
  for (const d of findings) {
    if (d.position) points.push([d.position.x, d.position.y, d.position.z]);
    list.append(diagnosticButton(d, () => {
      if (d.motion) {
        // Motion N (1-based, trace order) → its drawn segment (none when decimated away).
        const segment = state.motionSegment[d.motion - 1] ?? -1;
        view.markSegment(segment);
        $("view3d").dataset.marked = String(segment);
      }
      jumpTo("input", d.line);
    }));
  }
  // A floor region left uncut: one sample position per feature.
  for (const f of report.features || []) {
    const sample = f.coverage && f.coverage.uncovered_sample;
    if (sample) points.push([sample.x, sample.y, sample.z]);
  }
  view.showFindings(points);
  $("findings-section").hidden = false;
  $("view3d").dataset.findings = String(points.length);
  setStatus(response.ok
    ? `Verify: ${report.ok ? "pass" : "FAIL"}, ${findings.length} findings, ${points.length} shown in 3D.`
    : `Verify: ${response.status} ${report.title ?? ""}`, !response.ok || !report.ok);
}

// ---- wiring ---------------------------------------------------------------------------------

function takeFile(file) {
  if (!file) return;
  state.file = file;
  $("file-name").textContent = `${file.name} (${file.size.toLocaleString()} bytes)`;
}

$("file").addEventListener("change", () => takeFile($("file").files[0]));
// A file dropped anywhere on the page is taken (and never opened by the browser instead).
const drop = $("drop");
document.addEventListener("dragover", (event) => {
  event.preventDefault();
  drop.classList.add("over");
});
document.addEventListener("dragleave", (event) => {
  if (!event.relatedTarget) drop.classList.remove("over");
});
document.addEventListener("drop", (event) => {
  event.preventDefault();
  drop.classList.remove("over");
  takeFile(event.dataTransfer.files[0]);
});
$("compare-form").addEventListener("submit", (event) => event.preventDefault());
$("post").addEventListener("submit", post);
$("verify").addEventListener("click", verify);
$("fit").addEventListener("click", () => view.fit());
$("compare").addEventListener("click", compareProfiles);
const TABS = ["output", "input"];
async function openTab(tab) {
  if (tab === "input" && state.file) await loadInput();
  showTab(tab);
}
for (const tab of TABS) {
  $(`tab-${tab}`).addEventListener("click", () => openTab(tab));
  // The tab pattern of WAI-ARIA: arrow keys move between the tabs, Home and End to the ends.
  $(`tab-${tab}`).addEventListener("keydown", async (event) => {
    const at = TABS.indexOf(tab);
    const next = { ArrowRight: at + 1, ArrowLeft: at - 1, Home: 0, End: TABS.length - 1 }[event.key];
    if (next === undefined) return;
    event.preventDefault();
    const target = TABS[(next + TABS.length) % TABS.length];
    await openTab(target);
    $(`tab-${target}`).focus();
  });
}
for (const page of ["page-post", "page-profiles"]) {
  $(`nav-${page}`).addEventListener("click", () => {
    for (const other of ["page-post", "page-profiles"]) {
      $(other).hidden = other !== page;
      $(`nav-${other}`).setAttribute("aria-current", other === page ? "page" : "false");
    }
    if (page === "page-post") view.resize();
  });
}

loadProfiles().catch((error) => setStatus(String(error), true));
