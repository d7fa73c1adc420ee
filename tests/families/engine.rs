//! The engine formats against their engines: codes equal to the engines' encoders on
//! seeded and edge vectors (meshoptimizer itself, ports of Bevy's and Unity's code in
//! `oracles/`), decoders equal to the reference decoders on every code of up to 16 bits
//! and a seeded sample above, or within a stated bound where the model's fetch is a
//! product by the reciprocal and the engine's a quotient. What the model computes here,
//! every verify path computes bit for bit (tests/verify_gpu.rs).

use crate::oracles::{bevy, draco, meshopt, unity};
use unitpack::codecs::Spec;
use unitpack::codecs::functions::function::{Function, Role};

pub(crate) fn function(spec: &str, role: Role) -> Function {
    let spec: Spec = spec.parse().unwrap();
    spec.emitted()
        .functions
        .iter()
        .find(|f| f.role == role)
        .cloned()
        .unwrap()
}

pub(crate) fn run(f: &Function, input: &[u32]) -> Vec<u32> {
    let mut out = vec![0u32; f.out_words];
    (f.eval)(input, &mut out);
    out
}

/// Seeded unit vectors, non-unit and tiny ones, the fold and the axes with both zeros,
/// and the hostile inputs (zero, NaN, infinities).
pub(crate) fn inputs() -> Vec<[f32; 3]> {
    let mut v = unitpack::support::sampling::random_unit_vectors(43, 200_000, false);
    for k in [-20, -3, 5, 20] {
        let s = 2f32.powi(k);
        v.extend(
            unitpack::support::sampling::random_unit_vectors(k as u128 + 100, 2_000, false)
                .into_iter()
                .map(|d| d.map(|x| x * s * 1.37)),
        );
    }
    v.extend(unitpack::codecs::functions::inputs::edge_vectors());
    let parts = [
        0.0f32,
        -0.0,
        0.5,
        -0.5,
        1.0,
        -1.0,
        1e-30,
        f32::NAN,
        f32::INFINITY,
    ];
    for &x in &parts {
        for &y in &parts {
            for &z in &parts {
                v.push([x, y, z]);
            }
        }
    }
    v
}

fn bits(v: [f32; 3]) -> [u32; 3] {
    v.map(f32::to_bits)
}

#[test]
fn meshopt_encoders_write_meshoptimizers_words() {
    let vs = inputs();
    let data: Vec<[f32; 4]> = vs.iter().map(|v| [v[0], v[1], v[2], 0.0]).collect();
    for k in 4..=16 {
        for word in [8, 16] {
            if k > word {
                continue;
            }
            let enc = function(&format!("meshopt_oct{word}:bits={k}"), Role::Encode);
            let want: Vec<u64> = if word == 8 {
                ::meshopt::encode_filter_oct::<u8>(&data, k)
                    .iter()
                    .map(|w| u64::from(u32::from_le_bytes(*w)))
                    .collect()
            } else {
                ::meshopt::encode_filter_oct::<u16>(&data, k)
                    .iter()
                    .map(|w| w.iter().rev().fold(0u64, |a, &h| a << 16 | u64::from(h)))
                    .collect()
            };
            for (v, want) in vs.iter().zip(want) {
                let got = run(&enc, &bits(*v));
                let got = got.iter().rev().fold(0u64, |a, &w| a << 32 | u64::from(w));
                assert_eq!(
                    got, want,
                    "meshopt_oct{word} K={k}: {v:?} → {got:x} vs {want:x}"
                );
            }
        }
    }
}

