//! The conventions every codec states (README, "Conventions"), for every codec: sign at zero, oct fold sides, a defined valid
//! code for zero / NaN / ±inf / non-unit input, every code decodes to a finite vector.

use unitpack::codecs::Spec;
use unitpack::codecs::codec::sign_not_zero;
use unitpack::codecs::functions::{Emitted, Function, Role};
use unitpack::codecs::oct::{oct_direction, oct_params};
use unitpack::model::{V2, V3};
use unitpack::verify::inputs;

fn role(e: &Emitted, r: Role) -> &Function {
    e.functions.iter().find(|f| f.role == r).unwrap()
}

fn codecs() -> Vec<Spec> {
    Spec::all()
        .into_iter()
        .filter(|s| s.codec.domain.is_some())
        .collect()
}

#[test]
fn sign_not_zero_counts_negative_zero_as_positive() {
    let s = sign_not_zero(V2::new(-0.0f32, 0.0));
    assert_eq!((s.x, s.y), (1.0, 1.0));
    let s = sign_not_zero(V2::new(-1e-45f32, f32::MIN_POSITIVE));
    assert_eq!((s.x, s.y), (-1.0, 1.0));
}

#[test]
fn oct_folds_on_encode_at_z_le_0_and_on_decode_at_z_lt_0() {
    // z = +0 and z = -0 are both folded by the encoder: the equator maps to the border.
    for z in [0.0f32, -0.0] {
        let p = oct_params(V3::new(0.5f32, 0.5, z));
        assert_eq!((p.x, p.y), (0.5, 0.5), "equator point with z = {z:?}");
    }
    let p = oct_params(V3::new(0.25f32, 0.25, 0.5));
    assert_eq!((p.x, p.y), (0.25, 0.25), "upper hemisphere is not folded");
    let p = oct_params(V3::new(0.25f32, 0.25, -0.5));
    assert_eq!((p.x, p.y), (0.75, 0.75), "lower hemisphere is folded");
    // Decode: on the diamond's edge z = 0 is not unfolded; outside it is.
    let v = oct_direction(V2::new(0.5f32, 0.5));
    assert!(v.z == 0.0 && v.x > 0.0 && v.y > 0.0);
    let v = oct_direction(V2::new(0.75f32, 0.75));
    assert!(v.z < 0.0 && v.x > 0.0 && v.y > 0.0);
}

#[test]
fn degenerate_input_encodes_to_the_documented_code() {
    for spec in codecs() {
        let e = spec.emitted();
        let enc = role(&e, Role::Encode);
        let mut plus_z = vec![0u32; enc.out_words];
        (enc.eval)(&[0f32, 0.0, 1.0].map(f32::to_bits), &mut plus_z);
        for bad in [
            [0.0f32, 0.0, 0.0],
            [-0.0, -0.0, -0.0],
            [f32::NAN, 0.0, 0.0],
            [0.0, f32::NAN, 1.0],
            [f32::INFINITY, 0.0, 0.0],
            [0.0, f32::NEG_INFINITY, 0.0],
        ] {
            let mut code = vec![0u32; enc.out_words];
            (enc.eval)(&bad.map(f32::to_bits), &mut code);
            assert_eq!(
                code, plus_z,
                "{spec}: {bad:?} must encode as +Z ({plus_z:x?}), got {code:x?}"
            );
        }
    }
}

#[test]
fn non_unit_input_encodes_like_its_direction() {
    for spec in codecs() {
        let e = spec.emitted();
        let (enc, dec) = (role(&e, Role::Encode), role(&e, Role::Decode));
        let hemi = spec.codec.domain == Some(unitpack::codecs::codec::Domain::Hemisphere);
        let dir = if hemi {
            [0.36f32, 0.48, 0.8]
        } else {
            [0.36f32, -0.48, -0.8]
        };
        let mut want = vec![0u32; enc.out_words];
        (enc.eval)(&dir.map(f32::to_bits), &mut want);
        for scale in [1e-30f32, 1e-3, 7.0, 1e30] {
            let mut code = vec![0u32; enc.out_words];
            (enc.eval)(&dir.map(|x| (x * scale).to_bits()), &mut code);
            let mut a = [0u32; 3];
            let mut b = [0u32; 3];
            (dec.eval)(&code, &mut a);
            (dec.eval)(&want, &mut b);
            let (a, b) = (a.map(f32::from_bits), b.map(f32::from_bits));
            let angle = unitpack::quality::angle_deg(a, b);
            assert!(
                angle < 1.5,
                "{spec}: scale {scale} decodes {angle}° away from the unit input"
            );
        }
    }
}

#[test]
fn every_encoder_output_is_a_valid_code_and_every_code_decodes_finite() {
    let edges = inputs::edge_vectors();
    for spec in codecs() {
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
        // Every code (all of them up to 24 bits, a seeded sample above).
        let codes = inputs::generate(&dec.inputs, dec.in_words);
        for c in codes.chunks(dec.in_words) {
            (dec.eval)(c, &mut out);
            let v = out.map(f32::from_bits);
            assert!(
                v.iter().all(|x| x.is_finite()),
                "{spec}: code {c:x?} decodes to {v:?}"
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
    assert!(refused(|_| Tf::c(2.0) * Tf::c(3.0)), "constant expression");
    assert!(
        refused(|x| x * Tf::c(3.0) * Tf::c(5.0)),
        "literal multiply chain"
    );
    assert!(
        !refused(|x| x * Tf::c(1.0 / 3.0)),
        "reciprocal multiply is the allowed form"
    );
}
