// The suite's side of the browser paths: asks the verifier on 127.0.0.1 for jobs one at a
// time and posts back each job's output words (or why it could not run). A job is one
// little-endian u32 giving the length of a JSON header, the header, padding to four bytes,
// then the input words.
"use strict";

(async () => {
  const post = (path, body) => fetch(path, { method: "POST", body });
  await post("/hello", JSON.stringify(await unitpack.describe()));
  for (;;) {
    let r;
    try {
      r = await fetch("/job");
    } catch (e) {
      return; // The verifier has gone.
    }
    if (r.status === 204) continue; // No job yet: ask again.
    if (r.status !== 200) return;
    const buf = await r.arrayBuffer();
    const len = new DataView(buf).getUint32(0, true);
    const job = JSON.parse(new TextDecoder().decode(new Uint8Array(buf, 4, len)));
    job.input = new Uint32Array(buf, (4 + len + 3) & ~3);
    try {
      const out = await unitpack.run(job);
      await post("/output/" + job.id, out);
    } catch (e) {
      await post("/error/" + job.id, String((e && e.message) || e));
    }
  }
})();
