//! latlongd{16,24,32} (Smith et al.'s rings with the table decoder): the ring table holds
//! the documented construction (recomputed here in f64), the decoder's ring guess leaves
//! every code's ring among the two entries it fetches (every code at 16 and 24 bits, every
//! ring's first and last code at 32), codes decode to their patch centres and the encoder
//! picks the patch holding the input (both against f64 written here), invalid input
//! gives code 0, and on lavapipe the emitted functions around the table reads reproduce
//! the CPU encoder and decoder bit for bit.

use std::f64::consts::PI;
use unitpack::Lang;
use unitpack::api::Batch;
use unitpack::codecs::angular::latlongd::{RINGS, Rings, decode_ring};
use unitpack::generator::Generator;
use unitpack::support::sampling::random_unit_vectors;
use unitpack::verify::gpu::Gpu;

/// `(bits, Nφ, ε in degrees)` as the module documents them.
const DOCUMENTED: [(u32, u32, f64); 3] = [
    (16, 227, 0.562432),
    (24, 3629, 0.035069),
    (32, 58075, 0.00219148),
];

/// The patches of ring `j` in the well-conditioned form the module documents, in f64
/// with std's functions (the geometric test below checks the form itself).
fn ring_count(nphi: u32, eps: f64, j: u32) -> f64 {
    if j == 0 || j == nphi - 1 {
        return 1.0;
    }
    let dphi = PI / f64::from(nphi - 1);
    let p = f64::from(j.min(nphi - 1 - j)) * dphi;
    let q = p + dphi / 2.0;
    let d = q - p;
    let s2 = ((eps - d) / 2.0).sin() * ((eps + d) / 2.0).sin() / (p.sin() * q.sin());
    PI / (2.0 * s2.sqrt().asin())
}

/// Each size's table: `Nφ` rings, `ε` as documented, at most `2^B` patches, poles of one
/// patch, rings symmetric about the equator, offsets the running sums, and each count
/// the ceiling of the construction's ratio (computed here; where the ratio lies within
/// `1e-9` of an integer, either neighbour is accepted).
#[test]
fn ring_tables_hold_the_documented_construction() {
    for (bits, nphi, eps_deg) in DOCUMENTED {
        let r = Rings::of(bits);
        assert_eq!(RINGS.iter().find(|x| x.0 == bits).unwrap().1, nphi);
        assert_eq!(r.entries.len(), nphi as usize, "{bits}");
        assert!(
            (r.epsilon.to_degrees() - eps_deg).abs() < 5e-7 * eps_deg.max(1.0),
            "{bits}: ε {}°",
            r.epsilon.to_degrees()
        );
        assert!(u64::from(r.total) <= 1u64 << bits, "{bits}: {}", r.total);
        let mut offset = 0u64;
        for (j, e) in r.entries.iter().enumerate() {
            assert_eq!(u64::from(e[0]), offset, "{bits} ring {j}");
            offset += u64::from(e[1]);
            let mirror = r.entries[nphi as usize - 1 - j][1];
            assert_eq!(e[1], mirror, "{bits} ring {j}: not symmetric");
            let want = ring_count(nphi, r.epsilon, j as u32);
            let ok = f64::from(e[1]) == want.ceil()
                || ((want - want.round()).abs() < 1e-9 && f64::from(e[1]) == want.round());
            assert!(ok, "{bits} ring {j}: {} patches vs {want}", e[1]);
        }
        assert_eq!(offset, u64::from(r.total));
        assert_eq!((r.entries[0][1], r.entries[nphi as usize - 1][1]), (1, 1));
    }
}

