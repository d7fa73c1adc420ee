//! crytek_bfn24 (Crytek's Best Fit Normals through its fitting table): the table holds
//! the documented scales (recomputed here in f64), the encoder reads the texel nearest
//! sampling at Crytek's coordinate selects and stores the direction scaled by its
//! length as the documented bytes (checked against f64 arithmetic written here), invalid
//! input gives +Z at scale 1, and on lavapipe the emitted functions around a real
//! texture fetch reproduce the CPU encoder bit for bit.

use unitpack::Lang;
use unitpack::api::Batch;
use unitpack::codecs::table::crytek_bfn::{SIZE, fitting_table, fitting_texel};
use unitpack::generator::Generator;
use unitpack::model::V3;
use unitpack::support::sampling::random_unit_vectors;
use unitpack::verify::gpu::Gpu;

const SPEC: &str = "crytek_bfn24";

/// The scale the module documents for texel `(i, j)`, written out here: the first odd
/// `k` in 3 … 255 with the least `max|q - p|/(k/255)` over the three components of the
/// texel's direction (largest component 1) times `k/255`, `q` its unorm8 round trip.
fn documented_scale(i: usize, j: usize) -> u8 {
    let n = SIZE as f64;
    let a = (i as f64 + 0.5) / n;
    let b = a * (j as f64 + 0.5) / n;
    let c = (1.0 - a * a - b * b).max(0.0).sqrt();
    let top = a.max(c);
    let mut best = (f64::MAX, 0);
    for k in (3..=255u32).step_by(2) {
        let t = f64::from(k) / 255.0;
        let mut worst = 0f64;
        for x in [a / top, b / top, c / top] {
            let p = x * t;
            let byte = ((p + 1.0) * 127.5 + 0.5).floor();
            worst = worst.max((byte * 2.0 / 255.0 - 1.0 - p).abs());
        }
        if worst / t < best.0 {
            best = (worst / t, k);
        }
    }
    best.1 as u8
}

#[test]
fn table_holds_the_documented_scales() {
    let table = fitting_table();
    assert_eq!(table.len(), SIZE * SIZE);
    for j in 0..SIZE {
        for i in 0..SIZE {
            let byte = table[j * SIZE + i];
            assert!(byte % 2 == 1 && byte >= 3, "texel ({i}, {j}): {byte}");
            assert_eq!(byte, documented_scale(i, j), "texel ({i}, {j})");
        }
    }
    // Near an axis every length rounds the minor components to the bytes next to ½, so
    // the longest one has the least relative error.
    assert_eq!(table[0], 255);
    // The scales vary: the table is not a constant.
    let distinct: std::collections::BTreeSet<u8> = table.iter().copied().collect();
    assert!(distinct.len() > 60, "{} distinct scales", distinct.len());
}

/// Whether `x` lies within `eps` of an integer (a texel boundary of `floor`), where the
/// f64 reference cannot speak for the encoder's fixed point.
fn near_integer(x: f64, eps: f64) -> bool {
    (x - x.round()).abs() < eps
}

/// Whether `x` lies within `eps` of a tie (a code boundary of `round`).
fn near_tie(x: f64, eps: f64) -> bool {
    near_integer(x + 0.5, eps)
}

/// Over 200,000 vectors: the texel is `(floor(512·mid), floor(512·minor/mid))` of the
/// unit input's sorted magnitudes, clamped to 511, and each byte is
/// `round(127.5 + (n/major)·k/2)` (ties up) with `k` the table's byte there, computed in
/// f64. Vectors are set aside (under 2 %) where the encoder's fixed point may decide
/// otherwise: within `1e-3` texels of a boundary of `i` (the encoder divides by a length
/// known to `2^-22`, relative), `1e-4` of one of `j` (a product's rounding, `2^-24`
/// relative, decides a near tie), or `5e-4` codes of a rounding
/// boundary (its ratios sit on a `2^-20` grid, times `k/2`).
#[test]
fn encoder_reads_the_sampled_texel_and_stores_the_scaled_direction() {
    let batch = Batch::new(SPEC).unwrap();
    let vs = random_unit_vectors(0xbf24, 200_000, false);
    let mut codes = vec![0u32; vs.len()];
    batch.encode(&vs, &mut codes);
    let table = fitting_table();
    let mut set_aside = 0;
    for (v, &code) in vs.iter().zip(&codes) {
        let n = v.map(f64::from);
        let len = n.iter().map(|x| x * x).sum::<f64>().sqrt();
        let mut m = n.map(|x| x.abs() / len);
        m.sort_by(f64::total_cmp);
        let (minor, mid, major) = (m[0], m[1], m[2]);
        let (ti, tj) = (mid * 512.0, minor / mid * 512.0);
        if near_integer(ti, 1e-3) || near_integer(tj, 1e-4) {
            set_aside += 1;
            continue;
        }
        let texel = [ti.floor().min(511.0) as u32, tj.floor().min(511.0) as u32];
        let t = fitting_texel::<f32>(V3::from_array(*v));
        assert_eq!([t.x, t.y], texel, "{v:?}");
        let k = f64::from(table[texel[1] as usize * SIZE + texel[0] as usize]);
        let bytes = n.map(|x| 127.5 + x / len / major * k / 2.0);
        if bytes.iter().any(|&b| near_tie(b, 5e-4)) {
            set_aside += 1;
            continue;
        }
        let want = bytes
            .iter()
            .enumerate()
            .map(|(c, b)| ((b + 0.5).floor() as u32) << (8 * c))
            .sum::<u32>();
        assert_eq!(code, want, "{v:?}: {code:#08x} vs {want:#08x}");
    }
    assert!(set_aside < 4000, "{set_aside} vectors set aside");
}

