// Bundles src/main.js with three.js (from node_modules, pinned by package-lock.json) and
// writes index.html: src/index.html with the bundle inlined. ncpostd serves that one file at
// `/` under a Content-Security-Policy that allows inline scripts only, so the page loads
// nothing else and works without a network. Run by `npm run build` (scripts/install-deps.sh).
import { build } from "esbuild";
import { readFile, writeFile, rename } from "node:fs/promises";
import { fileURLToPath } from "node:url";
import path from "node:path";

const here = path.dirname(fileURLToPath(import.meta.url));
const result = await build({
  entryPoints: [path.join(here, "src", "main.js")],
  bundle: true,
  format: "iife",
  minify: true,
  target: "es2022",
  write: false,
  legalComments: "eof",
});
// "</script" inside the bundle would end the inline script early.
const script = result.outputFiles[0].text.replaceAll("</script", "<\\/script");
const template = await readFile(path.join(here, "src", "index.html"), "utf8");
const marker = "<!-- bundle -->";
if (!template.includes(marker)) throw new Error(`src/index.html has no ${marker}`);
const page = template.replace(marker, () => `<script>${script}</script>`);
const target = path.join(here, "index.html");
await writeFile(`${target}.tmp`, page);
await rename(`${target}.tmp`, target);
console.log(`web/index.html: ${page.length} bytes`);