/// The counts checked geometrically, without the construction's trigonometric identity:
/// a patch's corner on the equator side of its band (polar angle `p + Δ/2`, azimuth
/// `π/count` from the centre) is within `ε` of the patch centre, and with one patch
/// fewer it would not be (angles from the vectors' cross and dot products). Every ring at
/// 16 and 24 bits, every 97th at 32.
#[test]
fn ring_counts_are_the_fewest_patches_within_epsilon() {
    let angle = |p: f64, q: f64, h: f64| {
        let a = [p.sin(), 0.0, p.cos()];
        let b = [q.sin() * h.cos(), q.sin() * h.sin(), q.cos()];
        let cross = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        let sin = cross.iter().map(|x| x * x).sum::<f64>().sqrt();
        let cos: f64 = a.iter().zip(&b).map(|(x, y)| x * y).sum();
        sin.atan2(cos)
    };
    for (bits, step) in [(16, 1), (24, 1), (32, 97)] {
        let r = Rings::of(bits);
        let nphi = r.entries.len() as u32;
        let dphi = PI / f64::from(nphi - 1);
        for j in (1..nphi - 1).step_by(step) {
            let count = f64::from(r.entries[j as usize][1]);
            let p = f64::from(j.min(nphi - 1 - j)) * dphi;
            let q = p + dphi / 2.0;
            let within = angle(p, q, PI / count);
            assert!(
                within <= r.epsilon * (1.0 + 1e-9),
                "{bits} ring {j}: {within}"
            );
            if count > 1.0 {
                let fewer = angle(p, q, PI / (count - 1.0));
                assert!(fewer > r.epsilon * (1.0 - 1e-9), "{bits} ring {j}: {fewer}");
            }
        }
    }
}

/// At 16 and 24 bits, a ring count one or two either side of the chosen one needs a
/// larger `ε` for the same codes (the chosen count is a local least).
#[test]
fn ring_counts_are_the_least_error_nearby() {
    for (bits, nphi, _) in &DOCUMENTED[..2] {
        let best = Rings::build(*bits, *nphi).epsilon;
        for other in [nphi - 2, nphi - 1, nphi + 1, nphi + 2] {
            let e = Rings::build(*bits, other).epsilon;
            assert!(e > best, "{bits}: {other} rings give {e} ≤ {best}");
        }
    }
}

/// The ring holding `code`, by binary search over the offsets.
fn ring_of(r: &Rings, code: u32) -> u32 {
    let code = code.min(r.total - 1);
    (r.entries.partition_point(|e| e[0] <= code) - 1) as u32
}

fn guess_holds(r: &Rings, code: u32) {
    let g = decode_ring::<f32>(r, code);
    let ring = ring_of(r, code);
    assert!(
        ring == g || ring == g + 1,
        "code {code:#x}: ring {ring}, guess {g}"
    );
}

/// The guess leaves the code's ring at `g` or `g + 1`: every code at 16 and 24 bits
/// (and the unused codes past the total, which decode as -Z), and at 32 bits the first
/// and last code of every ring, between which the guess moves monotonically up to the
/// trigonometry's error.
#[test]
fn decode_ring_leaves_the_ring_among_its_two_entries() {
    for bits in [16, 24] {
        let r = Rings::of(bits);
        for code in 0..(1u32 << bits) {
            guess_holds(r, code);
        }
    }
    let r = Rings::of(32);
    for e in &r.entries {
        guess_holds(r, e[0]);
        guess_holds(r, e[0] + e[1] - 1);
    }
    guess_holds(r, u32::MAX);
    // The real-valued guess, monotone in the code, is within 0.9 rings of the ring at
    // every ring's first and last code, so at every code between them: the model's
    // guess, within a few hundredths of a ring of it (the trigonometry's 2^-21 half
    // turns times Nφ), then floors to the ring or the one below.
    for bits in [16, 24, 32] {
        let r = Rings::of(bits);
        let last = (r.entries.len() - 1) as f64;
        let total = f64::from(r.total);
        let real = |c: u32| {
            let south = 2 * u64::from(c) >= u64::from(r.total);
            let cc = if south { r.total - 1 - c } else { c };
            let u = (f64::from(cc) + 0.5) / total;
            let g = (2.0 * (u * (1.0 - u)).sqrt()).atan2(1.0 - 2.0 * u) / PI * last;
            if south { last - g } else { g }
        };
        for (j, e) in r.entries.iter().enumerate() {
            for c in [e[0], e[0] + e[1] - 1] {
                let g = real(c);
                assert!(
                    (g - j as f64).abs() < 0.9,
                    "latlongd{bits} code {c}: G {g}, ring {j}"
                );
            }
        }
    }
}

/// The patch centre of `code` in f64: ring `j` at `θ = π·j/(Nφ - 1)`, patch `k` at
/// `φ = π·(2k/count - 1)`.
fn centre(r: &Rings, code: u32) -> [f64; 3] {
    let j = ring_of(r, code);
    let [offset, count] = r.entries[j as usize];
    let k = code.min(r.total - 1) - offset;
    let theta = PI * f64::from(j) / (r.entries.len() - 1) as f64;
    let phi = PI * (2.0 * f64::from(k) / f64::from(count) - 1.0);
    [
        phi.cos() * theta.sin(),
        phi.sin() * theta.sin(),
        theta.cos(),
    ]
}

