//! Normal-map texel layouts (`layout=` on the two-parameter hemisphere codecs): each
//! channel holds what the layout says, the parameter bytes are the nearest unorm8 codes
//! of `p·½ + ½` for the codec's exact parameters (computed here in f64), the decoders
//! read only their channels and agree with an f64 decode, xra's two encoders decode alike,
//! and a texel written by the CPU encoder, uploaded as an RGBA8 texture on lavapipe,
//! fetched and sampled, decodes in the shader to the bits the model computes.

use unitpack::Lang;
use unitpack::api::Batch;
use unitpack::codecs::Spec;
use unitpack::codecs::functions::function::Function;
use unitpack::generator::Generator;
use unitpack::support::sampling::random_unit_vectors;
use unitpack::verify::gpu::Gpu;

const FAMILIES: [&str; 5] = [
    "xy",
    "xy_stereo",
    "hemioct",
    "paraboloid",
    "paraboloid_square",
];
const LAYOUTS: [&str; 5] = ["rg", "dxt5nm", "rxgb", "latc", "xra"];

fn spec(family: &str, precise: bool, layout: &str) -> String {
    format!(
        "{family}16{}:layout={layout}",
        if precise { "p" } else { "" }
    )
}

fn encode(spec: &str, vs: &[[f32; 3]]) -> Vec<u32> {
    let b = Batch::new(spec).unwrap();
    let mut out = vec![0u32; vs.len()];
    b.encode(vs, &mut out);
    out
}

fn decode(spec: &str, codes: &[u32]) -> Vec<[f32; 3]> {
    let b = Batch::new(spec).unwrap();
    let mut out = vec![[0f32; 3]; codes.len()];
    b.decode(codes, &mut out);
    out
}

fn function(spec: &str, name: &str) -> Function {
    let s: Spec = spec.parse().unwrap();
    s.emitted()
        .functions
        .iter()
        .find(|f| f.name == name)
        .cloned()
        .unwrap_or_else(|| panic!("{spec} has no {name}"))
}

fn bytes(t: u32) -> [u32; 4] {
    [t & 255, t >> 8 & 255, t >> 16 & 255, t >> 24]
}

/// Unit vectors over the whole sphere (below-horizon input projects onto the horizon)
/// plus the edge cases.
fn vectors() -> Vec<[f32; 3]> {
    let mut vs = random_unit_vectors(0x7e1, 40_000, false);
    vs.extend([
        [0.6, 0.0, 0.8],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.6, -0.8, 0.0],
    ]);
    vs
}

/// The input projected onto the +Z hemisphere, normalized, in f64; -Z (which projects
/// to zero) is +Z, as every codec's edge policy says.
fn upper(v: [f32; 3]) -> [f64; 3] {
    let h = [f64::from(v[0]), f64::from(v[1]), f64::from(v[2]).max(0.0)];
    let l = (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt();
    if l == 0.0 {
        [0.0, 0.0, 1.0]
    } else {
        h.map(|x| x / l)
    }
}

/// Each family's parameters in `[-1, 1]` for a unit hemisphere direction, in f64.
fn params(family: &str, h: [f64; 3]) -> [f64; 2] {
    let [x, y, z] = h;
    match family {
        "xy" => [x, y],
        "xy_stereo" => [x / (1.0 + z), y / (1.0 + z)],
        "paraboloid" => {
            let a = z / 2.0 + (x * x + y * y + z * z / 4.0).sqrt();
            [x / a, y / a]
        }
        "hemioct" => {
            let l1 = x.abs() + y.abs() + z;
            [(x + y) / l1, (x - y) / l1]
        }
        "paraboloid_square" => {
            // The ray t·h meets z = (1 - X²)(1 - Y²) where g(t) changes sign.
            let g = |t: f64| (1.0 - (t * x).powi(2)) * (1.0 - (t * y).powi(2)) - t * z;
            let (mut lo, mut hi) = (0.0, 1.0 / x.abs().max(y.abs()).max(1e-300));
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if g(mid) >= 0.0 { lo = mid } else { hi = mid }
            }
            [(lo * x).clamp(-1.0, 1.0), (lo * y).clamp(-1.0, 1.0)]
        }
        _ => unreachable!(),
    }
}

