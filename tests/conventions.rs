//! The conventions every codec states (README, "Conventions"), for every codec: sign at zero, oct fold sides, a defined valid
//! code for zero / NaN / ±inf / non-unit input, every code decodes to a finite vector.

use unitpack::codecs::Spec;
use unitpack::codecs::core::codec::sign_not_zero;
use unitpack::codecs::functions::function::{Emitted, Function, Inputs, Role};
use unitpack::codecs::octahedral::oct::{oct_direction, oct_params};
use unitpack::codecs::toolkit::quant::Quant;
use unitpack::model::{V2, V3};
use unitpack::verify::inputs;

fn role(e: &Emitted, r: Role) -> &Function {
    e.cpu_function(r).unwrap()
}

fn codecs() -> Vec<Spec> {
    Spec::all()
        .into_iter()
        .filter(|s| s.info().domain.is_some())
        .collect()
}

#[test]
fn sign_not_zero_counts_negative_zero_as_positive() {
    let s = sign_not_zero(V2::new(-0.0f32, 0.0));
    assert_eq!((s.x, s.y), (1.0, 1.0));
    let s = sign_not_zero(V2::new(-1e-45f32, f32::MIN_POSITIVE));
    assert_eq!((s.x, s.y), (-1.0, 1.0));
}

/// On the fold line itself folding changes nothing but the sign of zero, so signed zeros
/// are what tell `z <= 0` from `z < 0`: compare bits.
#[test]
fn oct_folds_on_encode_at_z_le_0_and_on_decode_at_z_lt_0() {
    // Encode: z = +0 folds (z <= 0), and folding (-0, 1) gives x = +0.
    let p = oct_params(V3::new(-0.0f32, 1.0, 0.0));
    assert_eq!(
        (p.x.to_bits(), p.y),
        (0.0f32.to_bits(), 1.0),
        "z = +0 must fold"
    );
    let p = oct_params(V3::new(-0.0f32, 1.0, -0.0));
    assert_eq!(p.x.to_bits(), 0.0f32.to_bits(), "z = -0 must fold");
    let p = oct_params(V3::new(-0.0f32, 1.0, 1e-30));
    assert_eq!(p.x.to_bits(), (-0.0f32).to_bits(), "z > 0 must not fold");
    // Decode: (-0, 1) has z = 0 exactly, which must not unfold: x stays -0.
    let v = oct_direction(V2::new(-0.0f32, 1.0));
    assert_eq!(
        (v.x.to_bits(), v.y, v.z),
        ((-0.0f32).to_bits(), 1.0, 0.0),
        "z = 0 must not unfold"
    );
    // Below the diamond both rules unfold.
    let p = oct_params(V3::new(0.25f32, 0.25, -0.5));
    assert_eq!((p.x, p.y), (0.75, 0.75));
    let v = oct_direction(V2::new(0.75f32, 0.75));
    assert!(v.z < 0.0 && v.x > 0.0 && v.y > 0.0);
}

/// Every codec but the engine formats, whose degenerate input gets the engine's own code
/// (their edge policy says which; tests/families/engine.rs holds them to the engines),
/// and those that take the input as it is (`Family::keeps_length`: glTF's quantization,
/// held to gltf-transform by tests/families/gltf.rs).
#[test]
fn degenerate_input_encodes_to_the_documented_code() {
    for (spec, r) in codecs()
        .into_iter()
        .filter(|s| s.family().engine(s).is_none() && !s.family().keeps_length())
        .flat_map(|s| [(s.clone(), Role::Encode), (s, Role::EncodeFloat)])
    {
        let e = spec.emitted();
        let enc = role(&e, r);
        let mut plus_z = vec![0u32; enc.out_words];
        (enc.eval)(&[0f32, 0.0, 1.0].map(f32::to_bits), &mut plus_z);
        for bad in [
            [0.0f32, 0.0, 0.0],
            [-0.0, -0.0, -0.0],
            [f32::NAN, 0.0, 0.0],
            [0.0, f32::NAN, 1.0],
            [f32::INFINITY, 0.0, 0.0],
            [0.0, f32::NEG_INFINITY, 0.0],
            [1.0, 0.0, f32::NAN],
            [1.0, 0.0, f32::NEG_INFINITY],
            [1.0, 0.0, f32::INFINITY],
        ] {
            let mut code = vec![0u32; enc.out_words];
            (enc.eval)(&bad.map(f32::to_bits), &mut code);
            assert_eq!(
                code, plus_z,
                "{spec} {r:?}: {bad:?} must encode as +Z ({plus_z:x?}), got {code:x?}"
            );
        }
    }
}

