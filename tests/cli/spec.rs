//! Spec errors, as every verb that takes a SPEC reports them (shown through `gen`).

use crate::common::*;
use std::collections::BTreeSet;
use unitpack::codecs::FAMILIES;
use unitpack::codecs::core::info::Sizes;

#[test]
fn unknown_codec_suggests_the_nearest_and_lists_all() {
    let err = bad_spec("octt16");
    assert!(err.contains("unknown codec 'octt16'"), "{err}");
    let after = err
        .split("did you mean ")
        .nth(1)
        .unwrap_or_else(|| panic!("no suggestion: {err}"));
    let first: String = after
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect();
    assert_eq!(
        first, "oct16",
        "nearest match first, at the size typed: {err}"
    );
    let valid = err
        .split("Valid codecs: ")
        .nth(1)
        .unwrap_or_else(|| panic!("no list of codecs: {err}"));
    let valid: BTreeSet<&str> = valid.trim().split(", ").collect();
    // Families spelled by component size (snorm8x3, float16x3) list those spellings; their
    // family names are not specs.
    for c in FAMILIES.iter().map(|f| f.info()) {
        if let Sizes::PerComponent { .. } = c.sizes {
            assert!(
                !valid.contains(c.name),
                "{} alone does not parse: {err}",
                c.name
            );
            for (id, _) in c.spellings() {
                assert!(valid.contains(id.as_str()), "valid codecs lack {id}: {err}");
            }
        } else {
            assert!(
                valid.contains(c.name),
                "valid codecs lack {}: {err}",
                c.name
            );
        }
    }
    for id in ["snorm8x3", "snorm10x3", "snorm16x3", "float16x3"] {
        assert!(valid.contains(id), "valid codecs lack {id}: {err}");
    }

    let err = bad_spec("hemiokt16");
    let first = err.split("did you mean ").nth(1).unwrap();
    assert!(first.starts_with("hemioct16?"), "{err}");
    // The size typed picks the spelling, and a precise `p` stays where there is one.
    let suggested = |typed: &str| {
        let err = bad_spec(typed);
        let after = err
            .split("did you mean ")
            .nth(1)
            .unwrap_or_else(|| panic!("{err}"));
        after.split('?').next().unwrap().to_string()
    };
    assert_eq!(suggested("meshopt16"), "meshopt_oct16");
    assert_eq!(suggested("octt16p"), "oct16p");
    assert_eq!(suggested("meshopt_okt16p"), "meshopt_oct16");
    // Without a size, the families' names.
    assert_eq!(suggested("octt"), "oct");
    let err = bad_spec("");
    assert!(err.contains("unknown codec ''"), "{err}");
}

#[test]
fn invalid_bits_name_the_allowed_sizes() {
    let err = bad_spec("oct17");
    assert!(err.contains("oct has no 17-bit form"), "{err}");
    assert!(err.contains("allowed sizes: 16, 20, 22, 24, 32"), "{err}");
    let err = bad_spec("hemioct20p");
    assert!(err.contains("allowed sizes: 16, 24, 32"), "{err}");
    // Bits are required.
    let err = bad_spec("oct");
    assert!(err.contains("allowed sizes: 16, 20, 22, 24, 32"), "{err}");
    let err = bad_spec("lambert16pp");
    assert!(err.contains("after lambert16 comes nothing"), "{err}");
}

#[test]
fn snorm3_is_spelled_by_component_size() {
    let err = bad_spec("snorm9x3");
    for id in ["snorm8x3", "snorm10x3", "snorm16x3"] {
        assert!(err.contains(id), "{err}");
    }
    for id in ["snorm8x3", "snorm10x3", "snorm16x3"] {
        let r = ok(&["gen", id, "--lang", "wgsl"]);
        assert!(
            r.stdout.contains(&format!("fn unitpack_{id}_encode(")),
            "{r:?}"
        );
    }
    // The family name is not a spec; the precise form (Best Fit Normals) is.
    let err = bad_spec("snorm3");
    assert!(err.contains("snorm8x3"), "{err}");
    let r = ok(&["gen", "snorm8x3p", "--lang", "wgsl"]);
    assert!(r.stdout.contains("fn unitpack_snorm8x3p_encode("), "{r:?}");
    bad_spec("snorm8x3pp");
    bad_spec("snorm0x3");
}

#[test]
fn snorm12x2_takes_no_bits_or_precise_suffix() {
    let r = ok(&["gen", "snorm12x2", "--lang", "wgsl"]);
    assert!(
        r.stdout.contains("fn unitpack_snorm12x2_to_unorm8x3("),
        "{r:?}"
    );
    assert!(
        r.stdout.contains("fn unitpack_unorm8x3_to_snorm12x2("),
        "{r:?}"
    );
    bad_spec("snorm12x2p");
    bad_spec("snorm12x3");
    let err = bad_spec("snorm12x2:foo=1");
    assert!(err.contains("'foo'"), "{err}");
}

#[test]
fn layout_rgb8_is_oct24_only() {
    for spec in ["oct16:layout=rgb8", "oct32p:layout=rgb8"] {
        let err = bad_spec(spec);
        assert!(
            err.contains("rgb8") && err.contains("oct24"),
            "{spec}: {err}"
        );
    }
    let err = bad_spec("oct24:layout=rgb9");
    assert!(
        err.contains("'rgb9'") && err.contains("expected snorm or rgb8"),
        "{err}"
    );
    // hemioct's layout option is the texel one, without rgb8; lambert has none.
    let err = bad_spec("hemioct24:layout=rgb8");
    assert!(err.contains("expected snorm or rg or dxt5nm"), "{err}");
    let err = bad_spec("lambert24:layout=rgb8");
    assert!(err.contains("no option 'layout'"), "{err}");
}

#[test]
fn stereo_scale_must_be_a_positive_finite_number() {
    // Also bounded, so that the literals derived from it (2s, -s, 0.5/s) stay finite.
    for v in ["-1", "0", "-0", "inf", "nan", "3e38", "1e-39"] {
        let err = bad_spec(&format!("stereo_scaled16:scale={v}"));
        assert!(
            err.contains(&format!("'{v}'")) && err.contains("[0.001, 1000]"),
            "scale={v}: {err}"
        );
    }
    for v in ["abc", ""] {
        let err = bad_spec(&format!("stereo_scaled16:scale={v}"));
        assert!(err.contains("expected a number"), "scale={v}: {err}");
    }
    ok(&["gen", "stereo_scaled24p:scale=1.5", "--lang", "hlsl"]);
}

#[test]
fn unknown_options_are_named() {
    let err = bad_spec("stereo_scaled16:foo=1");
    assert!(err.contains("no option 'foo'"), "{err}");
    assert!(
        err.contains("scale="),
        "the valid options should be listed: {err}"
    );
    let err = bad_spec("oct16:scale=2");
    assert!(
        err.contains("no option 'scale'") && err.contains("layout="),
        "{err}"
    );
}
