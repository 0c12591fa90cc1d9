// Validates glTF 2.0 files with the Khronos glTF validator:
//   node validate_gltf.cjs FILE...
// Prints each file's issue counts and every message; exits 1 when any file
// has an error, a warning, or an info that argil's meshes must not give
// (degenerate triangles), 2 on a bad call.
"use strict";
const fs = require("fs");
const path = require("path");
const validator = require("gltf-validator");

// Infos that still mean a broken mesh.
const REFUSED_INFOS = new Set(["ACCESSOR_INDEX_TRIANGLE_DEGENERATE"]);
const SEVERITY = ["error", "warning", "info", "hint"];

async function validate(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0, // all of them: a refused info must not hide behind the others
  });
  const issues = report.issues;
  console.log(
    `${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
      `${issues.numInfos} infos, ${issues.numHints} hints`
  );
  let refused = 0;
  const quiet = new Map(); // infos and hints that are fine, counted by code
  for (const m of issues.messages) {
    if (m.severity <= 1 || REFUSED_INFOS.has(m.code)) {
      console.log(`  ${SEVERITY[m.severity]} ${m.code} at ${m.pointer || "-"}: ${m.message}`);
      if (m.severity > 1) ++refused;
    } else {
      quiet.set(m.code, (quiet.get(m.code) || 0) + 1);
    }
  }
  for (const [code, count] of quiet) console.log(`  ${count} x ${code}`);
  return issues.numErrors === 0 && issues.numWarnings === 0 && refused === 0;
}

async function main() {
  const files = process.argv.slice(2);
  if (files.length === 0) {
    console.error("usage: node validate_gltf.cjs FILE...");
    process.exit(2);
  }
  let ok = true;
  for (const file of files) ok = (await validate(file)) && ok;
  process.exit(ok ? 0 : 1);
}

main().catch((e) => {
  console.error(`validate_gltf: ${e.message}`);
  process.exit(2);
});
