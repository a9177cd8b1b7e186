// ctest openapi_contract (issue 23: 13): openapi/openapi.yaml against the running ncpostd.
// For every operation and every status it documents, a request here makes the server answer
// that status, and the answer carries each header the description lists for it, with one of
// its content types. A documented status no request here produces must be named in
// ELSEWHERE with the test that produces it, so that adding a status to the description
// without a check fails this test.
//
// usage: node openapi_contract.mjs --ncpostd BIN --source DIR
import { spawn } from "node:child_process";
import { mkdtempSync, mkdirSync, readFileSync, rmSync, writeFileSync, copyFileSync } from "node:fs";
import { createRequire } from "node:module";
import http from "node:http";
import os from "node:os";
import path from "node:path";

const args = {};
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].slice(2)] = process.argv[i + 1];
const source = args.source;
const requireAll = process.env.NCPOST_REQUIRE_CORPUS === "1";

let YAML;
try {
  YAML = createRequire(path.join(source, "tests", "package.json"))("yaml");
} catch {
  console.log(`${requireAll ? "FAIL" : "SKIP"}: the yaml package is not installed (npm ci --prefix tests)`);
  process.exit(requireAll ? 1 : 77);
}
const spec = YAML.parse(readFileSync(path.join(source, "openapi/openapi.yaml"), "utf8"));

// Statuses the session answers the same way on every route, each produced by a test of its
// own (a timeout, a full queue, an exhausted memory budget): not repeated here per operation.
const ELSEWHERE = {
  408: "server_test ReadTimeout, upload_test (a request that does not arrive in --read-timeout)",
  503: "server_test QueueFull, memory_budget_test (queue or memory budget exhausted)",
  504: "server_test / upload_test JobTimeout (a job past --job-timeout)",
};
// A 500 the server gives only when it fails (HTTP-010) or a profile version cannot be written
// (PROFILE-007: a full or read-only disk): not something a request can cause on purpose.
const INTERNAL_ONLY = new Set([
  "POST /v1/conversions", "POST /v1/inspections", "POST /v1/traces", "POST /v1/verifications",
  "POST /v1/schemas", "PUT /v1/profiles/{id}",
]);