/// Every code a K-bit encoder can write (x, y in [-M, M], the third word M, the fourth
/// 0) for K ≤ 8, in both word sizes (with 8-bit words every x and y, hostile ones
/// included), and a seeded quarter million for larger K: the
/// decoder's output, read back as words, is the reference pseudo-code's; its floats are
/// those words as the snorm fetch reads them (`c·fl(1/INTN_MAX)`). meshoptimizer's own
/// decoder (SIMD on this machine) is within one unit of the output word, as the extension
/// allows.
#[test]
fn meshopt_decoders_are_the_extensions_reference() {
    let mut rng = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        rng
    };
    for word in [8u32, 16] {
        let max = ((1u32 << (word - 1)) - 1) as f32;
        for k in 4..=word {
            let dec = function(&format!("meshopt_oct{word}:bits={k}"), Role::Decode);
            let m = (1i32 << (k - 1)) - 1;
            let codes: Vec<(i32, i32)> = if k <= 8 {
                // 8-bit words: every x and y a word holds, those beyond the third word
                // (which no encoder writes, and where the fix-up's sign once depended on
                // the sign of a zero quotient) included.
                let (lo, hi) = if word == 8 { (-128, 127) } else { (-m, m) };
                (lo..=hi)
                    .flat_map(|x| (lo..=hi).map(move |y| (x, y)))
                    .collect()
            } else {
                (0..250_000)
                    .map(|_| {
                        let r = next();
                        let span = (2 * m + 1) as u64;
                        ((r % span) as i32 - m, ((r >> 32) % span) as i32 - m)
                    })
                    .collect()
            };
            let mut words = Vec::with_capacity(codes.len());
            for &(x, y) in &codes {
                let field = |c: i32| (c as u32) & ((1u32 << word) - 1);
                let input = if word == 8 {
                    vec![field(x) | field(y) << 8 | field(m) << 16]
                } else {
                    vec![field(x) | field(y) << 16, field(m)]
                };
                let got = run(&dec, &input);
                let want = meshopt::decode([x, y, m], max);
                for i in 0..3 {
                    let fetched = (want[i] as f32 * (1.0 / max)).max(-1.0);
                    assert_eq!(
                        got[i],
                        fetched.to_bits(),
                        "meshopt_oct{word} K={k} ({x}, {y}): lane {i} {:?} vs word {}",
                        f32::from_bits(got[i]),
                        want[i]
                    );
                }
                // meshoptimizer is compared on the codes its encoder writes.
                if x.abs() <= m && y.abs() <= m {
                    words.push((want, x, y));
                }
            }
            // meshoptimizer's decoder on the same words.
            let ulp = if word == 8 {
                let mut data: Vec<[i8; 4]> = words
                    .iter()
                    .map(|&(_, x, y)| [x as i8, y as i8, m as i8, 0])
                    .collect();
                ::meshopt::decode_filter_oct(&mut data);
                diff(
                    &words,
                    data.iter().map(|d| [d[0].into(), d[1].into(), d[2].into()]),
                )
            } else {
                let mut data: Vec<[i16; 4]> = words
                    .iter()
                    .map(|&(_, x, y)| [x as i16, y as i16, m as i16, 0])
                    .collect();
                ::meshopt::decode_filter_oct(&mut data);
                diff(
                    &words,
                    data.iter().map(|d| [d[0].into(), d[1].into(), d[2].into()]),
                )
            };
            assert!(
                ulp <= 1,
                "meshoptimizer's decoder {ulp} units from the reference"
            );
        }
    }
}

fn diff(words: &[([i32; 3], i32, i32)], lib: impl Iterator<Item = [i32; 3]>) -> i32 {
    words
        .iter()
        .zip(lib)
        .flat_map(|((w, _, _), l)| (0..3).map(move |i| (w[i] - l[i]).abs()))
        .max()
        .unwrap()
}

#[test]
fn bevy_encoder_writes_bevys_snorm16x2() {
    let enc = function("bevy_oct32", Role::Encode);
    for v in inputs() {
        let want = bevy::encode(v);
        let want = u32::from(want[0] as u16) | u32::from(want[1] as u16) << 16;
        assert_eq!(run(&enc, &bits(v))[0], want, "{v:?}");
    }
}

