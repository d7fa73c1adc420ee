//! Tests of the library's building blocks (exact arithmetic, enclosures, lanes, the
//! printer, the CLI's grammar and figure cache, the verifier's pieces), one module per
//! library module. They live here rather than beside their code so that the library is
//! compiled once for the suite: a unit-test target would compile all of it a second time
//! (`[lib] test = false` in Cargo.toml).

mod choice_filtering;
mod cli_figure_cache;
mod cli_grammar;
mod codecs_exact;
mod codecs_fixed_decode;
mod codecs_fixed_trig;
mod codecs_half;
mod codecs_inputs;
mod codecs_lattice;
mod codecs_sfib;
mod codecs_storage;
mod codecs_trace;
mod codecs_trig;
mod emit_folding;
mod emit_layout;
mod emit_printer;
mod layout;
mod model_enclosure;
mod model_lanes;
mod model_num;
mod par;
mod portability;
mod verify;
mod verify_alu;
mod verify_native;