function resolve(node) {
  while (node && node.$ref) {
    node = node.$ref.replace(/^#\//, "").split("/").reduce((n, key) => n[key], spec);
  }
  return node;
}

function request(port, { method, target, headers = {}, body = "" }) {
  return new Promise((done, fail) => {
    const payload = Buffer.from(body);
    const r = http.request(
      { host: "127.0.0.1", port, method, path: target, headers: { ...headers, "Content-Length": payload.length } },
      (res) => {
        const chunks = [];
        res.on("data", (c) => chunks.push(c));
        res.on("end", () => done({ status: res.statusCode, headers: res.headers, trailers: res.trailers, body: Buffer.concat(chunks).toString() }));
        res.on("error", fail);
      });
    // A server that answers 413 before reading the whole body may close while we still write.
    r.on("error", (e) => (e.code === "EPIPE" || e.code === "ECONNRESET" ? null : fail(e)));
    r.end(payload);
  });
}

function start(flags) {
  return new Promise((done, fail) => {
    const child = spawn(args.ncpostd, ["--listen", "127.0.0.1:0", "--access-log", "off", ...flags],
                        { stdio: ["ignore", "pipe", "pipe"] });
    let log = "";
    const timer = setTimeout(() => fail(new Error(`ncpostd did not start:\n${log}`)), 15000);
    const onData = (data) => {
      log += data.toString();
      const m = /"listening":"127\.0\.0\.1:(\d+)"/.exec(log);
      if (!m) return;
      clearTimeout(timer);
      done({ port: Number(m[1]), stop: () => new Promise((d) => { child.once("exit", d); child.kill("SIGTERM"); }) });
    };
    child.stdout.on("data", onData);
    child.stderr.on("data", onData);
  });
}

const read = (relative) => readFileSync(path.join(source, relative), "utf8");
const example = read("tests/golden/trace/cases/executables.stp");
const broken = read("tests/golden/p21-malformed/dangling-reference.stp");
const gcode = "G21 G90 G17\nG0 X1 Y1 Z5\nM3 S1000\nG1 Z-1 F100\nG1 X10\nM5\nM2\n";
const schema = "SCHEMA tiny;\nENTITY point;\n  x : REAL;\nEND_ENTITY;\nEND_SCHEMA;\n";
const tooLarge = "x".repeat(70 * 1024);
const tooManyHeaders = Object.fromEntries(Array.from({ length: 80 }, (_, i) => [`X-Pad-${i}`, "y".repeat(60)]));
const json = { Accept: "application/json" };
const token = "contract-test-token-0123456789abcdef";
const admin = { Authorization: `Bearer ${token}` };
const profileJson = read("stylesheets/linuxcnc/profile.json");
const stylesheet = read("stylesheets/linuxcnc/post.xsl");
function upload(id, profileText = profileJson.replace('"linuxcnc"', `"${id}"`)) {
  const parts = [["profile", profileText], ["stylesheet", stylesheet]];
  return {
    headers: { ...admin, "Content-Type": "multipart/form-data; boundary=B" },
    body: parts.map(([name, text]) => `--B\r\nContent-Disposition: form-data; name="${name}"\r\n\r\n${text}\r\n`).join("") + "--B--\r\n",
  };
}
const post = (target, body, headers = {}) => ({ method: "POST", target, body, headers });
// The size limits every upload route shares: a body over --max-body, headers over --max-header.
const generic = (operation, target, body) => [
  [operation, 413, post(target, tooLarge)],
  [operation, 431, { ...post(target, body), headers: tooManyHeaders }],
];

// [operation, status, request]; a request may be a function of earlier answers.
const answers = {};
const scenarios = [
  ["POST /v1/posts", 200, post("/v1/posts?profile=linuxcnc&name=part.stp", example), "text"],
  ["POST /v1/posts", 200, post("/v1/posts?profile=linuxcnc", example, json)],
  ["POST /v1/posts", 304, () => post("/v1/posts?profile=linuxcnc&name=part.stp", example, { "If-None-Match": answers.text.headers.etag })],
  ["POST /v1/posts", 400, post("/v1/posts", example)],
  ["POST /v1/posts", 404, post("/v1/posts?profile=no-such", example)],
  ["POST /v1/posts", 422, post("/v1/posts?profile=linuxcnc", broken)],
  ["POST /v1/posts", 500, post("/v1/posts?profile=broken", example)],
  ...generic("POST /v1/posts", "/v1/posts?profile=linuxcnc", example),
  ["POST /v1/conversions", 200, post("/v1/conversions?to=p28", example)],
  ["POST /v1/conversions", 400, post("/v1/conversions?to=bogus", example)],
  ["POST /v1/conversions", 422, post("/v1/conversions?to=p21", "hello")],
  ...generic("POST /v1/conversions", "/v1/conversions?to=p28", example),
  ["POST /v1/inspections", 200, post("/v1/inspections", example)],
  ["POST /v1/inspections", 400, post("/v1/inspections?strict=maybe", example)],
  ["POST /v1/inspections", 422, post("/v1/inspections", broken)],
  ...generic("POST /v1/inspections", "/v1/inspections", example),
  ["POST /v1/traces", 200, post("/v1/traces", example)],
  ["POST /v1/traces", 200, post("/v1/traces?format=json", example)],
  ["POST /v1/traces", 200, post("/v1/traces", example, json)],
  ["POST /v1/traces", 422, post("/v1/traces?format=json", broken)],
  ["POST /v1/posts", 200, post("/v1/posts?profile=linuxcnc&motions=true", example, json)],
  ["POST /v1/traces", 400, post("/v1/traces?format=yaml", example)],
  ["POST /v1/traces", 422, post("/v1/traces", broken)],
  ...generic("POST /v1/traces", "/v1/traces", example),
  ["POST /v1/verifications", 200, post("/v1/verifications", example)],
  ["POST /v1/verifications", 400, post("/v1/verifications?tolerance=-1", example)],
  ["POST /v1/verifications", 422, post("/v1/verifications", broken)],
  ...generic("POST /v1/verifications", "/v1/verifications", example),
  ["POST /v1/schemas", 200, post("/v1/schemas", schema)],
  ["POST /v1/schemas", 400, post("/v1/schemas", "")],
  ["POST /v1/schemas", 422, post("/v1/schemas", "SCHEMA broken;\nENTITY\n")],
  ...generic("POST /v1/schemas", "/v1/schemas", schema),
  ["POST /v1/nc/parse", 200, post("/v1/nc/parse?dialect=linuxcnc", gcode)],
  ["POST /v1/nc/parse", 200, post("/v1/nc/parse?dialect=linuxcnc&format=xml", gcode)],
  ["POST /v1/nc/parse", 400, post("/v1/nc/parse", gcode)],
  ["POST /v1/nc/parse", 404, post("/v1/nc/parse?dialect=no-such", gcode)],
  ["POST /v1/nc/parse", 413, post("/v1/nc/parse?dialect=linuxcnc", tooLarge)],
  ["POST /v1/nc/parse", 422, post("/v1/nc/parse?dialect=linuxcnc", "G1 X[1+\nM2\n")],
  ["POST /v1/nc/translate", 200, post("/v1/nc/translate?from=linuxcnc&to=fanuc-0i", gcode)],
  ["POST /v1/nc/translate", 400, post("/v1/nc/translate?from=linuxcnc", gcode)],
  ["POST /v1/nc/translate", 404, post("/v1/nc/translate?from=linuxcnc&to=no-such", gcode)],
  ["POST /v1/nc/translate", 413, post("/v1/nc/translate?from=linuxcnc&to=fanuc-0i", tooLarge)],
  ["POST /v1/nc/translate", 422, post("/v1/nc/translate?from=linuxcnc&to=fanuc-0i", "G1 X[1+\nM2\n")],
  ["GET /v1/profiles", 200, { method: "GET", target: "/v1/profiles" }],
  ["GET /v1/profiles", 431, { method: "GET", target: "/v1/profiles", headers: tooManyHeaders }],
  ["GET /v1/profiles/{id}", 200, { method: "GET", target: "/v1/profiles/fanuc-0i" }, "profile"],
  ["GET /v1/profiles/{id}", 304, () => ({ method: "GET", target: "/v1/profiles/fanuc-0i", headers: { "If-None-Match": answers.profile.headers.etag } })],
  ["GET /v1/profiles/{id}", 400, { method: "GET", target: "/v1/profiles/UPPER" }],
  ["GET /v1/profiles/{id}", 404, { method: "GET", target: "/v1/profiles/no-such" }],
  ["GET /v1/profiles/{id}", 500, { method: "GET", target: "/v1/profiles/broken" }],
  ["PUT /v1/profiles/{id}", 201, { method: "PUT", target: "/v1/profiles/shop-mill", ...upload("shop-mill") }],
  ["PUT /v1/profiles/{id}", 200, { method: "PUT", target: "/v1/profiles/shop-mill", ...upload("shop-mill", profileJson.replace('"linuxcnc"', '"shop-mill"').replace(/"name": "[^"]*"/, '"name": "Shop mill 2"')) }],
  ["PUT /v1/profiles/{id}", 400, { method: "PUT", target: "/v1/profiles/shop-mill", headers: { ...admin, "Content-Type": "application/json" }, body: "{}" }],
  ["PUT /v1/profiles/{id}", 401, { method: "PUT", target: "/v1/profiles/shop-mill", ...upload("shop-mill"), headers: { "Content-Type": "multipart/form-data; boundary=B" } }],
  ["PUT /v1/profiles/{id}", 403, { method: "PUT", target: "/v1/profiles/shop-mill", ...upload("shop-mill"), headers: { Authorization: "Bearer wrong", "Content-Type": "multipart/form-data; boundary=B" } }],
  ["PUT /v1/profiles/{id}", 409, { method: "PUT", target: "/v1/profiles/common", ...upload("common") }],
  ["PUT /v1/profiles/{id}", 413, { method: "PUT", target: "/v1/profiles/shop-mill", headers: admin, body: tooLarge }],
  ["PUT /v1/profiles/{id}", 422, { method: "PUT", target: "/v1/profiles/shop-mill", ...upload("shop-mill", '{"id": "shop-mill"}') }],
  ["DELETE /v1/profiles/{id}", 204, { method: "DELETE", target: "/v1/profiles/shop-mill", headers: admin }],
  ["DELETE /v1/profiles/{id}", 400, { method: "DELETE", target: "/v1/profiles/UPPER", headers: admin }],
  ["DELETE /v1/profiles/{id}", 401, { method: "DELETE", target: "/v1/profiles/shop-mill" }],
  ["DELETE /v1/profiles/{id}", 403, { method: "DELETE", target: "/v1/profiles/shop-mill", headers: { Authorization: "Bearer wrong" } }],
  ["DELETE /v1/profiles/{id}", 404, { method: "DELETE", target: "/v1/profiles/shop-mill", headers: admin }],
  ["DELETE /v1/profiles/{id}", 409, { method: "DELETE", target: "/v1/profiles/linuxcnc", headers: admin }],
  ["GET /healthz", 200, { method: "GET", target: "/healthz" }],
  ["GET /readyz", 503, { method: "GET", target: "/readyz" }],
  ["GET /metrics", 200, { method: "GET", target: "/metrics" }],
  ["GET /openapi.yaml", 200, { method: "GET", target: "/openapi.yaml" }],
  ["GET /", 200, { method: "GET", target: "/" }],
];
// On a second server without the broken profile, without the description and the front end.
const plainScenarios = [
  ["GET /readyz", 200, { method: "GET", target: "/readyz" }],
  ["GET /openapi.yaml", 404, { method: "GET", target: "/openapi.yaml" }],
  ["GET /", 404, { method: "GET", target: "/" }],
];

const failures = [];
const covered = new Set();

function check(operation, status, req, res) {
  const where = `${operation} -> ${status} (${req.method} ${req.target})`;
  if (res.status !== status) {
    failures.push(`${where}: answered ${res.status}: ${res.body.slice(0, 300)}`);
    return;
  }
  const [method, template] = operation.split(" ");
  const documented = resolve(spec.paths[template][method.toLowerCase()].responses[String(status)]);
  if (!documented) {
    failures.push(`${where}: the status is not documented`);
    return;
  }
  covered.add(`${operation} ${status}`);
  const isJson = /json/.test(res.headers["content-type"] || "");
  const trailerFields = (res.headers.trailer || "").split(",").map((s) => s.trim().toLowerCase()).filter(Boolean);
  for (const [name, header] of Object.entries(documented.headers || {})) {
    const h = resolve(header);
    const lower = name.toLowerCase();
    const description = h.description || "";
    // A header documented for one form of the answer: "(format=xml) ..." for one query.
    const condition = /^\((\w+=\w+)\)/.exec(description);
    if (condition && !req.target.includes(condition[1])) continue;
    if (trailerFields.includes(lower)) {
      if (!(lower in res.trailers)) failures.push(`${where}: the trailer field ${name} is announced but missing`);
      continue;
    }
    const streamedOnly = /streamed\s+form\s+only/i.test(description) || /^A trailer field/i.test(description);
    if (streamedOnly && isJson) continue;
    if (/^A trailer field/i.test(description)) {
      failures.push(`${where}: ${name} is documented but the Trailer header does not announce it`);
      continue;
    }
    if (!(lower in res.headers)) failures.push(`${where}: documented header ${name} is missing`);
  }
  const types = Object.keys(documented.content || {});
  if (types.length && status !== 304 && status !== 204) {
    const got = (res.headers["content-type"] || "").split(";")[0].trim();
    const ok = types.some((t) => t === got || (t === "text/plain" && got.startsWith("text/")) || t === "*/*");
    if (!ok) failures.push(`${where}: Content-Type ${got} is not one of ${types.join(", ")}`);
  }
}

async function runAll(port, list) {
  for (const [operation, status, make, remember] of list) {
    const req = typeof make === "function" ? make() : make;
    const res = await request(port, req);
    if (remember) answers[remember] = res;
    check(operation, status, req, res);
  }
}

const work = mkdtempSync(path.join(os.tmpdir(), "ncpost-contract-"));
try {
  const store = path.join(work, "profiles");
  mkdirSync(path.join(store, "broken"), { recursive: true });
  writeFileSync(path.join(store, "broken", "profile.json"), profileJson.replace('"linuxcnc"', '"broken"'));
  writeFileSync(path.join(store, "broken", "post.xsl"), "<xsl:stylesheet");
  writeFileSync(path.join(work, "token"), token + "\n", { mode: 0o600 });
  const limits = ["--max-body", "65536", "--max-header", "4096", "--admin-token-file", path.join(work, "token")];
  const server = await start(["--profiles", store, "--web-root", path.join(source, "web"),
                              "--openapi", path.join(source, "openapi/openapi.yaml"), ...limits]);
  try {
    await runAll(server.port, scenarios);
  } finally {
    await server.stop();
  }
  const plain = await start(["--web-root", path.join(work, "no-web"), "--openapi", path.join(work, "none.yaml")]);
  try {
    await runAll(plain.port, plainScenarios);
  } finally {
    await plain.stop();
  }
} finally {
  rmSync(work, { recursive: true, force: true });
}

// Every documented status: checked here, or by the named test.
for (const [template, operations] of Object.entries(spec.paths)) {
  for (const [method, op] of Object.entries(operations)) {
    if (method === "parameters") continue;
    const operation = `${method.toUpperCase()} ${template}`;
    for (const status of Object.keys(op.responses)) {
      if (covered.has(`${operation} ${status}`) || ELSEWHERE[status]) continue;
      if (status === "500" && INTERNAL_ONLY.has(operation)) continue;
      failures.push(`${operation} -> ${status}: documented, but no request here produces it`);
    }
  }
}

console.log(`checked ${covered.size} documented (operation, status) pairs against ncpostd`);
if (failures.length) {
  console.log(`FAIL: ${failures.length} disagreement(s) between openapi.yaml and the server:`);
  for (const f of failures) console.log(`  ${f}`);
  process.exit(1);
}
console.log("PASS");