/// Each family's decode of parameters `p`, in f64.
fn direction(family: &str, p: [f64; 2]) -> [f64; 3] {
    let q = p[0] * p[0] + p[1] * p[1];
    let unit = |v: [f64; 3]| {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        v.map(|x| x / l)
    };
    match family {
        "xy" => [p[0], p[1], (1.0 - q.min(1.0)).sqrt()],
        "xy_stereo" => [
            2.0 * p[0] / (1.0 + q),
            2.0 * p[1] / (1.0 + q),
            (1.0 - q) / (1.0 + q),
        ],
        "paraboloid" => unit([p[0], p[1], 1.0 - q.min(1.0)]),
        "hemioct" => {
            let t = [(p[0] + p[1]) / 2.0, (p[0] - p[1]) / 2.0];
            unit([t[0], t[1], 1.0 - t[0].abs() - t[1].abs()])
        }
        "paraboloid_square" => unit([p[0], p[1], (1.0 - p[0] * p[0]) * (1.0 - p[1] * p[1])]),
        _ => unreachable!(),
    }
}

/// The unorm8 code of `p·½ + ½` rounded to nearest (ties up), and whether `p` lies so
/// near a rounding boundary that the codec's exact, fixed-point decision may take either
/// side.
fn unorm8(p: f64) -> (u32, bool) {
    let s = 127.5 * p + 127.5;
    // p = 0 (an input on the horizon gives rxgb's blue that) is exactly a tie: up.
    let near = ((s - s.floor()) - 0.5).abs() < 2e-4 && p != 0.0;
    ((s + 0.5).floor().clamp(0.0, 255.0) as u32, near)
}

#[test]
fn dxt5nm_stores_x_in_alpha_and_y_in_green() {
    let t = encode("xy16:layout=dxt5nm", &[[0.6, 0.0, 0.8]])[0];
    let [r, g, b, a] = bytes(t);
    assert_eq!(a, 0xcc, "{t:#010x}: 0.6·½ + ½ = 0.8 is 204/255");
    assert_eq!(g, 0x80, "{t:#010x}: y = 0 is 127.5/255, ties up");
    assert_eq!((r, b), (0xff, 0), "{t:#010x}: R = 1, B = 0");
    // And back, through the float form the shader gets from the texture unit.
    let n = decode("xy16:layout=dxt5nm", &[t])[0];
    assert!(
        (n[0] - 0.6).abs() < 4e-3 && n[1].abs() < 4e-3 && (n[2] - 0.8).abs() < 4e-3,
        "{n:?}"
    );
}

/// +Z has no code (`p = 0` is 127.5/255): it, and every input without a direction on the
/// hemisphere, is stored as x = y = 128 (ties up), by the fast and the precise encoders
/// alike (the other layouts hold the same bytes: `channels_hold_what_the_layout_says`).
#[test]
fn plus_z_and_invalid_input_store_128() {
    let inputs = [
        [0.0, 0.0, 1.0],
        [0.0, 0.0, 7.5e-30],
        [0.0, 0.0, -1.0],
        [0.0, 0.0, 0.0],
        [f32::NAN, 0.0, 1.0],
        [f32::INFINITY, 1.0, 0.0],
        [1e-45, -1e-45, 0.0],
    ];
    for family in FAMILIES {
        for precise in [false, true] {
            let s = spec(family, precise, "rg");
            for (v, t) in inputs.iter().zip(encode(&s, &inputs)) {
                assert_eq!(t, 0xff00_8080, "{s} {v:?}: {t:#010x}");
            }
        }
    }
}

