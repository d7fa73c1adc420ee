//! The spec grammar: every spec reads back from both of its written forms, names ending in
//! a digit have a spelling, and malformed specs name the real problem.

use unitpack::codecs::core::info::{OptKind, Sizes};
use unitpack::codecs::{FAMILIES, Spec, SpecError};

/// Every family × size × encoder × option value (numbers at their ends, default and a
/// seeded spread in between).
fn every_configuration() -> Vec<String> {
    let mut out = Vec::new();
    let mut x: u32 = 0x9e37_79b9;
    for f in FAMILIES {
        let info = f.info();
        for (spelled, _) in info.spellings() {
            for p in ["", "p"] {
                if p == "p" && !f.precise() {
                    continue;
                }
                out.push(format!("{spelled}{p}"));
                for o in info.options {
                    let values: Vec<String> = match o.kind {
                        OptKind::Choice(names) => names.iter().map(|n| n.to_string()).collect(),
                        OptKind::Number { default, min, max } => {
                            let mut v = vec![min, max, default, 1.0, 2.5];
                            for _ in 0..40 {
                                x ^= x << 13;
                                x ^= x >> 17;
                                x ^= x << 5;
                                v.push(min + (max - min) * (x as f32 / u32::MAX as f32));
                            }
                            v.iter().map(|n| n.to_string()).collect()
                        }
                    };
                    for v in values {
                        out.push(format!("{spelled}{p}:{}={v}", o.key));
                    }
                }
            }
        }
    }
    out
}

#[test]
fn display_and_id_read_back_as_the_same_spec() {
    let mut parsed = 0;
    for text in every_configuration() {
        let spec = match text.parse::<Spec>() {
            Ok(s) => s,
            // Option combinations a family refuses (rgb8 outside oct24) are errors, not panics.
            Err(SpecError::BadValue { .. }) => continue,
            Err(e) => panic!("{text}: {e}"),
        };
        parsed += 1;
        let display = spec.to_string();
        assert_eq!(
            display.parse::<Spec>().as_ref(),
            Ok(&spec),
            "{text} → {display}"
        );
        let id = spec.id();
        assert_eq!(id.parse::<Spec>().as_ref(), Ok(&spec), "{text} → id {id}");
        assert!(
            id.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'),
            "id {id} is not an identifier"
        );
        assert_eq!(display.to_uppercase().parse::<Spec>().as_ref(), Ok(&spec));
    }
    assert!(parsed > 100, "only {parsed} configurations parsed");
    for spec in Spec::all() {
        assert_eq!(spec.id().parse::<Spec>(), Ok(spec.clone()));
        assert_eq!(spec.to_string().parse::<Spec>(), Ok(spec));
    }
}

#[test]
fn ids_are_unique_across_the_catalogue() {
    let mut ids: Vec<String> = Spec::all().iter().map(Spec::id).collect();
    let n = ids.len();
    ids.sort();
    ids.dedup();
    assert_eq!(ids.len(), n);
    assert!(ids.contains(&"oct24p_rgb8".to_string()));
}

#[test]
fn every_size_spelling_is_unambiguous() {
    // No spelling of one family is a spelling of another.
    let mut all = Vec::new();
    for f in FAMILIES {
        for (s, _) in f.info().spellings() {
            assert!(!all.contains(&s), "{s} spelled twice");
            let spec: Spec = s.parse().unwrap();
            assert_eq!(spec.info().name, f.info().name);
            all.push(s);
        }
    }
}

#[test]
fn names_ending_in_a_digit_take_an_underscore_before_their_size() {
    use unitpack::codecs::core::info::{FloatForm, Info};
    let info = Info {
        name: "cry3",
        title: "",
        sizes: Sizes::Total(&[16, 24]),
        domain: None,
        source: "",
        edge_policy: "",
        decode_note: "",
        float_form: FloatForm::Absent,
        options: &[],
    };
    let s: Vec<String> = info.spellings().into_iter().map(|s| s.0).collect();
    assert_eq!(s, ["cry3_16", "cry3_24"]);
}

fn err(s: &str) -> String {
    s.parse::<Spec>().unwrap_err().to_string()
}

#[test]
fn malformed_specs_name_the_problem() {
    assert!(err("oct24:").contains("empty option"), "{}", err("oct24:"));
    assert!(err("oct24:layout=rgb8,").contains("empty option"));
    assert!(err("oct24:,layout=rgb8").contains("empty option"));
    let e = err("oct24:layout=rgb8,layout=snorm");
    assert!(e.contains("layout is given twice"), "{e}");
    let e = err("oct24_rgb8:layout=rgb8");
    assert!(e.contains("layout is given twice"), "{e}");
    let e = err("stereo_scaled16_scale2:scale=3");
    assert!(e.contains("scale is given twice"), "{e}");
    let e = err("snorm11_11_10p");
    assert!(e.contains("snorm11_11_10 has no precise encoder"), "{e}");
    let e = err("snorm12x2p");
    assert!(e.contains("snorm12x2 has no precise encoder"), "{e}");
    let e = err("oct24_rgb9");
    assert!(e.contains("'rgb9'") && e.contains("layout="), "{e}");
    let e = err("oct16_rgb8");
    assert!(e.contains("oct24 only"), "{e}");
    let e = err("stereo_scaled16_scale0");
    assert!(e.contains("'scale0'"), "{e}");
    let e = err("stereo_scaled16:scale=0");
    assert!(e.contains("[0.001, 1000]"), "{e}");
    let e = err("oct16pp");
    assert!(e.contains("after oct16 comes nothing"), "{e}");
    let e = err("snorm9x3");
    assert!(e.contains("snorm8x3, snorm10x3, snorm16x3"), "{e}");
}

/// A family offers the precise encoder exactly where its codec decides the search in
/// exact arithmetic (`Family::precise` is derived from `Codec::EXACT_SEARCH`), so every
/// precise spec's packed encoder is portable, and asking a family without one for `p`
/// is refused.
#[test]
fn the_precise_encoder_is_offered_where_its_search_is_exact() {
    for f in FAMILIES {
        let (spelled, _) = f.info().spellings()[0].clone();
        let p = format!("{spelled}p").parse::<Spec>();
        if f.precise() {
            let spec = p.unwrap_or_else(|e| panic!("{spelled}p: {e}"));
            assert!(
                spec.emitted().portable_encoder,
                "{spec}: a precise encoder whose search is not exact"
            );
        } else {
            assert!(
                p.is_err(),
                "{spelled}p parses, though {spelled} has no precise encoder"
            );
        }
    }
}

/// A family reads its options by key and its choices by name: a name the option does not
/// list is a mistake in the family's code, and says which family, option and name.
#[test]
fn reading_a_choice_the_option_does_not_list_names_family_option_and_name() {
    let spec: Spec = "oct24:layout=rgb8".parse().unwrap();
    let layout = spec
        .info()
        .options
        .iter()
        .find(|o| o.key == "layout")
        .unwrap();
    assert!(spec.chose(layout, "rgb8") && !spec.chose(layout, "snorm"));
    let wrong =
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| spec.chose(layout, "rgb9")))
            .unwrap_err();
    let text = wrong.downcast_ref::<String>().unwrap();
    assert_eq!(text, "oct: option layout has no choice rgb9");
    let scaled: Spec = "stereo_scaled16:scale=2.5".parse().unwrap();
    let scale = scaled
        .info()
        .options
        .iter()
        .find(|o| o.key == "scale")
        .unwrap();
    assert_eq!(scaled.number_of(scale), 2.5);
    assert_eq!(spec.option(scale), None, "oct has no scale option");
}