/// hemioct's float form projects the input onto the hemisphere before fitting its range:
/// a hemisphere L1 norm that is denormal or tiny beside `z` still gives the horizon
/// direction (no denormal reaches the division), and a NaN `z` is not projected away.
#[test]
fn hemioct_float_form_fits_the_projected_input() {
    use unitpack::codecs::Codec;
    use unitpack::codecs::octahedral::hemioct::HemiOct;
    let c = HemiOct { bits: 16 };
    for (v, want) in [
        ([1e-45f32, 1e-45, -1.0], [1.0f32, 0.0]),
        ([1e-13, 0.0, -1.0], [1.0, 1.0]),
        ([0.0, -3e-39, -5.0], [-1.0, 1.0]),
        ([0.5, 0.5, f32::NAN], [0.0, 0.0]),
        ([0.5, 0.5, f32::NEG_INFINITY], [0.0, 0.0]),
        ([0.0, 0.0, -1.0], [0.0, 0.0]),
    ] {
        let p = c.params(V3::from_array(v));
        assert_eq!([p.x, p.y], want, "{v:?}");
    }
}

/// Scaling by a power of two changes no rounding anywhere in the encoders, so the code
/// must be identical, from denormal-adjacent to overflowing magnitudes. The lean tier
/// (`guarantee=ieee`) leaves out the range fit by design (its doc comment says so): it
/// is held to the magnitudes whose norm neither overflows nor underflows. A codec that
/// takes the input as it is (`Family::keeps_length`) is not held to it.
#[test]
fn non_unit_input_encodes_like_its_direction() {
    for spec in codecs().into_iter().filter(|s| !s.family().keeps_length()) {
        let lean = unitpack::codecs::core::ieee::asked(&spec);
        let scales: &[i32] = if lean {
            &[-20, -1, 1, 20]
        } else {
            &[-100, -20, -1, 1, 20, 100, 127]
        };
        let e = spec.emitted();
        let enc = role(&e, Role::Encode);
        let code = |v: [f32; 3]| {
            let mut c = vec![0u32; enc.out_words];
            (enc.eval)(&v.map(f32::to_bits), &mut c);
            c
        };
        for dir in [
            [0.36f32, 0.48, 0.8],
            [0.36, -0.48, -0.8],
            [1.0, 1.0, 0.0],
            [-0.6, 0.0, 0.8],
        ] {
            let want = code(dir);
            for &k in scales {
                let scaled = dir.map(|x| x * 2f32.powi(k));
                assert_eq!(code(scaled), want, "{spec}: {dir:?} scaled by 2^{k}");
            }
        }
        // Components so large that their L1 norm (or squared length) overflows. Not a
        // power-of-two multiple: float32x3 floors the input's own digits before its
        // integer arithmetic (`exact::unit_on_grid`), so its components may move with the
        // magnitude, provably by under 19 units of 2^-24 (tests/api.rs); every other
        // codec decides its codes from the direction alone.
        if lean {
            continue;
        }
        for (huge, unit) in [
            ([3e38, 3e38, 0.0], [1.0, 1.0, 0.0]),
            ([-f32::MAX, 0.0, f32::MAX], [-1.0, 0.0, 1.0]),
        ] {
            let (a, b) = (code(huge), code(unit));
            if spec.to_string() == "float32x3" {
                for (x, y) in a.iter().zip(&b) {
                    let d = (f64::from(f32::from_bits(*x)) - f64::from(f32::from_bits(*y))).abs();
                    assert!(
                        d <= 19.0 * 2f64.powi(-24),
                        "{spec}: {huge:?} → {a:x?} vs {b:x?}"
                    );
                }
            } else {
                assert_eq!(a, b, "{spec}: {huge:?} encodes unlike {unit:?}");
            }
        }
    }
}

#[test]
fn every_encoder_output_is_a_valid_code_and_every_code_decodes_finite() {
    // Tens of millions of decodes: the specs are spread over every core.
    let specs = codecs();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(|| {
                while let Some(spec) =
                    specs.get(next.fetch_add(1, std::sync::atomic::Ordering::Relaxed))
                {
                    every_code_of(spec);
                }
            });
        }
    });
}

