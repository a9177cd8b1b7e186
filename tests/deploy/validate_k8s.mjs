// Validates rendered Kubernetes manifests (ctest deploy_kubernetes, docs/deploy.md):
//  1. every object against the Kubernetes API's JSON schemas, as compiled by the npm package
//     kubernetes-models (types, enums, required fields; it does not refuse unknown fields);
//  2. the deployment contract of issue 22, which also catches a misspelt field that matters
//     (its value is then missing): probes, resources, securityContext, grace period versus
//     preStop + drain deadline, selectors that match the pods, the admin token as a file,
//     Prometheus annotations, volumes that name objects of the same set.
// Usage: node validate_k8s.mjs NAME FILE.yaml...   (one rendered set; exit 1 on any finding)
import { readFileSync } from "node:fs";
import { parseAllDocuments } from "yaml";

const [setName, ...files] = process.argv.slice(2);
const findings = [];
const problem = (where, message) => findings.push(`${setName}: ${where}: ${message}`);

const objects = [];
for (const file of files) {
  for (const doc of parseAllDocuments(readFileSync(file, "utf8"))) {
    if (doc.errors.length) problem(file, doc.errors.map((e) => e.message).join("; "));
    const value = doc.toJSON();
    if (value) objects.push(value);
  }
}

const name = (o) => `${o.kind}/${o.metadata?.name}`;
for (const o of objects) {
  let module;
  try {
    module = await import(`kubernetes-models/${o.apiVersion}`);
  } catch {
    problem(name(o), `unknown apiVersion ${o.apiVersion}`);
    continue;
  }
  const Model = module[o.kind];
  if (!Model) {
    problem(name(o), `unknown kind ${o.kind} in ${o.apiVersion}`);
    continue;
  }
  try {
    new Model(o).validate();
  } catch (error) {
    problem(name(o), `schema: ${error.message}`);
  }
}

const byKind = (kind) => objects.filter((o) => o.kind === kind);
const names = (kind) => new Set(byKind(kind).map((o) => o.metadata.name));
const selects = (selector, labels) =>
  selector && Object.keys(selector).length > 0 &&
  Object.entries(selector).every(([k, v]) => labels?.[k] === v);

function checkSecurity(where, pod, container) {
  const p = pod.securityContext ?? {};
  const c = container.securityContext ?? {};
  if (!(c.runAsNonRoot ?? p.runAsNonRoot)) problem(where, "runAsNonRoot is not true");
  if (!((c.runAsUser ?? p.runAsUser) > 0)) problem(where, "no non-zero runAsUser");
  if (c.readOnlyRootFilesystem !== true) problem(where, "readOnlyRootFilesystem is not true");
  if (c.allowPrivilegeEscalation !== false) problem(where, "allowPrivilegeEscalation is not false");
  if (c.privileged) problem(where, "privileged");
  if (!c.capabilities?.drop?.includes("ALL")) problem(where, "capabilities do not drop ALL");
  for (const kind of ["requests", "limits"])
    for (const resource of ["cpu", "memory"])
      if (!container.resources?.[kind]?.[resource]) problem(where, `no resources.${kind}.${resource}`);
  for (const env of container.env ?? [])
    if (/TOKEN/i.test(env.name)) problem(where, `the token in the environment (${env.name})`);
}

function checkVolumes(where, pod) {
  const configMaps = names("ConfigMap");
  const claims = names("PersistentVolumeClaim");
  const declared = new Set((pod.volumes ?? []).map((v) => v.name));
  for (const v of pod.volumes ?? []) {
    if (v.configMap && !configMaps.has(v.configMap.name))
      problem(where, `volume ${v.name}: no ConfigMap ${v.configMap.name} in the set`);
    if (v.persistentVolumeClaim && !claims.has(v.persistentVolumeClaim.claimName))
      problem(where, `volume ${v.name}: no PersistentVolumeClaim ${v.persistentVolumeClaim.claimName}`);
  }
  for (const c of pod.containers)
    for (const m of c.volumeMounts ?? [])
      if (!declared.has(m.name)) problem(where, `mount of undeclared volume ${m.name}`);
}

