#!/usr/bin/env python3
"""Checks generated GLSL under an OpenGL driver's own GLSL compiler (Mesa's llvmpipe, or a
GPU's), through EGL, with and without `#define UNITPACK_PRECISE precise`:

1. float16x3 and float32x3 decode on hostile codes (NaN, infinite, zero and denormal
   halves and floats in every combination, and 2^20 random codes), against their
   definition (the stored floats, or +Z; float32 denormals read as +0);
2. every packed encoder with a `vec3` input on hostile vectors (every combination of 18
   special values), 65536 random and 16384 small-integer vectors, against the model
   (`unitpack encode SPEC --format binary`).

Usage: python3 tools/mesa_gl_check.py generated/glsl target/release/unitpack [DIFFS.tsv]
(DIFFS.tsv: every differing item, one per line: what, input words, driver's words, model's)
Needs: pip install moderngl numpy; Mesa's EGL and GL drivers (Debian: libegl1 libegl-mesa0
libgl1-mesa-dri). Exits 1 if anything differs. Stands in for a verify path until
`unitpack verify` runs OpenGL itself.
"""
import glob, re, subprocess, sys

import moderngl
import numpy as np

inc_dir, exe = sys.argv[1], sys.argv[2]
diffs = open(sys.argv[3], "w") if len(sys.argv) > 3 else None
ctx = moderngl.create_standalone_context(backend="egl", require=430)
print(ctx.info["GL_RENDERER"], ctx.info["GL_VERSION"])
differing = 0


