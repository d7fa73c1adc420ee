//! Figures about specs, computed from their traced functions and never printed here:
//! round-trip error statistics ([`quality`], the survey's method), proven decoder bounds
//! ([`decode_bound`], branch and bound over interval evaluation) and the deviation report
//! of `verify --portable` ([`portability`]). [`measure`] gathers a spec's figures into one
//! record ([`figures::Measured`]) that emission and the reports print; nothing here names
//! `emit`.

pub mod decode_bound;
pub mod figures;
pub mod portability;
pub mod quality;

use crate::codecs::Spec;
use crate::codecs::functions::function::Role;
use figures::{ErrorStats, FrameFigures, Measured};

/// `spec`'s traced functions and every figure its docs quote: the frame figures of a
/// tangent-frame spec, the proven bounds of its decoders, and `errors` (measured by the
/// caller, who chooses the sample: [`measure`] takes one for a batch).
pub fn measured(spec: &Spec, errors: Option<ErrorStats>) -> Measured {
    let emitted = spec.emitted();
    let frames = quality::measure_frames(spec).map(|stats| FrameFigures {
        stats,
        baseline: quality::oct_frame_baseline(spec.bits()),
    });
    // The bounds the docs state: the packed decoder's and the float form's (the first
    // function of each role; a frame's TBN decoder and a texel's other decoders are
    // documented through them).
    let bounds = [Role::Decode, Role::DecodeFloat]
        .into_iter()
        .filter_map(|role| emitted.functions.iter().find(|f| f.role == role))
        .filter_map(|f| Some((f.name, decode_bound::cached(&emitted.module, f)?)))
        .collect();
    Measured {
        spec: spec.clone(),
        emitted,
        figures: figures::Figures {
            errors,
            frames,
            bounds,
        },
    }
}

/// [`measured`] for every spec of a batch: the decoders proven and, where `samples` is
/// given, the error statistics measured (each once per process), on every core.
pub fn measure(specs: &[Spec], samples: Option<usize>) -> Vec<Measured> {
    let errors = match samples {
        Some(n) => quality::measure_all_once(specs, n),
        None => vec![None; specs.len()],
    };
    decode_bound::prove_all(specs);
    let pairs: Vec<_> = specs.iter().zip(errors).collect();
    crate::support::par::map(&pairs, |(spec, errors)| measured(spec, *errors))
}