/// Codes decode to their patch centres (within 1e-6 per component: the decoder's
/// trigonometry and its `2^-24` grid of the azimuth): every 16-bit code, and 2^16 codes
/// spread over the 24- and 32-bit ranges plus each ring's first and last.
#[test]
fn codes_decode_to_their_patch_centres() {
    for bits in [16u32, 24, 32] {
        let r = Rings::of(bits);
        let batch = Batch::new(&format!("latlongd{bits}")).unwrap();
        let span = (1u64 << bits) as f64;
        let mut codes: Vec<u32> = (0..1u32 << 16)
            .map(|i| (f64::from(i) / 65536.0 * span) as u32)
            .collect();
        for e in &r.entries {
            codes.extend([e[0], e[0] + e[1] - 1]);
        }
        let mut out = vec![[0f32; 3]; codes.len()];
        batch.decode(&codes, &mut out);
        for (&c, d) in codes.iter().zip(&out) {
            let want = centre(r, c);
            for (a, b) in d.iter().zip(want) {
                assert!(
                    (f64::from(*a) - b).abs() < 1e-6,
                    "latlongd{bits} code {c:#x}: {d:?} vs {want:?}"
                );
            }
        }
    }
}

/// Over 200,000 vectors per size, the code is the patch holding the input: ring
/// `round(θ/π·(Nφ - 1))`, patch `round((φ + π)/2π·count) mod count`, in f64; vectors
/// within four steps of the encoder's angle grid (`2^-23` half turns) of a rounding
/// boundary are set aside (about 10 % at 32 bits, where four steps are 3 % of a ring and
/// of a patch).
#[test]
fn encoder_picks_the_patch_holding_the_input() {
    let vs = random_unit_vectors(0x1a7d, 200_000, false);
    for bits in [16u32, 24, 32] {
        let r = Rings::of(bits);
        let batch = Batch::new(&format!("latlongd{bits}")).unwrap();
        let mut codes = vec![0u32; vs.len()];
        batch.encode(&vs, &mut codes);
        // The encoder's angles are on a grid of 2^-23 half turns: a rounding boundary
        // closer than a few of its steps may fall either way.
        let near_tie = |x: f64, steps: f64| ((x - x.floor()) - 0.5).abs() < 1e-5 + 4.0 * steps;
        let mut aside = 0;
        for (v, &code) in vs.iter().zip(&codes) {
            let [x, y, z] = v.map(f64::from);
            let theta = (x * x + y * y).sqrt().atan2(z);
            let rings = theta / PI * (r.entries.len() - 1) as f64;
            if near_tie(rings, (r.entries.len() - 1) as f64 * 2f64.powi(-23)) {
                aside += 1;
                continue;
            }
            let [offset, count] = r.entries[rings.round() as usize];
            let patch = (y.atan2(x) + PI) / (2.0 * PI) * f64::from(count);
            if near_tie(patch, f64::from(count) * 2f64.powi(-24)) {
                aside += 1;
                continue;
            }
            let k = (patch.round() as u32) % count;
            assert_eq!(code, offset + k, "latlongd{bits} {v:?}");
        }
        assert!(aside < 25_000, "latlongd{bits}: {aside} set aside");
    }
}

#[test]
fn invalid_input_encodes_code_zero() {
    for bits in [16, 24, 32] {
        let batch = Batch::new(&format!("latlongd{bits}")).unwrap();
        let bad = [
            [0.0, 0.0, 0.0],
            [f32::NAN, 0.0, 1.0],
            [0.0, f32::INFINITY, 0.0],
            [f32::NEG_INFINITY, 1.0, 1.0],
        ];
        let mut codes = vec![1u32; bad.len()];
        batch.encode(&bad, &mut codes);
        assert_eq!(codes, vec![0; bad.len()], "latlongd{bits}");
    }
}

