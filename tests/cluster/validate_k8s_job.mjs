// Validates a Kubernetes batch/v1 Job manifest (JSON) with the npm package
// kubernetes-models (major 5): its Job model carries a validator generated
// from the Kubernetes OpenAPI schema (types, enums, formats, required
// fields).
//
//   node validate_k8s_job.mjs NPM_PREFIX MANIFEST.json
//
// NPM_PREFIX is the directory of `npm install --prefix NPM_PREFIX
// kubernetes-models@5`. Exit 0: valid (prints the package version);
// 1: invalid (the validator's messages on stderr); 2: usage or unreadable
// manifest; 3: the script failed; 77: the validator could not be loaded
// (not installed, or this node cannot run it).
//
// Unknown fields: the generated schemas are open (no additionalProperties:
// false) and the package has no strict option, so on its own it accepts a
// misspelled field that a server with strict field validation (kubectl's
// default) rejects. The validator itself is therefore asked whether each
// field of the manifest is in its schema: the field's value is replaced by
// a value of no JSON type, which every typed schema rejects at exactly that
// place; a field whose replacement draws no error there is unknown to the
// schema. (A field the schema leaves untyped would be reported unknown too:
// the check errs towards rejecting, never towards accepting.)
import { readFileSync } from "node:fs";
import { join } from "node:path";
import { pathToFileURL } from "node:url";

process.on("uncaughtException", (e) => {
  console.error(`validate_k8s_job.mjs failed: ${e.stack}`);
  process.exit(3);
});
if (process.argv.length !== 4) {
  console.error("usage: node validate_k8s_job.mjs NPM_PREFIX MANIFEST.json");
  process.exit(2);
}
const [prefix, file] = process.argv.slice(2);
const packageDir = join(prefix, "node_modules", "kubernetes-models");

let Job, version;
try {
  version = JSON.parse(readFileSync(join(packageDir, "package.json"), "utf8")).version;
  ({ Job } = await import(pathToFileURL(join(packageDir, "batch", "v1", "Job.js")).href));
} catch (e) {
  console.error(`cannot load kubernetes-models from ${prefix}: ${e.message}`);
  process.exit(77);
}
if (!version.startsWith("5.")) {
  console.error(`kubernetes-models ${version} in ${prefix}, expected major version 5`);
  process.exit(77);
}

let manifest;
try {
  manifest = JSON.parse(readFileSync(file, "utf8"));
} catch (e) {
  console.error(`${file}: ${e.message}`);
  process.exit(2);
}

// The validator's verdict on a manifest: null when valid, else its
// ValidationError (message, and errors with their instancePath).
function check(doc) {
  try {
    new Job(doc).validate();
    return null;
  } catch (e) {
    if (!Array.isArray(e.errors)) throw e;
    return e;
  }
}

const invalid = check(manifest);
if (invalid) {
  console.error(`${file}: invalid (kubernetes-models ${version}): ${invalid.message}`);
  process.exit(1);
}

// JSON pointer of a place, as the validator's instancePath writes it.
const pointer = (path) => path.map((k) => "/" + String(k).replaceAll("~", "~0").replaceAll("/", "~1")).join("");

const unknown = [];
function visit(node, path) {
  if (Array.isArray(node)) {
    node.forEach((child, i) => visit(child, [...path, i]));
    return;
  }
  if (node === null || typeof node !== "object") return;
  for (const key of Object.keys(node)) {
    const probe = structuredClone(manifest);
    let parent = probe;
    for (const k of path) parent = parent[k];
    parent[key] = Symbol("not JSON");
    const where = pointer([...path, key]);
    if (!(check(probe)?.errors ?? []).some((e) => e.instancePath === where)) unknown.push(where);
    else visit(node[key], [...path, key]);
  }
}
visit(manifest, []);
if (unknown.length > 0) {
  console.error(`${file}: invalid (kubernetes-models ${version}): unknown field(s) ${unknown.join(", ")}`);
  process.exit(1);
}
console.log(`${file}: valid (kubernetes-models ${version})`);
