//! Every codec spec, with no figure of its own: each input lies within the reach of its
//! code's neighbours. A rounding encoder puts the input within half a step of its code in
//! every field, so (where the map is smooth) its decode is at most half the sum, over the
//! fields, of how far one step moves the decode; a precise encoder's code is nearer
//! still. The test allows the whole sum, for the map's curvature. A codec whose encoder
//! and decoder disagree (a wrong sign, fold, axis or scale) sends inputs to codes far from
//! them, and fails wherever that happens, whatever its family.
//!
//! Fields of fewer than four bits select (a hemisphere, a cube face) rather than measure,
//! and are not stepped; float32 fields (float32x3) are finer than the codec's own grid,
//! which `accuracy::float32x3_is_within_its_grids` bounds instead. An input whose code sits
//! at the end of a field's range, where a codec may clamp what it cannot represent (the
//! scaled stereographic codec beyond its disk), is not held to the bound; at least half
//! of each sample must be.
//!
//! The README's statistics ([`crate::stats`]) are means and maxima: this needs each
//! input's code, so it encodes its own smaller sample of the same seeded vectors.

use unitpack::codecs::Spec;
use unitpack::codecs::core::info::Domain;
use unitpack::codecs::functions::function::{Function, Inputs, Role};
use unitpack::codecs::toolkit::quant::{Quant, field_offsets};
use unitpack::measure::figures::VECTOR_SEED;
use unitpack::measure::quality::angle_deg;
use unitpack::report::doc_tables::codec_specs;
use unitpack::support::sampling::random_unit_vectors;

/// Vectors per spec: the first ones of the README's sample.
const SAMPLES: usize = 1 << 13;

/// Fields narrower than this select rather than measure.
const MEASURING_BITS: u32 = 4;

/// The decoder's own rounding, a few f32 ULP of a unit vector, in degrees: what a step
/// finer than it could not show.
const ROUNDING_DEG: f64 = 1e-5;

/// The code with field `i` (at bit `off`) moved one step by `dir` (±1) in value order,
/// or `None` at the end of the field's range.
fn step(code: &[u32], q: Quant, off: u32, dir: i64) -> Option<Vec<u32>> {
    let (w, sh) = ((off / 32) as usize, off % 32);
    let mask = (((1u64 << q.bits()) - 1) as u32) << sh;
    let raw = i64::from((code[w] & mask) >> sh);
    let next = match q {
        Quant::Snorm(b) => {
            let m = (1i64 << (b - 1)) - 1;
            let v = if raw > m { raw - (1 << b) } else { raw };
            let n = v + dir;
            if v < -m || n.abs() > m {
                return None;
            }
            n & ((1 << b) - 1)
        }
        Quant::Unorm(b) => {
            let n = raw + dir;
            if n < 0 || n >= 1 << b {
                return None;
            }
            n
        }
        // binary16 in value order: sign and magnitude as one signed integer.
        Quant::Half => {
            let v = if raw & 0x8000 != 0 {
                -(raw & 0x7fff)
            } else {
                raw
            };
            let n = v + dir;
            let bits = if n < 0 { 0x8000 | -n } else { n };
            if bits & 0x7c00 == 0x7c00 || raw & 0x7c00 == 0x7c00 {
                return None;
            }
            bits
        }
        Quant::Single => unreachable!("float32 fields are not stepped"),
    };
    let mut c = code.to_vec();
    c[w] = (c[w] & !mask) | ((next as u32) << sh);
    Some(c)
}

/// How the inputs of a spec's sample sit against their codes' neighbours' reach.
struct Cover {
    /// Inputs whose codes are off every stepped field's ends.
    checked: usize,
    /// The largest error beyond the reach (negative: within it), its reach and input.
    excess: f64,
    reach: f64,
    at: [f32; 3],
}

