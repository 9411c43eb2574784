// Runs the Khronos glTF validator (npm gltf-validator) over the files given; prints each file's
// counts and messages, and exits 1 if any file has an error. Warnings and infos are printed for
// a reader to weigh (an extension the validator does not know, such as MSFT_lod, is an info).
import validator from 'gltf-validator';
import fs from 'fs';

let bad = 0;
for (const file of process.argv.slice(2)) {
  const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)),
                                               {maxIssues: 100});
  const i = report.issues;
  console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ` +
              `${i.numInfos} infos, ${i.numHints} hints`);
  const names = ['error', 'warning', 'info', 'hint'];
  for (const m of i.messages)
    console.log(`  ${names[m.severity]} ${m.code} ${m.pointer || ''}: ${m.message}`);
  if (i.numErrors) bad++;
}
process.exit(bad ? 1 : 0);
