// Shared by the browser tests: find the tools, start ncpostd on 127.0.0.1 with an ephemeral
// port, launch Debian's chromium headless through playwright-core, and skip (77) or fail
// clearly when something is missing.
import { spawn, execFileSync } from "node:child_process";
import { existsSync } from "node:fs";
import { createRequire } from "node:module";
import path from "node:path";

export const SKIP = 77;
const requireAll = process.env.NCPOST_REQUIRE_CORPUS === "1";

export function parseArgs(argv) {
  const args = {};
  for (let i = 0; i < argv.length; i += 2) {
    if (!argv[i].startsWith("--")) throw new Error(`unexpected argument ${argv[i]}`);
    args[argv[i].slice(2)] = argv[i + 1];
  }
  return args;
}

// Missing tools or data: skip with the reason, or fail under NCPOST_REQUIRE_CORPUS=1.
export function skipOrFail(reason) {
  console.log(`${requireAll ? "FAIL" : "SKIP"}: ${reason}`);
  process.exit(requireAll ? 1 : SKIP);
}

export function loadPlaywright(source) {
  const require = createRequire(path.resolve(source, "tests", "package.json"));
  try {
    return require("playwright-core");
  } catch {
    skipOrFail("playwright-core is not installed (scripts/install-deps.sh runs npm ci --prefix tests)");
  }
  return null;
}

export function chromiumPath() {
  for (const candidate of [process.env.NCPOST_CHROMIUM, "/usr/bin/chromium"]) {
    if (candidate && existsSync(candidate)) return candidate;
  }
  skipOrFail("Debian's chromium is not installed (scripts/install-deps.sh installs it)");
  return null;
}

export function corpusFile(source, relative) {
  const root = process.env.NCPOST_CORPUS || path.join(source, "..", "shared", "corpus");
  const file = path.join(root, relative);
  if (!existsSync(file)) skipOrFail(`corpus file ${file} not found (NCPOST_CORPUS or ../shared/corpus)`);
  return file;
}

// Starts ncpostd; resolves with {url, stop()} once its first log line names the bound port.
export function startServer(ncpostd, webRoot) {
  return new Promise((resolve, reject) => {
    const child = spawn(ncpostd, ["--listen", "127.0.0.1:0", "--web-root", webRoot], {
      stdio: ["ignore", "pipe", "pipe"],
    });
    let log = "";
    const timer = setTimeout(() => reject(new Error(`ncpostd did not start:\n${log}`)), 15000);
    const onData = (data) => {
      log += data.toString();
      const match = /"listening":"(127\.0\.0\.1:\d+)"/.exec(log);
      if (!match) return;
      clearTimeout(timer);
      resolve({
        url: `http://${match[1]}`,
        log: () => log,
        stop: () => new Promise((done) => {
          child.once("exit", done);
          child.kill("SIGTERM");
        }),
      });
    };
    child.stdout.on("data", onData);
    child.stderr.on("data", onData);
    child.once("exit", (code) => reject(new Error(`ncpostd exited ${code}:\n${log}`)));
  });
}

export async function launchBrowser(playwright) {
  return playwright.chromium.launch({
    executablePath: chromiumPath(),
    headless: true,
    // Software WebGL (SwiftShader) in a headless machine without a GPU.
    args: ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--no-sandbox"],
  });
}

// Records the longest main-thread task (Long Tasks API) from page load on.
export const LONG_TASK_PROBE = `
  window.__longestTask = 0;
  window.__longTasks = 0;
  new PerformanceObserver((list) => {
    for (const entry of list.getEntries()) {
      window.__longTasks++;
      window.__longestTask = Math.max(window.__longestTask, entry.duration);
    }
  }).observe({ type: "longtask", buffered: true });
`;

export function run(command, args) {
  return execFileSync(command, args, { maxBuffer: 1 << 30, encoding: "utf8" });
}

// For commands whose exit status 1 is an answer (verify finding a fault): their stdout.
export function runAllowingFailure(command, args) {
  try {
    return run(command, args);
  } catch (error) {
    if (error.status === 1 && typeof error.stdout === "string") return error.stdout;
    throw error;
  }
}