/// `decode_float` is Bevy's `octahedral_decode_signed` bit for bit on every Snorm16 fetch
/// of a seeded million codes and of every code on the axes and the fold's edges; the
/// packed decoder, whose fetch is `c·fl(1/32767)`, is within 2^-22 of Bevy's fetch and
/// decode.
#[test]
fn bevy_decoders_are_bevys() {
    let (decf, dec) = (
        function("bevy_oct32", Role::DecodeFloat),
        function("bevy_oct32", Role::Decode),
    );
    let mut codes: Vec<(i16, i16)> = Vec::new();
    for c in i16::MIN..=i16::MAX {
        codes.extend([(c, 0), (0, c), (c, 32767), (-32767, c), (c, c), (c, -c)]);
    }
    let mut s = 7u32;
    for _ in 0..1_000_000 {
        s = s.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
        codes.push(((s >> 16) as i16, s as i16));
    }
    let mut worst = 0f32;
    for (x, y) in codes {
        let f = [bevy::snorm16_to_f32(x), bevy::snorm16_to_f32(y)];
        let got = run(&decf, &f.map(f32::to_bits));
        assert_eq!(
            got,
            bits(bevy::octahedral_decode_signed(f)),
            "fetched {f:?}"
        );
        let got = run(&dec, &[u32::from(x as u16) | u32::from(y as u16) << 16]);
        let want = bevy::decode([x, y]);
        for i in 0..3 {
            worst = worst.max((f32::from_bits(got[i]) - want[i]).abs());
        }
    }
    assert!(
        worst <= 2f32.powi(-22),
        "packed decode {worst:e} from Bevy's"
    );
}

#[test]
fn unity_encoder_writes_unitys_bytes() {
    let enc = function("unity_oct24", Role::Encode);
    for v in inputs() {
        let b = unity::encode(v);
        let want = u32::from(b[0]) | u32::from(b[1]) << 8 | u32::from(b[2]) << 16;
        assert_eq!(run(&enc, &bits(v))[0], want, "{v:?}");
    }
}

/// Every one of the 2^24 codes: the decoder is Unity's, its `/ 4095.0` taken as the
/// product by the reciprocal HLSL compilers write, so within 2^-20 of the quotient's
/// decode, and bit-equal where the product and the quotient agree for both codes (over
/// 2^22 of the codes, asserted); the float form reads back the bytes of
/// `Unpack888ToFloat2`.
#[test]
fn unity_decoders_are_unitys() {
    let (decf, dec) = (
        function("unity_oct24", Role::DecodeFloat),
        function("unity_oct24", Role::Decode),
    );
    let mut worst = 0f32;
    let same_fetch = |c: u32| c as f32 * (1.0 / 4095.0) == c as f32 / 4095.0;
    let mut equal = 0u32;
    for code in 0u32..1 << 24 {
        let b = code.to_le_bytes();
        let want = unity::decode([b[0], b[1], b[2]]);
        let got = run(&dec, &[code]);
        let (cx, cy) = (
            code & 0xff | (code >> 16 & 15) << 8,
            code >> 8 & 0xff | (code >> 20) << 8,
        );
        if same_fetch(cx) && same_fetch(cy) {
            assert_eq!(got, bits(want), "code {code:06x}");
            equal += 1;
        }
        for i in 0..3 {
            worst = worst.max((f32::from_bits(got[i]) - want[i]).abs());
        }
        if code % 97 == 0 {
            let f = [b[0], b[1], b[2]].map(unity::unorm8_to_f32);
            assert_eq!(run(&decf, &f.map(f32::to_bits)), got, "code {code:06x}");
        }
    }
    assert!(worst <= 2f32.powi(-20), "{worst:e}");
    assert!(equal > 1 << 22, "{equal} codes with both fetches equal");
}

/// `rounding=nearest` writes codes Unity's decoder reads, with a smaller error than
/// Unity's truncation (half its largest scalar error): the mean angle over a seeded
/// sample drops by more than a quarter (to 0.71 of it).
#[test]
fn unity_nearest_rounding_lowers_the_error() {
    let vs = unitpack::support::sampling::random_unit_vectors(5, 100_000, false);
    let mean = |spec: &str| {
        let (enc, dec) = (function(spec, Role::Encode), function(spec, Role::Decode));
        vs.iter()
            .map(|v| {
                let d = run(&dec, &run(&enc, &bits(*v)));
                let dot: f64 = (0..3)
                    .map(|i| f64::from(v[i]) * f64::from(f32::from_bits(d[i])))
                    .sum();
                dot.clamp(-1.0, 1.0).acos()
            })
            .sum::<f64>()
            / vs.len() as f64
    };
    let (trunc, near) = (mean("unity_oct24"), mean("unity_oct24:rounding=nearest"));
    assert!(
        near < trunc * 0.75,
        "nearest {near:e} vs truncate {trunc:e}"
    );
}

