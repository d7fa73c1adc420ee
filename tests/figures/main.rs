//! The figures the repository states, checked in one binary: the generated tables in
//! `docs/` and the ALU budgets (`tables`), the survey's Table 1 rows (`accuracy`) and the
//! proven decoder bounds (`decode_bound`). Together because they read the same figures:
//! each spec's error statistics are measured once here ([`stats`]) and each decoder's
//! bound proven once (the library's per-process cache).

mod accuracy;
mod cover;
mod decode_bound;
mod tables;

use std::sync::OnceLock;
use unitpack::codecs::Spec;
use unitpack::measure::figures::ErrorStats;
use unitpack::measure::quality::measure_all_once;
use unitpack::report::doc_tables::{README_SAMPLES, codec_specs};

/// The error statistics of `specs` over `samples` seeded vectors, as
/// [`unitpack::measure::quality::measure`] gives them. The first caller measures every codec spec
/// at the documented tables' sample size on all cores while the others wait, so that no test
/// measures a spec another one is measuring.
fn stats(specs: &[Spec], samples: usize) -> Vec<Option<ErrorStats>> {
    static CATALOGUE: OnceLock<()> = OnceLock::new();
    CATALOGUE.get_or_init(|| {
        measure_all_once(&codec_specs(), README_SAMPLES);
    });
    measure_all_once(specs, samples)
}
