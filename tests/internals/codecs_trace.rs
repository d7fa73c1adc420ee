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