/// Draco's codes for every size, on the seeded and edge vectors, and its decoder on every
/// code up to 16 bits (N ≤ 8) and a seeded quarter million above, bit for bit.
#[test]
fn draco_matches_draco() {
    let vs = inputs();
    for n in [8u32, 10, 12, 14, 16] {
        let spec = format!("draco_oct{n}");
        let (enc, dec) = (function(&spec, Role::Encode), function(&spec, Role::Decode));
        for v in &vs {
            let [s, t] = draco::encode(*v, n);
            assert_eq!(
                run(&enc, &bits(*v))[0],
                s as u32 | (t as u32) << n,
                "{spec}: {v:?}"
            );
        }
        let max = (1u32 << n) - 2;
        let mut st: Vec<(u32, u32)> = Vec::new();
        if n <= 8 {
            st.extend((0..=max).flat_map(|s| (0..=max).map(move |t| (s, t))));
        } else {
            let mut r = 0x9e37_79b9_7f4a_7c15u64;
            for _ in 0..250_000 {
                r ^= r << 13;
                r ^= r >> 7;
                r ^= r << 17;
                st.push(((r as u32) % (max + 1), ((r >> 32) as u32) % (max + 1)));
            }
        }
        for (s, t) in st {
            let want = draco::decode(s as i32, t as i32, n);
            assert_eq!(run(&dec, &[s | t << n]), bits(want), "{spec}: ({s}, {t})");
        }
    }
}

/// Draco's codes on the inputs where its f64 roundings decide: exact ties `x·c/a = j + ½`
/// on integer vectors; those ties moved by a few ULP of a component, and by a component far
/// below the others at every exponent, with one, two and all 24 significant bits (so that
/// the sum's rounding, its sticky bit and the first sum's rounding to the larger term's
/// ULP each decide some of them), at every size; and the three inputs the engine check
/// found parting (Draco's codes as its own build wrote them).
#[test]
fn draco_oct_matches_draco_where_its_roundings_decide() {
    let ulps = |x: f32, k: i32| {
        if x == 0.0 {
            x
        } else {
            f32::from_bits(x.to_bits().wrapping_add_signed(k))
        }
    };
    let p2 = |e: i32| 2f32.powi(e.max(-126)) * 2f32.powi((e + 126).min(0));
    // Significands of the far smaller component: one bit, two, and all 24.
    let tinies = [
        1.0,
        -3.0,
        1.0 + f32::EPSILON,
        -(2.0 - f32::EPSILON),
        1.333_333_4,
    ];
    let far = |e: i32| tinies.map(|t| t * p2(e));
    let mut near: Vec<[f32; 3]> = Vec::new();
    for x in -24..=24 {
        for y in -24..=24 {
            for z in [-37, -5, 0, 3, 41, 254] {
                near.push([x as f32, y as f32, z as f32]);
            }
        }
    }
    // Two equal magnitudes and a far smaller third: the sum's last place then rests on the
    // third's top bit, and its sticky bit on the third's lowest.
    for x in 1..=8 {
        for e in -70..-30 {
            for tiny in far(e) {
                let x = x as f32;
                near.extend([[x, x, tiny], [x, -x, tiny], [tiny, x, x]]);
            }
        }
    }
    for x in [1, 2, 3, 7, 17, 100, 175] {
        for z in [-237, -79, 13, 99, 237, 253] {
            for e in -149..-8 {
                for tiny in far(e) {
                    near.extend([
                        [x as f32, tiny, z as f32],
                        [tiny, x as f32, z as f32],
                        [x as f32, z as f32, tiny],
                    ]);
                }
            }
        }
    }
    for n in [8u32, 10, 12, 14, 16] {
        let c = (1i64 << (n - 1)) - 1;
        let enc = function(&format!("draco_oct{n}"), Role::Encode);
        let mut ties = near.clone();
        // x·c/a = ½ at this size, moved by a far smaller component.
        for x in 1..4 {
            let z = (2 * c * x - x) as f32;
            for e in -149..-10 {
                for tiny in far(e) {
                    ties.extend([[x as f32, tiny, z], [tiny, x as f32, -z]]);
                }
            }
        }
        for x in 1..12 {
            for y in 0..6 {
                let z = (2 * c * x - x - y) as f32;
                for (sx, sz) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0)] {
                    let base = [sx * x as f32, y as f32, sz * z];
                    for k in [-2, -1, 0, 1, 2] {
                        ties.extend([
                            [ulps(base[0], k), base[1], base[2]],
                            [base[0], ulps(base[1], k), base[2]],
                            [base[0], base[1], ulps(base[2], k)],
                        ]);
                    }
                }
            }
        }
        for v in &ties {
            let [s, t] = draco::encode(*v, n);
            let got = run(&enc, &bits(*v))[0];
            let want = s as u32 | (t as u32) << n;
            assert_eq!(got, want, "draco_oct{n}: {v:?}: {got:#x}, Draco {want:#x}");
        }
    }
    let enc = function("draco_oct8", Role::Encode);
    for (v, want) in [
        // 2^-34 = 5.820766091346741e-11 and 2^-43 = 1.1368683772161603e-13.
        ([175.0, 2f32.powi(-34), -79.0], 0x577f),
        ([1.0, 2f32.powi(-43), 1.0], 0xbf7f),
        ([17.0, 0.0, 237.0], 0xf67f),
    ] {
        let [s, t] = draco::encode(v, 8);
        assert_eq!(s as u32 | (t as u32) << 8, want, "the port, {v:?}");
        assert_eq!(run(&enc, &bits(v))[0], want, "{v:?}");
    }
}