#[test]
fn invalid_input_encodes_plus_z_at_scale_one() {
    let batch = Batch::new(SPEC).unwrap();
    let bad = [
        [0.0, 0.0, 0.0],
        [f32::NAN, 0.0, 1.0],
        [f32::INFINITY, 1.0, 0.0],
        [0.0, f32::NEG_INFINITY, 0.0],
    ];
    let mut codes = vec![0u32; bad.len()];
    batch.encode(&bad, &mut codes);
    assert_eq!(codes, vec![0x00ff_8080; bad.len()]);
}

/// The fitting table uploaded as an RGBA8 texture on lavapipe (its byte in R), read by
/// the emitted functions with `textureLoad` and through a nearest sampler at the texel's
/// centre: for 65,536 seeded vectors plus the edge cases, the shader's texel, fetch
/// (`c·(1/255)`) and code equal the CPU encoder's bit for bit.
#[test]
fn texture_round_trip_on_lavapipe() {
    let gpu = Gpu::shared().expect("a Vulkan adapter (install mesa-vulkan-drivers)");
    let mut vs = unitpack::verify::inputs::edge_vectors();
    vs.extend(random_unit_vectors(0xbf25, 1 << 16, false));
    let input: Vec<u32> = vs.iter().flat_map(|v| v.map(f32::to_bits)).collect();
    let include = Generator::new()
        .spec(SPEC)
        .lang(Lang::Wgsl)
        .error_stats(false)
        .render(Lang::Wgsl)
        .unwrap();
    let kernel = format!(
        r#"{include}
@group(0) @binding(0) var table: texture_2d<f32>;
@group(0) @binding(1) var nearest: sampler;
@group(0) @binding(2) var<storage, read_write> output_words: array<u32>;
@group(0) @binding(3) var<storage, read> inp: array<u32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {{
    let i = gid.x;
    if (i >= arrayLength(&output_words) / 6u) {{
        return;
    }}
    let v = bitcast<vec3<f32>>(vec3<u32>(inp[3u * i], inp[3u * i + 1u], inp[3u * i + 2u]));
    let t = unitpack_{SPEC}_fitting_texel(v);
    let loaded = textureLoad(table, t, 0).r;
    let sampled = textureSampleLevel(table, nearest, (vec2<f32>(t) + 0.5) / 512.0, 0.0).r;
    let o = array<u32, 6>(t.x, t.y, bitcast<u32>(loaded), bitcast<u32>(sampled),
        unitpack_{SPEC}_encode(v, loaded), unitpack_{SPEC}_encode(v, sampled));
    for (var k = 0u; k < 6u; k++) {{
        output_words[6u * i + k] = o[k];
    }}
}}
"#
    );
    let texels: Vec<u32> = fitting_table()
        .iter()
        .map(|&b| u32::from(b) | 0xff00_0000)
        .collect();
    let batch = Batch::new(SPEC).unwrap();
    let mut codes = vec![0u32; vs.len()];
    batch.encode(&vs, &mut codes);
    let out = gpu
        .run_texture(&kernel, &texels, SIZE as u32, &input, vs.len(), 6)
        .unwrap_or_else(|e| panic!("{e:#}"));
    for (k, (o, v)) in out.chunks_exact(6).zip(&vs).enumerate() {
        let t = fitting_texel::<f32>(V3::from_array(*v));
        assert_eq!([o[0], o[1]], [t.x, t.y], "vector {k} {v:?}: texel");
        let byte = fitting_table()[(o[1] as usize) * SIZE + o[0] as usize];
        let fetch = (f32::from(byte) * (1.0f32 / 255.0)).to_bits();
        assert_eq!([o[2], o[3]], [fetch; 2], "vector {k} {v:?}: fetch");
        assert_eq!(
            [o[4], o[5]],
            [codes[k]; 2],
            "vector {k} {v:?}: shader code vs CPU {:#08x}",
            codes[k]
        );
    }
}