/// Encodes the sample with `enc` and decodes with `dec` (of the fields `q`).
fn cover(enc: &Function, dec: &Function, q: &[Quant], hemisphere: bool) -> Cover {
    let offs = field_offsets(q);
    let vs = random_unit_vectors(VECTOR_SEED, SAMPLES, hemisphere);
    let input: Vec<u32> = vs.iter().flat_map(|v| v.map(f32::to_bits)).collect();
    let mut codes = vec![0u32; SAMPLES * enc.out_words];
    enc.eval_many(&input, &mut codes);
    let decode = |c: &[u32]| {
        let mut o = [0u32; 3];
        (dec.eval)(c, &mut o);
        o.map(f32::from_bits)
    };
    let mut out = Cover {
        checked: 0,
        excess: f64::NEG_INFINITY,
        reach: 0.0,
        at: [0.0; 3],
    };
    // A field the encoder writes as one constant (a texel's constant channel, such as
    // xra's R = 1) measures nothing, though the decoder reads it.
    let raw = |c: &[u32], i: usize| c[(offs[i] / 32) as usize] >> (offs[i] % 32) & q[i].mask();
    let constant: Vec<bool> = (0..q.len())
        .map(|i| {
            let mut all = codes.chunks_exact(enc.out_words).map(|c| raw(c, i));
            let first = all.next();
            all.all(|x| Some(x) == first)
        })
        .collect();
    'sample: for (v, c) in vs.iter().zip(codes.chunks_exact(enc.out_words)) {
        let at = decode(c);
        let mut reach = 0.0;
        for (i, &field) in q.iter().enumerate() {
            if field.bits() < MEASURING_BITS || constant[i] {
                continue;
            }
            let (mut far, mut end) = (0f64, false);
            for dir in [-1, 1] {
                match step(c, field, offs[i], dir) {
                    Some(n) => far = far.max(angle_deg(at, decode(&n))),
                    None => end = true,
                }
            }
            // Nor does a field the decoder does not read (rxgb's z), wherever its value.
            if far == 0.0 {
                continue;
            }
            if end {
                continue 'sample;
            }
            reach += far;
        }
        out.checked += 1;
        let excess = angle_deg(*v, at) - reach - ROUNDING_DEG;
        if excess > out.excess {
            (out.excess, out.reach, out.at) = (excess, reach, *v);
        }
    }
    out
}

fn encoder_and_decoder(spec: &Spec) -> (Function, Function, Vec<Quant>, bool) {
    let e = spec.emitted();
    let find = |r: Role| e.cpu_function(r).expect("a codec function").clone();
    let dec = find(Role::Decode);
    let q = fields(&dec.inputs);
    let hemisphere = spec.info().domain == Some(Domain::Hemisphere);
    (find(Role::Encode), dec, q, hemisphere)
}

/// The specs whose encoders are coarser than their own codes, and why: they must stay
/// beyond reach (the list cannot go stale), and every other spec within it.
const BEYOND_REACH: &[(&str, &str)] = &[(
    "spherical_lut16",
    "the seed's tables read codes as c/128 - 1 where the encoder writes c/127.5 - 1, \
     which puts its worst errors near the poles (README, spherical_lut; lut=matched is within reach)",
)];

#[test]
fn every_input_lies_within_its_codes_neighbours_reach() {
    let specs: Vec<Spec> = codec_specs()
        .into_iter()
        .filter(|s| !encoder_and_decoder(s).2.contains(&Quant::Single))
        .collect();
    assert!(specs.len() > 200, "{}", specs.len());
    let failures: Vec<String> = unitpack::support::par::map(&specs, |spec| {
        let (enc, dec, q, hemisphere) = encoder_and_decoder(spec);
        let c = cover(&enc, &dec, &q, hemisphere);
        let mut out = Vec::new();
        let id = spec.to_string();
        if let Some((_, why)) = BEYOND_REACH.iter().find(|(s, _)| *s == id) {
            if c.excess <= 0.0 {
                out.push(format!(
                    "{spec} is now within reach: remove it from BEYOND_REACH"
                ));
            }
            println!("{spec}: {:.6}° beyond reach, as stated ({why})", c.excess);
        } else if c.excess > 0.0 {
            out.push(format!(
                "{spec}: {:?} lies {:.6}° beyond its code's neighbours' reach ({:.6}°)",
                c.at, c.excess, c.reach
            ));
        }
        if c.checked < SAMPLES / 2 {
            out.push(format!(
                "{spec}: only {} of {SAMPLES} inputs have codes off their fields' ends",
                c.checked
            ));
        }
        out
    })
    .into_iter()
    .flatten()
    .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The test can fail: an encoder paired with the decoder of another map on the same
/// layout (oct16's codes read as eqarea_oct16's and back, the concentric eqarea codes
/// read as stereographic ones) lands inputs beyond their codes' reach.
#[test]
fn a_mismatched_encoder_and_decoder_fail_the_cover() {
    for (a, b) in [
        ("oct16", "eqarea_oct16"),
        ("eqarea_oct16", "oct16"),
        ("eqarea_concentric16", "stereo_concentric16"),
    ] {
        let (enc, _, _, hemisphere) = encoder_and_decoder(&a.parse().unwrap());
        let (_, dec, q, _) = encoder_and_decoder(&b.parse().unwrap());
        let c = cover(&enc, &dec, &q, hemisphere);
        assert!(c.excess > 0.0, "{a} read as {b}: within by {}°", -c.excess);
        assert!(c.checked >= SAMPLES / 2, "{a} read as {b}: {}", c.checked);
    }
}

/// The fields of a decoder's packed code.
fn fields(inputs: &Inputs) -> Vec<Quant> {
    match inputs {
        Inputs::Codes(q) | Inputs::CodesWith(q, _) | Inputs::CodesAndIndex(q, _) => q.clone(),
        other => panic!("a decoder of packed codes, not {other:?}"),
    }
}
