// The Khronos glTF validator on each file named: one JSON line per file with its path
// and the validator's issue counts and messages, as tests/cli/gltf.rs reads them.
// Usage: node validate.mjs FILE...
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import validator from 'gltf-validator';

for (const file of process.argv.slice(2)) {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    externalResourceFunction: (uri) =>
      readFile(path.join(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
  });
  const messages = report.issues.messages.map((m) => ({
    code: m.code, severity: m.severity, pointer: m.pointer, message: m.message,
  }));
  console.log(JSON.stringify({
    file,
    errors: report.issues.numErrors,
    warnings: report.issues.numWarnings,
    messages,
  }));
}
