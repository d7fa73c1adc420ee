//! gltf-transform's quantization of normals and tangents (`@gltf-transform/functions`
//! 4.5.1, `packages/functions/src/quantize.ts`: `quantizeAttribute`, with
//! `getQuantizationSettings` choosing `Int8Array` up to 8 bits and `Int16Array` above):
//! a port of its arithmetic, and the package itself run by Node.js.

/// `quantizeAttribute`'s integer for one component at `bits` (8 or 16, so that its bit
/// spreading `q << lo | q >> hi` is the identity): `clamp(x, [-1, 1])`,
/// `Math.round(|x|·(2^(bits-1) - 1))` in f64 (the product is exact, halves go up), times
/// `Math.sign(x)`, stored by a typed array (NaN as 0).
pub fn quantized(x: f32, bits: u32) -> i32 {
    let scale = f64::from((1u32 << (bits - 1)) - 1);
    let x = f64::from(x);
    // Math.min(Math.max(x, -1), 1): NaN stays NaN.
    let clamped = if x.is_nan() { x } else { x.clamp(-1.0, 1.0) };
    // Math.round of a non-negative value: floor(v + 0.5), exact here since v·2 has at
    // most 40 significant bits.
    let q = (clamped.abs() * scale + 0.5).floor();
    let signed = q * if x.is_nan() { f64::NAN } else { x.signum() };
    // A typed array stores NaN as 0 and -0 as 0.
    if signed.is_nan() { 0 } else { signed as i32 }
}

/// `quantize({ pattern: /^SEMANTIC$/, quantizeNormal: bits })` on one primitive whose
/// `semantic` accessor holds `values` (3 or 4 floats per element): the quantized
/// accessor's integers, through `tools/gltf-js/quantize.mjs`.
pub fn run(bits: u32, semantic: &str, values: &[f32]) -> Vec<i32> {
    use std::io::Write;
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/gltf-js");
    assert!(
        dir.join("node_modules/@gltf-transform/functions/package.json")
            .exists(),
        "gltf-transform is not installed: run `npm ci --prefix tools/gltf-js` \
         (Node.js and npm: the Debian packages `nodejs` and `npm`)"
    );
    let mut child = std::process::Command::new("node")
        .arg(dir.join("quantize.mjs"))
        .arg(bits.to_string())
        .arg(semantic)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("running `node` (the Debian package `nodejs`): {e}"));
    let bytes: Vec<u8> = values.iter().flat_map(|x| x.to_le_bytes()).collect();
    let mut stdin = child.stdin.take().expect("piped");
    let writer = std::thread::spawn(move || stdin.write_all(&bytes));
    let out = child.wait_with_output().expect("node's output");
    writer
        .join()
        .expect("writer")
        .expect("writing node's input");
    assert!(
        out.status.success(),
        "quantize.mjs failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let width = if bits <= 8 { 1 } else { 2 };
    assert_eq!(
        out.stdout.len(),
        values.len() * width,
        "one integer per value"
    );
    out.stdout
        .chunks(width)
        .map(|b| match b {
            [x] => i32::from(*x as i8),
            [lo, hi] => i32::from(i16::from_le_bytes([*lo, *hi])),
            _ => unreachable!(),
        })
        .collect()
}