/// The one double `q` below ½ whose `q + ½` rounds up to 1, `½ - 2^-54`, is `c·p` rounded
/// for no double `p` at any of draco_oct's sizes (`c = 2^(N-1) - 1`), so the encoder's
/// `floor(q + ½)` never meets it (src/codecs/engine/draco_f64.rs): only a `p` within a
/// few ULP of `1/(2c)` could give a product that near ½, and none does.
#[test]
fn draco_oct_never_rounds_a_product_to_the_one_q_whose_half_rounds_up() {
    let q = 0.5 - 2f64.powi(-54);
    assert_eq!(q + 0.5, 1.0, "the double that rounds up");
    for n in 8..=16 {
        let c = ((1u64 << (n - 1)) - 1) as f64;
        let p = 1.0 / (2.0 * c);
        for k in -64i64..=64 {
            let p = f64::from_bits(p.to_bits().wrapping_add_signed(k));
            assert_ne!(p * c, q, "N = {n}: p = {p:e}");
        }
    }
}

/// Draco's `a > 1e-6` on sums at the threshold and one f64 step either side of it: 1e-6
/// split into three f32 parts (the largest f32 below it, the largest below the rest, the
/// remainder, each exact), the last moved by a step of `2^-72`, 1e-6's last place, so the
/// f64 sum is exactly at, below or above it. At or below, the code is +X's; above, the
/// direction's.
#[test]
fn draco_oct_takes_draco_s_threshold_as_draco_does() {
    let ulps = |x: f32, k: i32| f32::from_bits(x.to_bits().wrapping_add_signed(k));
    let below = |x: f64| {
        let f = x as f32;
        if f64::from(f) > x { ulps(f, -1) } else { f }
    };
    let d = 1e-6f64;
    let step = 2f64.powi(-72);
    let mut cases = [0usize; 3];
    let enc = function("draco_oct10", Role::Encode);
    for kx in 0..40 {
        let x = ulps(below(d), -kx);
        let rest = d - f64::from(x);
        let y = if rest == 0.0 { 0.0 } else { below(rest) };
        let last = rest - f64::from(y);
        for kz in -2..=2 {
            let z = (last + f64::from(kz) * step) as f32;
            assert_eq!(f64::from(z), last + f64::from(kz) * step, "an exact part");
            let sum = (f64::from(x) + f64::from(y)) + f64::from(z).abs();
            cases[(sum.partial_cmp(&d).unwrap() as i32 + 1) as usize] += 1;
            for v in [[x, y, z], [-y, z.abs(), -x], [z, -x, y]] {
                let [s, t] = draco::encode(v, 10);
                let got = run(&enc, &bits(v))[0];
                assert_eq!(got, s as u32 | (t as u32) << 10, "{v:?}: sum {sum:e}");
            }
        }
    }
    assert!(
        cases.iter().all(|&n| n > 0),
        "sums below, at and above 1e-6: {cases:?}"
    );
}