/// Every layout holds the same two parameter bytes (the fast and the precise encoder each
/// decide them once, whatever the layout) where its table says, and its constant channels.
#[test]
fn channels_hold_what_the_layout_says() {
    let vs = vectors();
    for family in FAMILIES {
        for precise in [false, true] {
            let rg = encode(&spec(family, precise, "rg"), &vs);
            let layouts: Vec<Vec<u32>> = LAYOUTS
                .iter()
                .map(|l| encode(&spec(family, precise, l), &vs))
                .collect();
            let dxt1 = function(&spec(family, precise, "xra"), "encode_dxt1");
            let mut z_checked = 0;
            for (i, v) in vs.iter().enumerate() {
                let [x, y, b, a] = bytes(rg[i]);
                assert_eq!((b, a), (0, 255), "{family} rg {v:?}: {:#010x}", rg[i]);
                let t = |k: usize| bytes(layouts[k][i]);
                let s = |k: usize| spec(family, precise, LAYOUTS[k]);
                assert_eq!(t(1), [255, y, 0, x], "{} {v:?}", s(1));
                assert_eq!(t(3), [y, y, y, x], "{} {v:?}", s(3));
                assert_eq!(t(4), [255, y, 0, x], "{} {v:?}", s(4));
                let [r, g, z, a] = t(2);
                assert_eq!([r, g, a], [255, y, x], "{} {v:?}", s(2));
                let (want, near) = unorm8(upper(*v)[2]);
                if !near {
                    assert_eq!(z, want, "{}: blue of {v:?} is the input's z", s(2));
                    z_checked += 1;
                }
                let mut d = [0u32];
                (dxt1.eval)(&v.map(f32::to_bits), &mut d);
                assert_eq!(bytes(d[0]), [x, y, 0, 255], "{} encode_dxt1 {v:?}", s(4));
            }
            assert!(
                z_checked > vs.len() * 9 / 10,
                "{family}: {z_checked} blues checked"
            );
        }
    }
}

/// The fast encoders' parameter bytes are the nearest unorm8 codes of the exact
/// parameters: an independent f64 evaluation of each projection.
#[test]
fn fast_bytes_are_the_nearest_codes_of_the_parameters() {
    let vs = vectors();
    for family in FAMILIES {
        let rg = encode(&spec(family, false, "rg"), &vs);
        let mut checked = 0;
        for (v, t) in vs.iter().zip(&rg) {
            let p = params(family, upper(*v));
            let ((x, nx), (y, ny)) = (unorm8(p[0]), unorm8(p[1]));
            if nx || ny {
                continue;
            }
            let got = bytes(*t);
            assert_eq!(
                [got[0], got[1]],
                [x, y],
                "{family}16_rg {v:?}: parameters {p:?}, texel {t:#010x}"
            );
            checked += 1;
        }
        assert!(checked > vs.len() * 9 / 10, "{family}: {checked} checked");
    }
}

/// Each decoder reads only its layout's channels, and turns them into what the codec's
/// f64 decode gives for `p = (2c - 255)/255`; the precise encoders' texels decode no
/// farther from the input than the fast ones', and nearer on average.
#[test]
fn decoders_read_their_channels_and_precise_is_nearer() {
    let vs = vectors();
    for family in FAMILIES {
        for layout in LAYOUTS {
            let fast = spec(family, false, layout);
            let codes = encode(&fast, &vs);
            let decoded = decode(&fast, &codes);
            let precise = encode(&spec(family, true, layout), &vs);
            let decoded_p = decode(&fast, &precise);
            // Every channel the decoder does not read overwritten: the same bits.
            let unread: u32 = match layout {
                "rg" => 0xffff_0000,
                "xra" => 0x00ff_0000,
                _ => 0x00ff_00ff,
            };
            let others: Vec<u32> = codes
                .iter()
                .enumerate()
                .map(|(i, c)| c ^ (unread & 0x5a3c_96e1u32.rotate_left(i as u32)))
                .collect();
            let back = decode(&fast, &others);
            let (mut sum, mut sum_p) = (0.0, 0.0);
            for (i, v) in vs.iter().enumerate() {
                let c = bytes(codes[i]);
                let (x, y) = match layout {
                    "rg" => (c[0], c[1]),
                    "xra" => (c[0] * c[3] / 255, c[1]),
                    _ => (c[3], c[1]),
                };
                let p = [x, y].map(|c| (2.0 * f64::from(c) - 255.0) / 255.0);
                let want = direction(family, p);
                // f32 rounding, amplified where xy's z = sqrt(1 - d) is near 0; a byte
                // read from the wrong channel moves p by at least 2/255.
                for k in 0..3 {
                    let d = (f64::from(decoded[i][k]) - want[k]).abs();
                    assert!(
                        d < 2e-5,
                        "{fast} {codes:#010x?}: {:?} vs {want:?}",
                        decoded[i],
                        codes = codes[i]
                    );
                }
                assert_eq!(
                    back[i].map(f32::to_bits),
                    decoded[i].map(f32::to_bits),
                    "{fast} {:#010x} vs {:#010x}",
                    others[i],
                    codes[i]
                );
                let h = upper(*v).map(|x| x as f32);
                let (e, e_p) = (angle(decoded[i], h), angle(decoded_p[i], h));
                assert!(
                    e_p <= e + 1e-5,
                    "{family}16p {layout} {v:?}: {e_p} vs fast {e}"
                );
                sum += e;
                sum_p += e_p;
            }
            assert!(
                sum_p < sum,
                "{family} {layout}: precise mean {sum_p} vs fast {sum}"
            );
        }
    }
}

