// Links each WESL module named on the command line with npm's `wesl` linker, as a
// JavaScript application would (`link` from "wesl/core", the module its own root), and
// prints one JSON line per module: {"file", "ok", "error"}. Run by tests/wesl.rs.
import { link } from "wesl/core";
import { readFileSync } from "node:fs";
import { basename } from "node:path";

for (const file of process.argv.slice(2)) {
  const name = basename(file, ".wesl");
  let error = null;
  try {
    const linked = await link({
      weslSrc: { [`./${name}.wesl`]: readFileSync(file, "utf8") },
      rootModuleName: name,
    });
    if (!linked.dest.includes("fn ")) error = "linked to no functions";
  } catch (e) {
    error = String(e && e.message ? e.message : e).split("\n")[0];
  }
  console.log(JSON.stringify({ file, ok: error === null, error }));
}