/// One spec's edge vectors round trip to finite values and every code decodes finite.
fn every_code_of(spec: &Spec) {
    let edges = inputs::edge_vectors();
    let e = spec.emitted();
    let (enc, dec, encf) = (
        role(&e, Role::Encode),
        role(&e, Role::Decode),
        role(&e, Role::EncodeFloat),
    );
    let mut out = [0u32; 3];
    for v in &edges {
        let mut code = vec![0u32; enc.out_words];
        (enc.eval)(&v.map(f32::to_bits), &mut code);
        (dec.eval)(&code, &mut out);
        assert!(
            out.iter().all(|b| f32::from_bits(*b).is_finite()),
            "{spec}: {v:?} → {code:x?} decodes non-finite"
        );
        let mut p = vec![0u32; encf.out_words];
        (encf.eval)(&v.map(f32::to_bits), &mut p);
        assert!(
            p.iter().all(|b| f32::from_bits(*b).is_finite()),
            "{spec}: float encoder gives non-finite parameters for {v:?}"
        );
    }
    // Every code (all of them up to 24 bits, a seeded sample above), decoded a block of
    // codes per call: one call per code cost a cheap decoder several times its arithmetic.
    const BLOCK: usize = 1 << 16;
    let codes = inputs::generate(&dec.inputs, dec.in_words);
    let mut decoded = vec![0u32; BLOCK * dec.out_words];
    for block in codes.chunks(BLOCK * dec.in_words) {
        let decoded = &mut decoded[..block.len() / dec.in_words * dec.out_words];
        (dec.eval)(block, decoded);
        for (c, v) in block
            .chunks(dec.in_words)
            .zip(decoded.chunks(dec.out_words))
        {
            assert!(
                v.iter().all(|b| f32::from_bits(*b).is_finite()),
                "{spec}: code {c:x?} decodes to {:?}",
                v.iter().map(|b| f32::from_bits(*b)).collect::<Vec<_>>()
            );
        }
    }
}

#[test]
fn trace_refuses_non_portable_arithmetic() {
    use unitpack::model::Float;
    use unitpack::model::trace::{Tf, define, trace_module};
    let refused = |f: fn(Tf) -> Tf| {
        std::panic::catch_unwind(|| trace_module(|| define("f", &["x"], f))).is_err()
    };
    assert!(refused(|x| x / Tf::c(3.0)), "division by a literal");
    assert!(refused(|x| Tf::c(2.0) / x), "literal numerator");
    assert!(
        !refused(|x| Tf::c(1.0) / x),
        "1/x: drivers compute rcp(x), which rounds as the division does"
    );
    assert!(
        refused(|_| Tf::c(0.1) * Tf::c(3.0)),
        "constant expression that rounds"
    );
    assert!(
        !refused(|_| Tf::c(2.0) * Tf::c(3.0) + Tf::c(256.0)),
        "an exact constant expression is folded: the same in f32 and f64"
    );
    assert!(
        refused(|x| x * Tf::c(3.0) * Tf::c(5.0)),
        "literal multiply chain"
    );
    assert!(
        !refused(|x| x * Tf::c(1.0 / 3.0)),
        "reciprocal multiply is the allowed form"
    );
    assert!(
        !refused(|x| x * Tf::c(3.0) * Tf::c(4.0)),
        "a power-of-two factor folds exactly"
    );
    // The same chains across helper calls, which drivers inline before folding.
    fn scales(x: Tf) -> Tf {
        x * Tf::c(5.0)
    }
    assert!(
        refused(|x| Tf::call("h", &[], x * Tf::c(3.0), scales)),
        "literal product passed to a helper that scales it"
    );
    assert!(
        refused(|x| Tf::call("k", &[], x * Tf::c(3.0), |y: Tf| Tf::call(
            "g",
            &[],
            y,
            scales
        ))),
        "a helper forwarding its parameter to one that scales it"
    );
    assert!(
        refused(|x| Tf::call("h", &[], x, |y: Tf| y * Tf::c(3.0)) * Tf::c(5.0)),
        "a helper's literal product scaled again by the caller"
    );
    assert!(
        !refused(|x| Tf::call("h", &[], x * Tf::c(3.0), |y: Tf| y * Tf::c(4.0))),
        "powers of two are exempt across calls too"
    );
    assert!(
        !refused(|x| Tf::call("h", &[], x * Tf::c(3.0), |y: Tf| y + Tf::c(5.0))),
        "a helper that does not scale its parameter"
    );
}