def dispatch(src, precise, body, words_in, words_out, items):
    pre = "#define UNITPACK_PRECISE precise\n" if precise else ""
    cs = f"""#version 430
layout(local_size_x = 64) in;
{pre}{src}
layout(std430, binding = 0) readonly buffer I {{ uint i[]; }};
layout(std430, binding = 1) writeonly buffer O {{ uint o[]; }};
void main() {{ uint n = gl_GlobalInvocationID.x; {body} }}"""
    prog = ctx.compute_shader(cs)
    pad = (-len(items)) % 64
    data = np.concatenate([items, np.zeros((pad, words_in), np.uint32)]).astype(np.uint32)
    bi, bo = ctx.buffer(data.tobytes()), ctx.buffer(reserve=len(data) * 4 * words_out)
    bi.bind_to_storage_buffer(0)
    bo.bind_to_storage_buffer(1)
    prog.run(group_x=len(data) // 64)
    got = np.frombuffer(bo.read(), np.uint32).reshape(-1, words_out)[: len(items)]
    bi.release(), bo.release(), prog.release()
    return got


def report(what, items, got, want):
    global differing
    bad = np.nonzero((got != want).any(1))[0]
    differing += len(bad)
    line = f"{what}: {len(bad)} of {len(items)} differ"
    hx = lambda w: " ".join(f"{x:08x}" for x in w)
    if len(bad):
        i = bad[0]
        line += f"; e.g. {hx(items[i])} -> {hx(got[i])}, model {hx(want[i])}"
    for i in bad if diffs else []:
        diffs.write(f"{what}\t{hx(items[i])}\t{hx(got[i])}\t{hx(want[i])}\n")
    print(line, flush=True)


rng = np.random.default_rng(1)

# 1. float16x3 / float32x3 decode on hostile codes.
def halves_model(h):
    f = h.astype(np.uint16).view(np.float16).astype(np.float32)
    bad = ~np.isfinite(f).all(1) | (f == 0).all(1)
    out = f.copy()
    out[bad] = [0, 0, 1]
    return out.view(np.uint32)


def singles_model(w):
    f = w.view(np.float32)
    f = np.where(np.abs(f) < np.float32(1.1754944e-38), np.float32(0), f)
    bad = ~np.isfinite(f).all(1) | (f == 0).all(1)
    out = f.astype(np.float32).copy()
    out[bad] = [0, 0, 1]
    return out.view(np.uint32)


sp16 = np.array([0x7C00, 0xFC00, 0x7C01, 0x7E00, 0x7FFF, 0xFC01, 0xFE00, 0xFFFF, 0, 0x8000,
                 0x3C00, 0xBC00, 0x0001, 0x8001, 0x3555, 0x7BFF], np.uint32)
h = np.concatenate([np.array(np.meshgrid(sp16, sp16, sp16)).reshape(3, -1).T,
                    rng.integers(0, 1 << 16, size=(1 << 20, 3), dtype=np.uint32)])
codes16 = np.stack([h[:, 0] | (h[:, 1] << 16), h[:, 2]], 1).astype(np.uint32)
sp32 = np.array([0x7F800000, 0xFF800000, 0x7F800001, 0x7FC00000, 0xFFFFFFFF, 0, 0x80000000,
                 0x3F800000, 0xBF800000, 1, 0x80000001, 0x007FFFFF, 0x00800000, 0x7F7FFFFF], np.uint32)
codes32 = np.concatenate([np.array(np.meshgrid(sp32, sp32, sp32)).reshape(3, -1).T,
                          rng.integers(0, 1 << 32, size=(1 << 20, 3), dtype=np.uint64)]).astype(np.uint32)
store = "o[n*3u] = floatBitsToUint(d.x); o[n*3u+1u] = floatBitsToUint(d.y); o[n*3u+2u] = floatBitsToUint(d.z);"
for spec, ty, k, codes, want in [("float16x3", "uvec2", 2, codes16, halves_model(h)),
                                 ("float32x3", "uvec3", 3, codes32, singles_model(codes32))]:
    src = open(f"{inc_dir}/{spec}.glsl").read()
    load = f"{ty}({', '.join(f'i[n*{k}u+{j}u]' for j in range(k))})"
    for precise in (False, True):
        got = dispatch(src, precise, f"vec3 d = unitpack_{spec}_decode({load}); {store}", k, 3, codes)
        report(f"{spec} decode, precise={precise}", codes, got, want)

# 2. Every packed encoder with a vec3 input.
sp = np.array([0, 0x80000000, 0x7FC00000, 0xFFC00000, 0x7F800001, 0x7F800000, 0xFF800000, 0x7F7FFFFF,
               0xFF7FFFFF, 1, 0x80000001, 0x007FFFFF, 0x00800000, 0x3F800000, 0xBF800000, 0x3F000000,
               0x3F3504F3, 0xBF3504F3], np.uint32)
ints = rng.integers(-64, 64, size=(1 << 14, 3)).astype(np.float32)
vin = np.concatenate([np.array(np.meshgrid(sp, sp, sp)).reshape(3, -1).T,
                      rng.normal(size=(1 << 16, 3)).astype(np.float32).view(np.uint32),
                      ints.view(np.uint32)]).astype(np.uint32)
specs = 0
for path in sorted(glob.glob(f"{inc_dir}/*.glsl")):
    src = open(path).read()
    spec = re.search(r"// Regenerate: unitpack gen (\S+) --lang glsl", src).group(1)
    m = re.search(r"^(uint|uvec2|uvec3) (unitpack_\w+_encode)\(vec3 \w+\)", src, re.M)
    if not m:
        continue
    ty, fn = m.groups()
    words = {"uint": 1, "uvec2": 2, "uvec3": 3}[ty]
    r = subprocess.run([exe, "encode", spec, "--format", "binary"], input=vin.tobytes(), capture_output=True)
    if r.returncode:
        sys.exit(f"{spec}: the model failed: {r.stderr.decode()}")
    want = np.frombuffer(r.stdout, np.uint8).reshape(len(vin), -1)
    nbytes = want.shape[1]
    padded = np.zeros((len(vin), 4 * words), np.uint8)
    padded[:, :nbytes] = want
    stores = " ".join(f"o[n*{words}u+{j}u] = c{'' if words == 1 else '.' + 'xyz'[j]};" for j in range(words))
    body = f"{ty} c = {fn}(uintBitsToFloat(uvec3(i[n*3u], i[n*3u+1u], i[n*3u+2u]))); {stores}"
    for precise in (False, True):
        got = dispatch(src, precise, body, 3, words, vin).view(np.uint8).reshape(len(vin), -1).copy()
        got[:, nbytes:] = 0
        bad = np.nonzero((got != padded).any(1))[0]
        if len(bad):
            report(f"{spec} encode, precise={precise}", vin, got.view(np.uint32), padded.view(np.uint32))
    specs += 1
print(f"{specs} packed encoders on {len(vin)} vectors each; {differing} items differ in all")
sys.exit(1 if differing else 0)
