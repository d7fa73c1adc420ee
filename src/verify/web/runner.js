// Runs one verification job in the browser: a selecting WGSL kernel through WebGPU
// (Tint, then the adapter's driver), or a GLSL ES 3.00 vertex shader through WebGL 2
// (ANGLE), over a job's input words, returning its output words. Shared by the suite's
// harness (harness.js, jobs served on 127.0.0.1) and `unitpack verify --web` (page.js,
// jobs embedded in the page).
"use strict";

const unitpack = (() => {
  let device = null;
  let deviceError = null;
  let adapterInfo = null;
  let layout = null;
  // The compiled module of the kernel last used: a spec's functions come one after the
  // other, so each WGSL include is compiled once.
  let lastModule = { key: null };

  async function gpu() {
    if (device) return device;
    if (deviceError) throw new Error(deviceError);
    if (!navigator.gpu) {
      deviceError = "this browser has no WebGPU (navigator.gpu is undefined)";
      throw new Error(deviceError);
    }
    const adapter = await navigator.gpu.requestAdapter();
    if (!adapter) {
      deviceError = "WebGPU offers no adapter";
      throw new Error(deviceError);
    }
    const i = adapter.info || {};
    adapterInfo = {
      vendor: i.vendor || "",
      architecture: i.architecture || "",
      device: i.device || "",
      description: i.description || "",
      fallback: !!i.isFallbackAdapter,
    };
    device = await adapter.requestDevice({
      requiredLimits: {
        maxStorageBufferBindingSize: adapter.limits.maxStorageBufferBindingSize,
        maxBufferSize: adapter.limits.maxBufferSize,
      },
    });
    device.lost.then((l) => {
      deviceError = "the WebGPU device was lost: " + l.message;
      device = null;
    });
    const entry = (binding, type) => ({
      binding,
      visibility: GPUShaderStage.COMPUTE,
      buffer: { type },
    });
    const group = device.createBindGroupLayout({
      entries: [entry(0, "read-only-storage"), entry(1, "storage")],
    });
    layout = device.createPipelineLayout({ bindGroupLayouts: [group] });
    return device;
  }

  function where(m) {
    return m.lineNum ? `${m.lineNum}:${m.linePos} ` : "";
  }

  // Tint's verdict on a WGSL module: the module, and its errors or null.
  async function validate(d, source) {
    d.pushErrorScope("validation");
    const module = d.createShaderModule({ code: source });
    const info = await module.getCompilationInfo();
    const scoped = await d.popErrorScope();
    const errors = info.messages
      .filter((m) => m.type === "error")
      .map((m) => where(m) + m.message);
    const error = errors.length
      ? errors.join("\n")
      : scoped
        ? scoped.message
        : null;
    return { module, error };
  }

  async function moduleOf(d, job) {
    if (lastModule.key === job.key) return lastModule;
    lastModule = { key: job.key, ...(await validate(d, job.source)) };
    return lastModule;
  }

  // A WebGPU job: `source` is a selecting kernel whose override 0 picks the function.
  async function runWebGpu(job) {
    const d = await gpu();
    const m = await moduleOf(d, job);
    if (m.error) throw new Error("WebGPU (Tint) rejects the WGSL: " + m.error);
    const n = job.input.length / job.in_words;
    const groups = Math.ceil(n / 64);
    if (groups > 65535) throw new Error(`${n} items exceed one dispatch`);
    d.pushErrorScope("validation");
    const pipeline = await d.createComputePipelineAsync({
      layout,
      compute: { module: m.module, entryPoint: "main", constants: { 0: job.selector } },
    });
    const bytes = (w) => Math.max(4, w * 4);
    const input = d.createBuffer({
      size: bytes(job.input.length),
      usage: GPUBufferUsage.STORAGE,
      mappedAtCreation: true,
    });
    new Uint32Array(input.getMappedRange()).set(job.input);
    input.unmap();
    const outWords = n * job.out_words;
    const output = d.createBuffer({
      size: bytes(outWords),
      usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC,
    });
    const read = d.createBuffer({
      size: bytes(outWords),
      usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST,
    });
    const group = d.createBindGroup({
      layout: pipeline.getBindGroupLayout(0),
      entries: [
        { binding: 0, resource: { buffer: input } },
        { binding: 1, resource: { buffer: output, size: outWords * 4 } },
      ],
    });
    const enc = d.createCommandEncoder();
    const pass = enc.beginComputePass();
    pass.setPipeline(pipeline);
    pass.setBindGroup(0, group);
    pass.dispatchWorkgroups(groups);
    pass.end();
    enc.copyBufferToBuffer(output, 0, read, 0, bytes(outWords));
    d.queue.submit([enc.finish()]);
    const scoped = await d.popErrorScope();
    if (scoped) throw new Error("WebGPU: " + scoped.message);
    await read.mapAsync(GPUMapMode.READ);
    const out = new Uint32Array(read.getMappedRange().slice(0, outWords * 4));
    read.unmap();
    for (const b of [input, output, read]) b.destroy();
    return out;
  }

  let gl = null;
  let glError = null;

  function webgl() {
    if (gl) return gl;
    if (glError) throw new Error(glError);
    gl = document.createElement("canvas").getContext("webgl2");
    if (!gl) {
      glError = "this browser has no WebGL 2";
      throw new Error(glError);
    }
    return gl;
  }

  function shader(g, type, source, what) {
    const s = g.createShader(type);
    g.shaderSource(s, source);
    g.compileShader(s);
    const log = (g.getShaderInfoLog(s) || "").trim();
    if (!g.getShaderParameter(s, g.COMPILE_STATUS)) {
      g.deleteShader(s);
      throw new Error(`WebGL (ANGLE) rejects the ${what}: ${log}`);
    }
    if (log) {
      g.deleteShader(s);
      throw new Error(`WebGL (ANGLE) warns on the ${what}: ${log}`);
    }
    return s;
  }

  // A WebGL 2 job: `source` is a GLSL ES 3.00 vertex shader reading an item's words from
  // integer attributes `unitpack_in_K` (four words each) and writing its output words to
  // flat `unitpack_out_K`, captured by transform feedback.
  function runWebGl(job) {
    const g = webgl();
    const n = job.input.length / job.in_words;
    const ins = Math.ceil(job.in_words / 4);
    const outs = Math.ceil(job.out_words / 4);
    const vs = shader(g, g.VERTEX_SHADER, job.source, "GLSL");
    const fs = shader(
      g,
      g.FRAGMENT_SHADER,
      "#version 300 es\nvoid main() {}\n",
      "empty fragment shader",
    );
    const p = g.createProgram();
    g.attachShader(p, vs);
    g.attachShader(p, fs);
    const names = Array.from({ length: outs }, (_, k) => "unitpack_out_" + k);
    g.transformFeedbackVaryings(p, names, g.INTERLEAVED_ATTRIBS);
    g.linkProgram(p);
    g.deleteShader(vs);
    g.deleteShader(fs);
    if (!g.getProgramParameter(p, g.LINK_STATUS)) {
      const log = g.getProgramInfoLog(p);
      g.deleteProgram(p);
      throw new Error("WebGL (ANGLE) cannot link the program: " + log);
    }
    const vao = g.createVertexArray();
    g.bindVertexArray(vao);
    const inBuf = g.createBuffer();
    g.bindBuffer(g.ARRAY_BUFFER, inBuf);
    g.bufferData(g.ARRAY_BUFFER, job.input, g.STATIC_DRAW);
    for (let k = 0; k < ins; k++) {
      g.enableVertexAttribArray(k);
      const size = Math.min(4, job.in_words - 4 * k);
      g.vertexAttribIPointer(k, size, g.UNSIGNED_INT, job.in_words * 4, 16 * k);
    }
    const tf = g.createBuffer();
    g.bindBuffer(g.TRANSFORM_FEEDBACK_BUFFER, tf);
    g.bufferData(g.TRANSFORM_FEEDBACK_BUFFER, n * outs * 16, g.STATIC_READ);
    const feedback = g.createTransformFeedback();
    g.bindTransformFeedback(g.TRANSFORM_FEEDBACK, feedback);
    g.bindBufferBase(g.TRANSFORM_FEEDBACK_BUFFER, 0, tf);
    g.useProgram(p);
    g.enable(g.RASTERIZER_DISCARD);
    g.beginTransformFeedback(g.POINTS);
    g.drawArrays(g.POINTS, 0, n);
    g.endTransformFeedback();
    g.disable(g.RASTERIZER_DISCARD);
    g.bindTransformFeedback(g.TRANSFORM_FEEDBACK, null);
    const padded = new Uint32Array(n * outs * 4);
    g.bindBuffer(g.TRANSFORM_FEEDBACK_BUFFER, tf);
    g.getBufferSubData(g.TRANSFORM_FEEDBACK_BUFFER, 0, padded);
    const err = g.getError();
    g.bindBuffer(g.TRANSFORM_FEEDBACK_BUFFER, null);
    g.bindBuffer(g.ARRAY_BUFFER, null);
    g.bindVertexArray(null);
    g.deleteTransformFeedback(feedback);
    g.deleteBuffer(tf);
    g.deleteBuffer(inBuf);
    g.deleteVertexArray(vao);
    g.deleteProgram(p);
    if (err !== g.NO_ERROR) throw new Error("WebGL error 0x" + err.toString(16));
    const out = new Uint32Array(n * job.out_words);
    for (let i = 0; i < n; i++) {
      out.set(padded.subarray(i * outs * 4, i * outs * 4 + job.out_words), i * job.out_words);
    }
    return out;
  }

  // What runs the jobs, for the report's adapter line.
  async function describe() {
    const d = {};
    try {
      await gpu();
      d.webgpu = adapterInfo;
    } catch (e) {
      d.webgpu = null;
      d.webgpu_error = String(e.message || e);
    }
    try {
      const g = webgl();
      const ext = g.getExtension("WEBGL_debug_renderer_info");
      d.webgl = g.getParameter(ext ? ext.UNMASKED_RENDERER_WEBGL : g.RENDERER);
    } catch (e) {
      d.webgl = null;
      d.webgl_error = String(e.message || e);
    }
    d.user_agent = navigator.userAgent;
    return d;
  }

  // A compilation only: a WGSL module validated by Tint, or a GLSL ES 3.00 vertex shader
  // compiled by ANGLE with an empty info log. Returns no words.
  async function compile(job) {
    if (job.api === "webgpu") {
      const m = await validate(await gpu(), job.source);
      if (m.error) throw new Error("WebGPU (Tint) rejects the WGSL: " + m.error);
    } else {
      const g = webgl();
      g.deleteShader(shader(g, g.VERTEX_SHADER, job.source, "GLSL"));
    }
    return new Uint32Array(0);
  }

  function run(job) {
    if (job.compile) return compile(job);
    return job.api === "webgpu" ? runWebGpu(job) : Promise.resolve().then(() => runWebGl(job));
  }

  return { run, describe };
})();
