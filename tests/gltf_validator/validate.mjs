// Runs the Khronos glTF-Validator (npm package gltf-validator, pinned in
// package-lock.json) on every file named on the command line and fails when
// any file has an error or a warning. Infos and hints are printed but allowed.
//
//   node validate.mjs FILE.glb FILE.gltf ...
//
// Exit status: 0 all files clean, 1 some file has errors or warnings (or could
// not be read or parsed), 2 usage error or the validator is not installed.
import { readFile } from 'node:fs/promises';
import { basename } from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
let validator;
try {
  validator = require('gltf-validator');
} catch (error) {
  console.error(
    'validate.mjs: the npm package gltf-validator is not installed next to this script ' +
      `(${error.code ?? error.message}). Install it with: ` +
      '(cd tests/gltf_validator && npm ci)  -- .ci/setup does this.');
  process.exit(2);
}

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error('usage: node validate.mjs FILE.glb|FILE.gltf ...');
  process.exit(2);
}

const severityNames = ['error', 'warning', 'info', 'hint'];
// Extension name -> how many files the validator reported it in as
// UNSUPPORTED_EXTENSION (an info: it does not check what the extension holds).
const unsupported = new Map();

// Validates one file; returns true when it has no errors and no warnings.
async function validateFile(path) {
  let bytes;
  try {
    bytes = new Uint8Array(await readFile(path));
  } catch (error) {
    console.log(`FAIL ${path}: cannot read: ${error.message}`);
    return false;
  }
  let report;
  try {
    report = await validator.validateBytes(bytes, {
      uri: basename(path),
      maxIssues: 0,  // report every issue
      writeTimestamp: false,
      // Our files never reference external resources (GLB chunk or data URI),
      // so any external URI is a failure, not something to load.
      externalResourceFunction: (uri) => Promise.reject(new Error(`external resource ${uri}`)),
    });
  } catch (error) {
    console.log(`FAIL ${path}: the validator could not parse it: ${error}`);
    return false;
  }
  const { numErrors, numWarnings, numInfos, numHints, messages } = report.issues;
  const clean = numErrors === 0 && numWarnings === 0;
  const info = report.info ?? {};
  console.log(
    `${clean ? 'ok  ' : 'FAIL'} ${path}: ${numErrors} errors, ${numWarnings} warnings, ` +
      `${numInfos} infos, ${numHints} hints (${info.drawCallCount ?? '?'} draw calls, ` +
      `${info.totalVertexCount ?? '?'} vertices, ${info.totalTriangleCount ?? '?'} triangles)`);
  for (const m of messages) {
    console.log(`       ${severityNames[m.severity] ?? m.severity} ${m.code} at ${m.pointer ?? m.offset ?? '?'}: ${m.message}`);
    const name = m.code === 'UNSUPPORTED_EXTENSION' ? /'([^']+)'/.exec(m.message)?.[1] : undefined;
    if (name) unsupported.set(name, (unsupported.get(name) ?? 0) + 1);
  }
  return clean;
}

console.log(`Khronos glTF-Validator ${validator.version()}, ${files.length} files`);
let failed = 0;
for (const file of files) {
  if (!(await validateFile(file))) ++failed;
}
for (const [name, count] of [...unsupported].sort()) {
  console.log(`not validated: ${name} in ${count} files (UNSUPPORTED_EXTENSION)`);
}
if (failed > 0) {
  console.log(`${failed} of ${files.length} files have glTF errors or warnings`);
  process.exit(1);
}
console.log(`all ${files.length} files pass with zero errors and zero warnings`);