/// The select-based vocabulary states its ±0 and NaN results; check them on raw bits.
#[test]
fn select_based_min_max_clamp_and_normalize_state_their_edge_results() {
    use unitpack::model::{Float, V2, V3};
    let bits = |x: f32| x.to_bits();
    assert_eq!(bits((-0.0f32).at_least(0.0)), bits(-0.0), "ties keep self");
    assert_eq!(bits(0.0f32.at_least(-0.0)), bits(0.0));
    assert_eq!(
        bits(f32::NAN.at_least(-1.0)),
        bits(-1.0),
        "NaN gives the bound"
    );
    assert_eq!(bits(f32::NAN.at_most(1.0)), bits(1.0));
    assert_eq!(bits(f32::NAN.clamped(-1.0, 1.0)), bits(-1.0));
    assert_eq!(bits(3.0f32.clamped(-1.0, 1.0)), bits(1.0));
    assert_eq!(bits((-3.0f32).clamped(-1.0, 1.0)), bits(-1.0));
    assert_eq!(bits(0.25f32.clamped(-1.0, 1.0)), bits(0.25));
    let fb = V2::new(0.0f32, 1.0);
    assert_eq!(V2::new(0.0f32, 0.0).normalize_or(fb), fb);
    assert_eq!(V2::new(-0.0f32, 0.0).normalize_or(fb), fb);
    assert_eq!(V2::new(f32::NAN, 1.0).normalize_or(fb), fb);
    assert_eq!(V2::new(3.0f32, 4.0).normalize_or(fb), V2::new(0.6, 0.8));
    let z = V3::new(0.0f32, 0.0, 1.0);
    assert_eq!(V3::new(0.0f32, 0.0, 0.0).normalize_or(z), z);
    assert_eq!(
        V3::new(0.0f32, -2.0, 0.0).normalize_or(z),
        V3::new(0.0, -1.0, 0.0)
    );
}

/// What a render target of the matching format stores for float-form parameters, computed
/// independently of the model: the graphics APIs' float→unorm/snorm conversion in f64,
/// fields in texel order from the lowest bits (RG8, RG16, A2B10G10R10, RGBA16 words...).
fn texel(q: &[Quant], params: &[f32]) -> Vec<u32> {
    let mut words = [0u64; 3];
    let mut bit = 0u32;
    for (quant, &x) in q.iter().zip(params) {
        let (field, bits) = match *quant {
            Quant::Snorm(b) => {
                let m = ((1u64 << (b - 1)) - 1) as f64;
                let c = (f64::from(x).clamp(-1.0, 1.0) * m).round() as i64;
                ((c as u64) & ((1 << b) - 1), b)
            }
            Quant::Unorm(b) => {
                let m = ((1u64 << b) - 1) as f64;
                ((f64::from(x).clamp(0.0, 1.0) * m).round() as u64, b)
            }
            Quant::Half => (half_of(x), 16),
            Quant::Single => (u64::from(x.to_bits()), 32),
        };
        if bit % 32 + bits > 32 {
            bit = (bit / 32 + 1) * 32; // a field never straddles a 32-bit word
        }
        words[(bit / 32) as usize] |= field << (bit % 32);
        bit += bits;
    }
    words
        .iter()
        .take(bit.div_ceil(32) as usize)
        .map(|w| *w as u32)
        .collect()
}

/// The grid an f32 → f16 conversion rounds `|x| ≤ 65504` to: `2^(e-10)` in the binade
/// `[2^e, 2^(e+1))`, `2^-24` below `2^-14`; as the factor that scales it to integers.
fn half_scale(x: f64) -> f64 {
    let e = x.abs().log2().floor().max(-14.0);
    2f64.powf(10.0 - e)
}

/// IEEE 754 f32 → binary16 with ties to even (what an RGBA16_FLOAT target stores), by
/// the definition of the format.
fn half_of(x: f32) -> u64 {
    let sign = if x.is_sign_negative() { 0x8000 } else { 0 };
    let a = f64::from(x).abs();
    if a == 0.0 {
        return sign;
    }
    let k = half_scale(a);
    let c = (a * k).round_ties_even();
    let e = 10.0 - k.log2(); // the binade's exponent
    let (c, e) = if c >= 2048.0 {
        (c / 2.0, e + 1.0)
    } else {
        (c, e)
    };
    if c < 1024.0 {
        sign | c as u64 // subnormal
    } else if e > 15.0 {
        sign | 0x7c00
    } else {
        sign | ((e + 15.0) as u64) << 10 | (c as u64 - 1024)
    }
}