fn angle(a: [f32; 3], b: [f32; 3]) -> f64 {
    unitpack::measure::quality::angle_deg(a, b).to_radians()
}

/// xra's one decoder serves both of its encoders: the DXT1 texel (x in R, A = 1) and
/// the DXT5 texel (x in A, R = 1) of every input decode to the same bits.
#[test]
fn xra_decodes_dxt1_and_dxt5_texels_alike() {
    let vs = vectors();
    for family in FAMILIES {
        for precise in [false, true] {
            let s = spec(family, precise, "xra");
            let dxt1 = function(&s, "encode_dxt1");
            let dxt5 = encode(&s, &vs);
            let input: Vec<u32> = vs.iter().flatten().map(|x| x.to_bits()).collect();
            let mut dxt1_codes = vec![0u32; vs.len()];
            dxt1.eval_many(&input, &mut dxt1_codes);
            let (a, b) = (decode(&s, &dxt1_codes), decode(&s, &dxt5));
            for (i, v) in vs.iter().enumerate() {
                let (t1, t5) = (dxt1_codes[i], dxt5[i]);
                // The two texels differ unless x = 255 (then R = A = 255 in both).
                assert!(t1 != t5 || t5 >> 24 == 255, "{s} {v:?}");
                assert_eq!(
                    a[i].map(f32::to_bits),
                    b[i].map(f32::to_bits),
                    "{s} {v:?}: {t1:#010x} {t5:#010x}"
                );
            }
        }
    }
}

/// The WGSL kernel around a spec's include: fetch texel `i` of the texture with
/// `textureLoad` and with `textureSampleLevel` (nearest, at the texel's centre), decode
/// both, and write the two fetches' and the two decodes' bits (14 words).
fn kernel(spec: &str, width: u32, height: u32) -> String {
    let include = Generator::new()
        .spec(spec)
        .lang(Lang::Wgsl)
        .error_stats(false)
        .render(Lang::Wgsl)
        .unwrap();
    let id = spec.parse::<Spec>().unwrap().id();
    format!(
        r#"{include}
@group(0) @binding(0) var texels: texture_2d<f32>;
@group(0) @binding(1) var nearest: sampler;
@group(0) @binding(2) var<storage, read_write> output_words: array<u32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {{
    let i = id.x;
    if (i >= arrayLength(&output_words) / 14u) {{
        return;
    }}
    let xy = vec2<u32>(i % {width}u, i / {width}u);
    let loaded = textureLoad(texels, xy, 0);
    let uv = (vec2<f32>(xy) + vec2<f32>(0.5, 0.5)) / vec2<f32>({width}.0, {height}.0);
    let sampled = textureSampleLevel(texels, nearest, uv, 0.0);
    let a = unitpack_{id}_decode_float(loaded);
    let b = unitpack_{id}_decode_float(sampled);
    let words = array<u32, 14>(
        bitcast<u32>(loaded.x), bitcast<u32>(loaded.y), bitcast<u32>(loaded.z), bitcast<u32>(loaded.w),
        bitcast<u32>(sampled.x), bitcast<u32>(sampled.y), bitcast<u32>(sampled.z), bitcast<u32>(sampled.w),
        bitcast<u32>(a.x), bitcast<u32>(a.y), bitcast<u32>(a.z),
        bitcast<u32>(b.x), bitcast<u32>(b.y), bitcast<u32>(b.z));
    for (var k = 0u; k < 14u; k++) {{
        output_words[i * 14u + k] = words[k];
    }}
}}
"#
    )
}

