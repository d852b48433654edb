// Usage: node tests/io/validate_gltf.js FILE.glb...
//
// Validates each file with the Khronos glTF validator (npm package
// gltf-validator, found through NODE_PATH) and prints its issue counts; exit 1
// if any file has an error (warnings, infos and hints are printed, not
// failures), 2 if the validator is not installed.
'use strict';
const fs = require('fs');
let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.error('gltf-validator is not installed (scripts/setup.sh installs ' +
                'it into build/node; NODE_PATH=' + process.env.NODE_PATH + ')');
  process.exit(2);
}

async function main(files) {
  let failed = 0;
  for (const file of files) {
    const report = await validator.validateBytes(
        new Uint8Array(fs.readFileSync(file)), {maxIssues: 100});
    const i = report.issues;
    console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ` +
                `${i.numInfos} infos, ${i.numHints} hints ` +
                `(validator ${report.validatorVersion})`);
    for (const m of i.messages) {
      console.log(`  ${['error', 'warning', 'info', 'hint'][m.severity]} ` +
                  `${m.code} at ${m.pointer || ''}: ${m.message}`);
    }
    if (i.numErrors > 0) failed++;
  }
  process.exit(failed ? 1 : 0);
}

if (process.argv.length < 3) {
  console.error('usage: node validate_gltf.js FILE.glb...');
  process.exit(2);
}
main(process.argv.slice(2)).catch((e) => {
  console.error(e);
  process.exit(1);
});
