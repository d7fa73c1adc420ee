use unitpack::emit::lang::literal::f32_literal;
use unitpack::emit::lang::printer::*;

/// A value named after a reserved word is printed under another name.
#[test]
fn reserved_words_are_never_declared() {
    use unitpack::emit::lang::wgsl::Wgsl;
    use unitpack::model::trace::{Tf, define, trace_module};
    use unitpack::model::{Float, Lane};
    let module = trace_module(|| {
        define("f", &["x"], |x: Tf| {
            ((x + Tf::c(1.0)).named("target") * x).named("filter")
        })
    });
    let p = print(&Wgsl, &module.funcs[0], &|n: &str| n.to_string());
    let body = p.body.join("\n");
    assert!(
        body.contains("let target2 = ") && body.contains("let filter2 = "),
        "{body}"
    );
    assert!(
        !body.contains("let target =") && !body.contains("let filter ="),
        "{body}"
    );
}

/// Every literal reads back as the same f32, directly and through f64, in every language.
#[test]
fn literals_round_trip_exactly() {
    let mut x: u32 = 0x1234_5678;
    for i in 0..200_000u32 {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        let v = f32::from_bits(if i < 1000 { i } else { x });
        if !v.is_finite() {
            continue;
        }
        {
            let s = f32_literal(v);
            let t = s.as_str();
            assert!(t.contains(['.', 'e']), "{s} is not a float literal");
            assert_eq!(t.parse::<f32>().unwrap().to_bits(), v.to_bits(), "{s}");
            assert_eq!(
                (t.parse::<f64>().unwrap() as f32).to_bits(),
                v.to_bits(),
                "{s} via f64"
            );
        }
    }
}