/// A texel written by the CPU encoder, uploaded as an RGBA8 texture on lavapipe, loaded
/// and sampled (nearest) in a compute shader and decoded there by the emitted
/// `decode_float`, for every layout of every codec: the encoder's texels for 65,536
/// seeded vectors, and every pair of parameter bytes in the layout's channels. lavapipe's
/// texture unit returns `c·(1/255)` for every channel (the packed decoder's own
/// conversion, within one ULP of `c/255`), so the shader's decode of the fetch is bit for
/// bit the packed decode of the texel. Where a driver returns `c/255` correctly rounded
/// instead (the APIs allow either), the model's decode of that differs from the packed
/// decode by at most [`CORRECTLY_ROUNDED_FETCH`] per component.
#[test]
fn texture_round_trip_on_lavapipe() {
    let gpu = Gpu::shared().expect("a Vulkan adapter (install mesa-vulkan-drivers)");
    let (width, height) = (256u32, 512u32);
    let mut worst = 0f64;
    for family in FAMILIES {
        for layout in LAYOUTS {
            let s = spec(family, false, layout);
            let vs = random_unit_vectors(0x7e2, 1 << 16, true);
            let written = encode(&s, &vs);
            // Every pair of parameter bytes, the other channels as the encoder writes
            // them (xra: DXT5 and DXT1 texels alternately).
            let swept = written.iter().enumerate().map(|(k, t)| {
                let (x, y) = ((k & 255) as u32, (k >> 8) as u32);
                let [r, _, b, a] = bytes(*t);
                let [r, g, b, a] = match layout {
                    "rg" => [x, y, b, a],
                    "xra" if k % 2 == 1 => [x, y, b, 255],
                    "latc" => [y, y, y, x],
                    _ => [r, y, b, x],
                };
                r | g << 8 | b << 16 | a << 24
            });
            let texels: Vec<u32> = written.iter().copied().chain(swept).collect();
            let out = gpu
                .run_texture(
                    &kernel(&s, width, height),
                    &texels,
                    width,
                    &[],
                    texels.len(),
                    14,
                )
                .unwrap_or_else(|e| panic!("{s}: {e:#}"));
            let decode_float = function(&s, "decode_float");
            let packed = decode(&s, &texels);
            for (k, (t, o)) in texels.iter().zip(out.chunks_exact(14)).enumerate() {
                let codes = bytes(*t);
                let at = format!("{s} texel {k} {t:#010x}");
                assert_eq!(&o[0..4], &o[4..8], "{at}: load vs sample");
                let own: Vec<u32> = codes
                    .iter()
                    .map(|&c| (c as f32 * (1.0f32 / 255.0)).to_bits())
                    .collect();
                assert_eq!(&o[0..4], &own[..], "{at}: lavapipe fetches c·(1/255)");
                let mut model = [0u32; 3];
                (decode_float.eval)(&o[0..4], &mut model);
                assert_eq!(&o[8..11], &model, "{at}: decode_float of the load");
                assert_eq!(&o[11..14], &model, "{at}: decode_float of the sample");
                assert_eq!(model, packed[k].map(f32::to_bits), "{at}: packed decode");
                let rounded: Vec<u32> = codes
                    .iter()
                    .map(|&c| (c as f32 / 255.0).to_bits())
                    .collect();
                let mut other = [0u32; 3];
                (decode_float.eval)(&rounded, &mut other);
                for (a, b) in other.iter().zip(packed[k]) {
                    worst = worst.max((f64::from(f32::from_bits(*a)) - f64::from(b)).abs());
                }
            }
        }
    }
    assert!(
        worst <= CORRECTLY_ROUNDED_FETCH,
        "a correctly rounded fetch decodes {worst:e} from the packed decode"
    );
}

/// The largest difference per component between the decode of a correctly rounded fetch
/// (`c/255`) and the packed decode (`c·(1/255)`), over the texels of
/// [`texture_round_trip_on_lavapipe`]: the sample maximum is 8.2e-6, at xy's texels near
/// the horizon, where `z = sqrt(1 - d)` magnifies the last bit of `d`.
const CORRECTLY_ROUNDED_FETCH: f64 = 1e-5;
