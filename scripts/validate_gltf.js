// Validates glTF/GLB files with the Khronos glTF-Validator (npm package gltf-validator).
// usage: node validate_gltf.js FILE...   (NODE_PATH must reach gltf-validator)
// Prints one line per file with the issue counts (and the first 5 errors/warnings); exits 1 if any
// file has an error, 0 otherwise.
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

async function validate(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 100,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)), (err, data) =>
          err ? reject(err.toString()) : resolve(new Uint8Array(data)));
      }),
  });
  const i = report.issues;
  console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ` +
              `${i.numHints} hints (validator ${report.validatorVersion})`);
  let shown = 0;
  for (const m of i.messages) {
    if (m.severity <= 1 && shown < 5) {
      console.log(`  ${m.severity === 0 ? 'error' : 'warning'} ${m.code}: ${m.message} (${m.pointer || ''})`);
      ++shown;
    }
  }
  return i.numErrors;
}

(async () => {
  const files = process.argv.slice(2);
  if (files.length === 0) {
    console.error('usage: validate_gltf.js FILE...');
    process.exit(2);
  }
  let errors = 0;
  for (const f of files) {
    try {
      errors += await validate(f);
    } catch (e) {
      console.log(`${f}: cannot validate: ${e}`);
      errors += 1;
    }
  }
  process.exit(errors > 0 ? 1 : 0);
})();