/// The emitted functions on lavapipe with the ring table read from a storage buffer:
/// `encode_ring`, the entry, `encode` for 65,536 seeded vectors plus the edge cases, and
/// `decode_ring`, the two entries, `decode_params` and `decode_float` for 2^16 codes
/// spread over the range (every code at 16 bits) plus every ring's first and last, equal
/// the CPU encoder and decoder bit for bit.
#[test]
fn table_round_trip_on_lavapipe() {
    let gpu = Gpu::shared().expect("a Vulkan adapter (install mesa-vulkan-drivers)");
    let mut vs = unitpack::verify::inputs::edge_vectors();
    vs.extend(random_unit_vectors(0x1a7e, 1 << 16, false));
    for bits in [16u32, 24, 32] {
        let spec = format!("latlongd{bits}");
        let r = Rings::of(bits);
        let include = Generator::new()
            .spec(spec.as_str())
            .lang(Lang::Wgsl)
            .error_stats(false)
            .render(Lang::Wgsl)
            .unwrap();
        let table: Vec<u32> = r.entries.iter().flatten().copied().collect();
        let base = table.len();
        let kernel = |body: &str, per: usize| {
            format!(
                r#"{include}
@group(0) @binding(0) var unused: texture_2d<f32>;
@group(0) @binding(1) var nearest: sampler;
@group(0) @binding(2) var<storage, read_write> output_words: array<u32>;
@group(0) @binding(3) var<storage, read> inp: array<u32>;

fn ring_entry(j: u32) -> vec2<u32> {{
    return vec2<u32>(inp[2u * j], inp[2u * j + 1u]);
}}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {{
    let i = gid.x;
    if (i >= arrayLength(&output_words) / {per}u) {{
        return;
    }}
    let at = {base}u;
    // The texture and sampler run_texture binds, referenced so that the layout has them.
    if (i == 0xffffffffu) {{
        output_words[0] = bitcast<u32>(textureSampleLevel(unused, nearest, vec2<f32>(0.0), 0.0).r);
    }}
{body}
}}
"#
            )
        };
        let dummy = [0xff00_0000u32];

        let encode = kernel(
            &format!(
                "    let v = bitcast<vec3<f32>>(vec3<u32>(inp[at + 3u * i], inp[at + 3u * i + 1u], inp[at + 3u * i + 2u]));
    output_words[i] = unitpack_{spec}_encode(v, ring_entry(unitpack_{spec}_encode_ring(v)));"
            ),
            1,
        );
        let mut input = table.clone();
        input.extend(vs.iter().flat_map(|v| v.map(f32::to_bits)));
        let out = gpu
            .run_texture(&encode, &dummy, 1, &input, vs.len(), 1)
            .unwrap_or_else(|e| panic!("{spec}: {e:#}"));
        let batch = Batch::new(&spec).unwrap();
        let mut codes = vec![0u32; vs.len()];
        batch.encode(&vs, &mut codes);
        for (k, (o, c)) in out.iter().zip(&codes).enumerate() {
            assert_eq!(o, c, "{spec} vector {k} {:?}", vs[k]);
        }

        let decode = kernel(
            &format!(
                "    let c = inp[at + i];
    let g = unitpack_{spec}_decode_ring(c);
    let p = unitpack_{spec}_decode_params(c, g, ring_entry(g), ring_entry(g + 1u));
    let n = bitcast<vec3<u32>>(unitpack_{spec}_decode_float(p));
    output_words[3u * i] = n.x;
    output_words[3u * i + 1u] = n.y;
    output_words[3u * i + 2u] = n.z;"
            ),
            3,
        );
        let span = (1u64 << bits) as f64;
        let mut all: Vec<u32> = (0..1u32 << 16)
            .map(|i| (f64::from(i) / 65536.0 * span) as u32)
            .collect();
        for e in &r.entries {
            all.extend([e[0], e[0] + e[1] - 1]);
        }
        all.push(u32::MAX >> (32 - bits));
        let mut input = table.clone();
        input.extend(&all);
        let out = gpu
            .run_texture(&decode, &dummy, 1, &input, all.len(), 3)
            .unwrap_or_else(|e| panic!("{spec}: {e:#}"));
        let mut want = vec![[0f32; 3]; all.len()];
        batch.decode(&all, &mut want);
        for ((o, w), c) in out.chunks_exact(3).zip(&want).zip(&all) {
            assert_eq!(o, w.map(f32::to_bits), "{spec} code {c:#x}: {w:?}");
        }
    }
}