#[test]
fn packed_code_is_the_texel_a_render_target_would_store() {
    let vs = unitpack::support::sampling::random_unit_vectors(11, 20_000, false);
    for spec in codecs() {
        let e = spec.emitted();
        let (enc, encf, dec) = (
            role(&e, Role::Encode),
            role(&e, Role::EncodeFloat),
            role(&e, Role::Decode),
        );
        let Inputs::Codes(q) = &dec.inputs else {
            panic!("{spec}: decoder inputs")
        };
        // The near-tie window below is eight f32 ULP of the scaled parameter: up to about
        // 6 % of the inputs for a 16-bit field, but a quarter of a code for a 20-bit one,
        // where an f32 parameter no longer decides the code. Said at once, by name.
        for field in q {
            assert!(
                matches!(field, Quant::Single | Quant::Half) || field.bits() <= 16,
                "{spec}: a {}-bit field ({field:?}): this check holds a packed code to the \
                 texel of its f32 float form, which decides fields of at most 16 bits; a \
                 wider field needs an oracle of its own (split it into fields of 16 bits or \
                 fewer, or extend this test)",
                field.bits()
            );
        }
        let mut ties = 0;
        for v in &vs {
            let mut code = vec![0u32; enc.out_words];
            (enc.eval)(&v.map(f32::to_bits), &mut code);
            let mut p = vec![0u32; encf.out_words];
            (encf.eval)(&v.map(f32::to_bits), &mut p);
            let p: Vec<f32> = p.iter().map(|b| f32::from_bits(*b)).collect();
            // Near a half the APIs allow either neighbour (D3D11 multiplies in f32, as the
            // model does; an exact conversion may land on the other side), and the float
            // form, rounded several times on its way (lambert: a product, a quotient, a
            // root, a quotient, a sum), may sit a few ULP from the exact parameter the
            // packed encoder rounds (ULP of the terms before the unorm's `+ 0.5`, so of
            // at least half the range), and the packed encoder decides its boundaries from
            // deterministic stand-ins accurate to a few units of 2^-23 (eqdist's polar
            // angle, in units of 2^-23 half turns, puts the radius on a 2^-22 grid): skip
            // inputs within eight such ulps of a half.
            // float32x3's packed components are decided from integers on the 2^-24 grid
            // (the input floored to 2^-21 of its largest component's binade first), so
            // they are near what an RGB32_FLOAT target stores, not equal to it.
            if q[0] == Quant::Single {
                for (w, x) in code.iter().zip(&p) {
                    let d = (f64::from(f32::from_bits(*w)) - f64::from(*x)).abs();
                    assert!(d <= 2f64.powi(-21), "{spec}: {v:?} → {code:08x?} vs {p:?}");
                }
                continue;
            }
            // A texel channel of exactly ½ is exact, not near a tie: rxgb's blue holds
            // `z·½ + ½` of the input projected onto the hemisphere, and every input below
            // the horizon projects to z = 0; unorm ties go up, as f64's round does.
            let tie = q.iter().zip(&p).any(|(q, x)| {
                if matches!(q, Quant::Unorm(_)) && *x == 0.5 {
                    return false;
                }
                let m = match q {
                    Quant::Half => half_scale(f64::from(*x)),
                    Quant::Single => unreachable!("compared above"),
                    _ => f64::from(q.max_code()),
                };
                let scaled = f64::from(*x) * m;
                let ulp = 8.0 * scaled.abs().max(m / 2.0) * 2f64.powi(-23);
                (scaled - scaled.floor() - 0.5).abs() <= ulp + 1e-12
            });
            if tie {
                ties += 1;
                continue;
            }
            assert_eq!(code, texel(q, &p), "{spec}: {v:?} → params {p:?}");
        }
        // A 16-bit field's window is ±1/32 of a code: up to about 6 % of the inputs per
        // field.
        assert!(
            ties < vs.len() / 6,
            "{spec}: {ties} near-ties of {}",
            vs.len()
        );
    }
}
