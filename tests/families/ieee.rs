//! The lean tier (`guarantee=ieee`): the same codec in plain arithmetic. Its codes are the
//! default tier's but near a rounding boundary, zero, NaN and infinite input encode as +Z
//! as in the default tier, a texel layout and the precise encoder refuse it, and its doc
//! comment calls it not portable. That it is bit-exact on every
//! verify path is `verify`'s (tests/verify_gpu.rs), its instruction count the figures'.

use unitpack::codecs::Spec;
use unitpack::codecs::functions::function::{Function, Role};
use unitpack::support::sampling::random_unit_vectors;
use unitpack::{Generator, Lang};

/// The families with a lean tier, at the sizes checked here.
const SPECS: [&str; 7] = [
    "oct16",
    "oct32",
    "hemioct16",
    "hemioct32",
    "lambert16",
    "stereo_scaled16",
    "xy16",
];

fn spec(text: &str) -> Spec {
    text.parse()
        .unwrap_or_else(|e| panic!("{text} is a spec: {e}"))
}

/// The packed encoder of `text`.
fn encoder(text: &str) -> Function {
    spec(text)
        .emitted()
        .functions
        .iter()
        .find(|f| f.role == Role::Encode && f.name == "encode")
        .cloned()
        .unwrap_or_else(|| panic!("{text} has a packed encoder"))
}

/// Each vector's code: the encoder's output words, one item at a time.
fn codes(f: &Function, vectors: &[[f32; 3]]) -> Vec<Vec<u32>> {
    vectors
        .iter()
        .map(|v| {
            let mut out = vec![0u32; f.out_words];
            (f.eval)(&v.map(f32::to_bits), &mut out);
            out
        })
        .collect()
}

/// The lean spec of a default one: `oct16` → `oct16:guarantee=ieee`.
fn lean(text: &str) -> String {
    format!("{text}:guarantee=ieee")
}

#[test]
fn lean_codes_are_the_default_tiers_but_near_a_boundary() {
    for text in SPECS {
        let hemisphere = text.starts_with("hemioct") || text.starts_with("xy");
        let vectors = random_unit_vectors(0x1ea4_7134, 1 << 15, hemisphere);
        let portable = codes(&encoder(text), &vectors);
        let ieee = codes(&encoder(&lean(text)), &vectors);
        let differ = portable.iter().zip(&ieee).filter(|(a, b)| a != b).count();
        // A rounded quotient or root sits on the wrong side of a code boundary for a few
        // vectors in a thousand at most; a different codec would differ almost everywhere.
        assert!(
            differ * 200 < vectors.len(),
            "{text}: {differ} of {} codes differ between the tiers",
            vectors.len()
        );
    }
}

#[test]
fn zero_nan_and_infinite_input_encode_as_in_the_default_tier() {
    let (inf, nan) = (f32::INFINITY, f32::NAN);
    let mut hostile = vec![[0.0, 0.0, 0.0], [-0.0, -0.0, -0.0], [nan, nan, nan]];
    for i in 0..3 {
        for x in [inf, -inf, nan, -nan] {
            let mut v = [0.3, -0.4, 0.5];
            v[i] = x;
            hostile.push(v);
            let mut axis = [0.0; 3];
            axis[i] = x;
            hostile.push(axis);
        }
    }
    for text in SPECS {
        let portable = codes(&encoder(text), &hostile);
        let ieee = codes(&encoder(&lean(text)), &hostile);
        for ((v, a), b) in hostile.iter().zip(&portable).zip(&ieee) {
            assert_eq!(
                a,
                b,
                "{text}: input {:08x?} encodes as {a:08x?} in the default tier, {b:08x?} in the lean one",
                v.map(f32::to_bits)
            );
        }
    }
}

#[test]
fn a_texel_layout_and_the_precise_encoder_refuse_the_lean_tier() {
    for (text, why) in [
        (
            "xy16:layout=rg,guarantee=ieee",
            "covers the codec's own packing",
        ),
        (
            "oct24:layout=rgb8,guarantee=ieee",
            "covers the codec's own packing",
        ),
        ("oct16p:guarantee=ieee", "is the fast encoder's"),
        ("lambert16p_ieee", "is the fast encoder's"),
    ] {
        let e = text
            .parse::<Spec>()
            .err()
            .unwrap_or_else(|| panic!("{text} parsed"));
        assert!(e.to_string().contains(why), "{text}: {e}");
    }
}

#[test]
fn the_lean_encoders_doc_comment_says_not_portable() {
    let include = |text: &str| {
        Generator::new()
            .spec(text)
            .lang(Lang::Glsl)
            .render(Lang::Glsl)
            .unwrap_or_else(|e| panic!("{text}: {e:?}"))
    };
    let lean = include("oct16:guarantee=ieee");
    assert!(
        lean.contains("The lean tier (guarantee=ieee), not portable"),
        "{lean}"
    );
    assert!(lean.contains("uint unitpack_oct16_ieee_encode(vec3 v)"));
    let portable = include("oct16");
    assert!(!portable.contains("guarantee=ieee"));
    assert!(portable.contains("Portable (as the header says): the same code on every such"));
}
