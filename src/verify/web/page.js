// `unitpack verify --web`: runs the embedded catalogue through this browser's WebGPU and
// compares the outputs with the model's, function by function. Packed outputs: two hashes
// of every word, and the first items' words to locate a mismatch. Float outputs: every
// word, the largest difference, and the function's proven bound where it has one. The
// result can be saved in `unitpack verify --json`'s shape; served over http(s), the page
// also posts it to /report (the suite reads it there).
"use strict";

(async () => {
  const data = JSON.parse(document.getElementById("unitpack-data").textContent);
  const $ = (id) => document.getElementById(id);
  const words = (b64) => {
    const s = atob(b64);
    const bytes = new Uint8Array(s.length);
    for (let i = 0; i < s.length; i++) bytes[i] = s.charCodeAt(i);
    return new Uint32Array(bytes.buffer);
  };
  // The same two hashes as src/verify/web.rs.
  const hashes = (w) => {
    let a = 0x811c9dc5,
      b = 0x9e3779b9;
    for (let i = 0; i < w.length; i++) {
      a = Math.imul(a ^ w[i], 0x01000193) >>> 0;
      b = Math.imul(b ^ w[i], 0x5bd1e995) >>> 0;
      b = ((b << 13) | (b >>> 19)) >>> 0;
    }
    return [a, b];
  };
  const f32 = new Float32Array(1);
  const u32 = new Uint32Array(f32.buffer);
  const asFloat = (w) => ((u32[0] = w), f32[0]);
  // |a - b| as the verifier's report defines it: 0 for two NaNs or zeros of either sign,
  // infinite when one side is NaN or their infinities differ.
  const difference = (x, y) => {
    const a = asFloat(x),
      b = asFloat(y);
    if (Number.isNaN(a) && Number.isNaN(b)) return 0;
    if (Number.isNaN(a) || Number.isNaN(b)) return Infinity;
    if (a === b) return 0;
    const d = Math.abs(a - b);
    return Number.isNaN(d) ? Infinity : d;
  };
  const hex = (w) => "0x" + (w >>> 0).toString(16).padStart(8, "0");
  const show = (ws, isFloat) =>
    Array.from(ws, (w) => (isFloat ? `${asFloat(w)} (${hex(w)})` : hex(w))).join(", ");

  const describe = await unitpack.describe();
  const gpu = describe.webgpu;
  const adapter = gpu
    ? `${gpu.vendor} ${gpu.architecture} ${gpu.device} ${gpu.description}`.replace(/\s+/g, " ").trim() +
      (gpu.fallback ? " (fallback adapter)" : "")
    : "none";
  $("adapter").textContent = `WebGPU adapter: ${adapter}. ${describe.user_agent}`;
  const rows = [];
  let failed = 0,
    items = 0;

  const addRow = (row, cls, result, details) => {
    const tr = document.createElement("tr");
    for (const [text, c] of [[row.spec], [row.function], [result, cls], [details]]) {
      const td = document.createElement("td");
      if (c) td.className = c;
      if (text.includes("\n")) {
        const pre = document.createElement("pre");
        pre.textContent = text;
        td.appendChild(pre);
      } else td.textContent = text;
      tr.appendChild(td);
    }
    $("rows").appendChild(tr);
  };

  for (const s of data.specs) {
    for (const f of s.functions) {
      const input = words(f.input);
      const n = input.length / f.in_words;
      const row = {
        spec: s.spec,
        function: f.name,
        path: "wgsl/webgpu",
        tested: n,
        mismatches: 0,
        passed: true,
        error: null,
        first_mismatches: [],
        same_code_as: null,
        largest_difference: null,
        largest_at: null,
        measured: false,
      };
      const item = (k, expected, actual) => ({
        input: Array.from(input.subarray(k * f.in_words, (k + 1) * f.in_words)),
        expected: Array.from(expected),
        actual: Array.from(actual),
        input_float: f.input_float,
        output_float: f.output_float,
      });
      let out;
      try {
        out = await unitpack.run({
          api: "webgpu",
          key: s.spec,
          source: s.wgsl,
          selector: f.selector,
          in_words: f.in_words,
          out_words: f.out_words,
          input,
        });
      } catch (e) {
        row.error = String((e && e.message) || e);
      }
      let cls = "pass",
        result = "pass",
        details = "";
      if (row.error) {
        row.passed = false;
        cls = "fail";
        result = "ERROR";
        details = row.error;
      } else if (f.output_float) {
        const want = words(f.expected);
        let largest = -1;
        for (let k = 0; k < n; k++) {
          const w = want.subarray(k * f.out_words, (k + 1) * f.out_words);
          const g = out.subarray(k * f.out_words, (k + 1) * f.out_words);
          let same = true,
            d = 0;
          for (let j = 0; j < f.out_words; j++) {
            if (w[j] !== g[j]) {
              same = false;
              d = Math.max(d, difference(w[j], g[j]));
            }
          }
          if (same) continue;
          row.mismatches++;
          if (row.first_mismatches.length < 5) row.first_mismatches.push(item(k, w, g));
          if (d > largest) {
            largest = d;
            row.largest_at = item(k, w, g);
          }
        }
        if (row.mismatches > 0) {
          row.largest_difference = Number.isFinite(largest) ? largest : null;
          if (f.bound !== null && largest <= f.bound) {
            result = "within bound";
            details = `${row.mismatches} of ${n} differ; largest ${largest.toExponential(3)} ≤ proven bound ${f.bound.toExponential(3)}`;
          } else if (f.bound === null) {
            row.measured = true;
            cls = "measured";
            result = "measured";
            details = `${row.mismatches} of ${n} differ; largest ${largest.toExponential(3)} (no proven bound: a float form, exact only where denormals are kept and nothing is contracted)`;
          } else {
            row.passed = false;
            cls = "fail";
            result = "FAIL";
            details = `largest difference ${largest.toExponential(3)} exceeds the proven bound ${f.bound.toExponential(3)}`;
          }
        }
      } else {
        const h = hashes(out);
        if (h[0] !== f.hashes[0] || h[1] !== f.hashes[1]) {
          row.passed = false;
          cls = "fail";
          result = "FAIL";
          const head = words(f.head);
          const m = Math.min(n, head.length / f.out_words);
          for (let k = 0; k < m; k++) {
            const w = head.subarray(k * f.out_words, (k + 1) * f.out_words);
            const g = out.subarray(k * f.out_words, (k + 1) * f.out_words);
            if (w.some((x, j) => x !== g[j])) {
              row.mismatches++;
              if (row.first_mismatches.length < 5) row.first_mismatches.push(item(k, w, g));
            }
          }
          if (row.mismatches === 0) {
            row.mismatches = 1;
            details = `the outputs differ beyond the first ${m} items (their hash differs)`;
          } else {
            details = `${row.mismatches} of the first ${m} items differ`;
          }
          if (f.lean) {
            // The lean tier promises its codes only where denormals are kept; this
            // browser's adapter may flush them.
            row.passed = true;
            row.measured = true;
            cls = "measured";
            result = "measured";
            details += " (the lean tier: exact only where denormals are kept)";
          }
        }
      }
      if (row.first_mismatches.length && (cls === "fail" || cls === "measured")) {
        details +=
          "\n" +
          row.first_mismatches
            .map(
              (m) =>
                `input [${show(m.input, m.input_float)}]\n  expected [${show(m.expected, m.output_float)}]\n  actual   [${show(m.actual, m.output_float)}]`,
            )
            .join("\n");
      }
      if (!row.passed) failed++;
      items += n;
      rows.push(row);
      addRow(row, cls, result, details);
      $("summary").textContent = `${rows.length} functions run, ${failed} failed…`;
    }
  }
  const report = {
    adapter: "WebGPU: " + adapter,
    driver: describe.user_agent,
    passed: failed === 0,
    checks: rows.length,
    items,
    failed,
    rows,
  };
  const json = JSON.stringify(report, null, 2) + "\n";
  $("summary").textContent = `${rows.length} functions run, ${items} items, ${failed} failed.`;
  const save = $("save");
  save.disabled = false;
  save.onclick = () => {
    const a = document.createElement("a");
    a.href = URL.createObjectURL(new Blob([json], { type: "application/json" }));
    a.download = "unitpack-verify.json";
    a.click();
  };
  document.title = (failed ? "FAILED" : "passed") + ": unitpack verify";
  if (location.protocol.startsWith("http")) {
    fetch("/report", { method: "POST", body: json }).catch(() => {});
  }
})();
