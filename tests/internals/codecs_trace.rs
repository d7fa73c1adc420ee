//! A spec is traced once per process, whatever asks for its functions: every language's
//! include, its WESL module, its figures, its proven bounds and the CPU batches share one
//! trace (`Spec::emitted`'s memo).

use unitpack::api::Batch;
use unitpack::codecs::Spec;
use unitpack::emit::{Lang, render_wesl};
use unitpack::generator::Generator;
use unitpack::measure::{measure, measured, quality};

#[test]
fn every_path_to_a_specs_functions_shares_one_trace() {
    // A spec no other test of this binary names.
    let id = "spherical22p";
    let spec: Spec = id.parse().unwrap();
    let g = Generator::new().spec(id);
    for lang in Lang::ALL {
        let text = g.clone().render(lang).unwrap();
        assert!(text.contains("spherical22p"), "{lang}");
    }
    let m = measure(std::slice::from_ref(&spec), Some(4096)).remove(0);
    assert!(m.figures.errors.is_some() && !m.figures.bounds.is_empty());
    assert!(render_wesl(&measured(&spec, None), "x").contains("fn decode"));
    assert!(quality::measure(&spec, 1024).is_some());
    let batch = Batch::new(id).unwrap();
    let mut codes = vec![0u32; batch.words()];
    batch.encode(&[[0.0, 0.0, 1.0]], &mut codes);
    assert_eq!(Spec::traces(id), 1, "{id} traced more than once");
}

/// A rule that fails while a function is traced can say where: the definitions open when
/// it panicked, outermost first, are left for `take_defining` (which `Spec::emitted` puts
/// in its message beside the spec and family), and the next trace starts with none.
#[test]
fn a_rule_failing_inside_a_definition_is_placed() {
    use unitpack::model::trace::{Tf, define, take_defining, trace_module};
    let failed = std::panic::catch_unwind(|| {
        trace_module(|| {
            define("encode", &["v"], |v: Tf| {
                define("round_codes", &["p"], |_: Tf| -> Tf {
                    panic!("a planted rule")
                });
                v
            })
        })
    });
    assert!(failed.is_err());
    assert_eq!(take_defining(), ["encode", "round_codes"]);
    assert!(take_defining().is_empty(), "taken once");
    let module = trace_module(|| define("f", &["x"], |x: Tf| x));
    assert_eq!(module.funcs.len(), 1);
    assert!(
        take_defining().is_empty(),
        "a finished trace leaves none open"
    );
}