const deployments = byKind("Deployment");
for (const d of deployments) {
  const where = name(d);
  const pod = d.spec.template.spec;
  const labels = d.spec.template.metadata?.labels;
  if (!selects(d.spec.selector?.matchLabels, labels)) problem(where, "selector does not match its pods");
  const container = pod.containers.find((c) => c.name === "ncpostd");
  if (!container) {
    problem(where, "no container ncpostd");
    continue;
  }
  checkSecurity(where, pod, container);
  checkVolumes(where, pod);
  if (container.readinessProbe?.httpGet?.path !== "/readyz") problem(where, "readiness probe is not GET /readyz");
  if (container.livenessProbe?.httpGet?.path !== "/healthz") problem(where, "liveness probe is not GET /healthz");
  const preStop = container.lifecycle?.preStop?.exec?.command;
  const delay = preStop?.[0] === "sleep" ? Number(preStop[1]) : NaN;
  if (!(delay > 0)) problem(where, "no preStop sleep");
  const drain = Number(container.env?.find((e) => e.name === "NCPOST_SHUTDOWN_TIMEOUT")?.value);
  if (!(drain > 0)) problem(where, "no NCPOST_SHUTDOWN_TIMEOUT (the drain deadline)");
  if (!(pod.terminationGracePeriodSeconds >= delay + drain))
    problem(where, `terminationGracePeriodSeconds ${pod.terminationGracePeriodSeconds} < preStop ${delay} + drain ${drain}`);
  const annotations = d.spec.template.metadata?.annotations ?? {};
  const port = container.ports?.find((p) => p.name === "http")?.containerPort;
  if (annotations["prometheus.io/scrape"] !== "true" || annotations["prometheus.io/path"] !== "/metrics" ||
      annotations["prometheus.io/port"] !== String(port))
    problem(where, "no Prometheus scrape annotations for /metrics on the http port");
  const token = pod.volumes?.find((v) => v.secret?.items?.some((i) => i.path === "ncpost-admin-token"));
  const tokenMount = container.volumeMounts?.find((m) => m.name === token?.name);
  if (!token || tokenMount?.mountPath !== "/run/secrets")
    problem(where, "the admin token is not a Secret file at /run/secrets/ncpost-admin-token");

  const others = [["Service", (o) => o.spec.selector], ["PodDisruptionBudget", (o) => o.spec.selector?.matchLabels],
                  ["NetworkPolicy", (o) => o.spec.podSelector?.matchLabels]];
  for (const [kind, selectorOf] of others) {
    const matching = byKind(kind).filter((o) => selects(selectorOf(o), labels));
    if (matching.length !== 1) problem(where, `${matching.length} ${kind} objects select its pods, not 1`);
  }
  const hpa = byKind("HorizontalPodAutoscaler").find((h) => h.spec.scaleTargetRef?.name === d.metadata.name);
  if (!hpa?.spec.metrics?.some((m) => m.type === "Resource" && m.resource?.name === "cpu"))
    problem(where, "no HorizontalPodAutoscaler on CPU");
  else if (!(hpa.spec.minReplicas >= 1 && hpa.spec.maxReplicas >= hpa.spec.minReplicas))
    problem(where, "HorizontalPodAutoscaler bounds");
}

for (const job of byKind("Job")) {
  const where = name(job);
  const pod = job.spec.template.spec;
  if (pod.restartPolicy !== "Never") problem(where, "restartPolicy is not Never (a failed batch must fail the Job)");
  for (const c of pod.containers) checkSecurity(`${where} ${c.name}`, pod, c);
  checkVolumes(where, pod);
}

if (deployments.length + byKind("Job").length === 0) problem("set", "neither a Deployment nor a Job");
for (const f of findings) console.log(`FAIL ${f}`);
const kinds = objects.map((o) => o.kind).sort().join(", ");
console.log(`${setName}: ${objects.length} objects (${kinds}), ${findings.length} findings`);
process.exit(findings.length ? 1 : 0);
