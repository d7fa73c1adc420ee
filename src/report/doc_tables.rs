//! The documentation's generated tables: the catalogue (every family with the specs a user
//! types, its options and source), the error figures of every spec, the proven decoder
//! bounds and the cost of portability. Each lives between two marker lines in one file
//! under `docs/` ([`BLOCKS`]); the test that computes it (`tests/figures/tables.rs`,
//! `tests/block_compression.rs`) checks that the file holds exactly this text and rewrites
//! it when [`REFRESH_ENV`] is set.

use crate::codecs::{FAMILIES, Spec};
use crate::measure::figures::{ErrorStats, VECTOR_SEED};

/// Samples behind the documented error figures (the survey's Table 1 used 2^20 too).
pub const README_SAMPLES: usize = 1 << 20;

/// The environment variable that makes the tests rewrite every file a tool writes (the
/// generated tables, `tests/alu_budgets.txt`) instead of failing when it is stale:
/// `UNITPACK_REFRESH=1 cargo test --release`.
pub const REFRESH_ENV: &str = "UNITPACK_REFRESH";

/// The command that rewrites every tool-written file, for error messages.
pub const REFRESH_COMMAND: &str = "UNITPACK_REFRESH=1 cargo test --release";

/// Whether this run rewrites tool-written files ([`REFRESH_ENV`] set, and not to `0`).
pub fn refreshing() -> bool {
    std::env::var_os(REFRESH_ENV).is_some_and(|v| !v.is_empty() && v != "0")
}

/// A generated block: its name, the file that holds it (relative to the repository
/// root) and the test that writes it (`tests/{test}.rs`).
#[derive(Clone, Copy, Debug)]
pub struct Block {
    pub name: &'static str,
    pub file: &'static str,
    pub test: &'static str,
}

/// Every generated block of the documentation, each in exactly one file.
pub const BLOCKS: &[Block] = &[
    Block {
        name: "catalogue",
        file: "docs/codecs.md",
        test: "figures/tables",
    },
    Block {
        name: "errors",
        file: "docs/codecs.md",
        test: "figures/tables",
    },
    Block {
        name: "frame_errors",
        file: "docs/codecs.md",
        test: "figures/tables",
    },
    Block {
        name: "seed_methods",
        file: "docs/design/families.md",
        test: "figures/tables",
    },
    Block {
        name: "bounds",
        file: "docs/design/decoder-bounds.md",
        test: "figures/tables",
    },
    Block {
        name: "portability_cost",
        file: "docs/design/portability.md",
        test: "figures/tables",
    },
    Block {
        name: "tiers",
        file: "docs/design/portability.md",
        test: "figures/tables",
    },
    Block {
        name: "recommendations",
        file: "README.md",
        test: "readme",
    },
    Block {
        name: "block_compression",
        file: "docs/design/block-compression.md",
        test: "block_compression",
    },
];

/// The block called `name`.
pub fn block(name: &str) -> &'static Block {
    BLOCKS
        .iter()
        .find(|b| b.name == name)
        .unwrap_or_else(|| panic!("no generated block called {name}"))
}

/// Markers around a generated block, naming the test file (`tests/{test}.rs`) that
/// checks and rewrites it; the test binary is the file's first path component
/// (`figures/tables` is in the `figures` binary).
pub fn markers(test: &str, name: &str) -> (String, String) {
    let binary = test.split('/').next().unwrap_or(test);
    (
        format!(
            "<!-- generated: {name} (tests/{test}.rs; {REFRESH_ENV}=1 cargo test --release --test {binary}) -->"
        ),
        format!("<!-- end generated: {name} -->"),
    )
}

/// One row per family: specs, domain, precise encoder, options, source.
pub fn catalogue_table() -> String {
    let mut s = String::from(
        "| codec | specs | domain | precise (`p`) | options | source |\n|---|---|---|---|---|---|\n",
    );
    for f in FAMILIES {
        let c = f.info();
        let specs: Vec<String> = c
            .spellings()
            .into_iter()
            .map(|(s, _)| format!("`{s}`"))
            .collect();
        // A `|` inside a cell would end it.
        let options: Vec<String> = c
            .options
            .iter()
            .map(|o| o.usage().replace('|', "\\|"))
            .collect();
        s.push_str(&format!(
            "| {} ({}) | {} | {} | {} | {} | {} |\n",
            c.name,
            c.title,
            specs.join(" "),
            f.takes().unwrap_or("— (helpers)"),
            if f.precise() { "yes" } else { "no" },
            if options.is_empty() {
                "—".to_string()
            } else {
                options.join("; ")
            },
            c.source
        ));
    }
    s
}

/// The tangent-frame specs' round-trip errors, each beside the octahedral normal, tangent
/// and sign at no more bits ([`crate::measure::quality::oct_frame_baseline`]).
pub fn frame_error_table() -> String {
    let specs: Vec<Spec> = Spec::all()
        .into_iter()
        .filter(|s| s.family().frames())
        .collect();
    let pair = |[mean, max]: [f64; 2]| format!("{mean:.5} / {max:.5}");
    let mut s = String::new();
    for (i, spec) in specs.iter().enumerate() {
        let f = crate::measure::quality::measure_frames(spec).expect("a frame spec");
        if i == 0 {
            s.push_str(&format!(
                "Over {} seeded orthonormal frames (seed 0x{:032x}), in degrees, mean / sample max (a sample maximum is not a bound); the reference tangent is the input's made orthogonal to the normal, the bitangent `cross(n, t)·sign`.\n\n| spec | bits | normal | tangent | bitangent | handedness flips |\n|---|---|---|---|---|---|\n",
                f.samples,
                crate::codecs::functions::inputs::FRAME_SEED
            ));
        }
        let ((n, t, bits), base) = crate::measure::quality::oct_frame_baseline(spec.bits());
        s.push_str(&format!(
            "| `{}` | {} | {} | {} | {} | {} |\n| {n} + {t} + sign | {bits} | {} | {} | {} | {} |\n",
            spec.id(),
            spec.bits(),
            pair(f.normal),
            pair(f.tangent),
            pair(f.bitangent),
            f.flips,
            pair(base.normal),
            pair(base.tangent),
            pair(base.bitangent),
            base.flips
        ));
    }
    s
}

/// Every spec the error table has a row for: the codecs (not the helpers).
pub fn codec_specs() -> Vec<Spec> {
    Spec::all()
        .into_iter()
        .filter(|s| s.info().domain.is_some())
        .collect()
}

/// Round-trip error of every [`codec_specs`] spec (`stats[i]` for spec `i`, from
/// [`crate::measure::quality::measure_all`]), with the ALU instructions of its packed encoder and
/// decoder (`alu[i]`, counted by `unitpack::verify::alu`, which needs the shader tools).
pub fn error_table(stats: &[Option<ErrorStats>], alu: &[[u32; 2]]) -> String {
    let specs = codec_specs();
    assert_eq!(specs.len(), alu.len(), "one ALU count pair per spec");
    assert_eq!(specs.len(), stats.len(), "one measurement per spec");
    let samples = stats
        .iter()
        .flatten()
        .next()
        .expect("codecs have error statistics")
        .samples;
    let mut s = format!(
        "Round-trip angular error over {samples} seeded unit vectors (seed `{VECTOR_SEED:#x}`; \
         hemisphere codecs over the +Z hemisphere). The maximum is the largest error in \
         that sample, not a bound. MSE and PSNR are the first seed's metric: the mean \
         squared error of the components of `n − n'` (its difference image's three \
         channels), and `10·log10(1/MSE)`. ALU: instructions of the packed `encode` and `decode` \
         (GLSL through `glslangValidator -V` and `spirv-opt -O`, counted as in \
         [What portability costs](design/portability.md#what-portability-costs); \
         `src/verify/alu.rs`).\n\n\
         | spec | bits | domain | mean | sample max | MSE | PSNR | encode ALU | decode ALU |\n\
         |---|---|---|---|---|---|---|---|---|\n"
    );
    for ((spec, st), [enc, dec]) in specs.iter().zip(stats).zip(alu) {
        let st = st.as_ref().expect("codecs have error statistics");
        s.push_str(&format!(
            "| `{}` | {} | {} | {:.5}° | {:.5}° | {:.3e} | {:.2} dB | {enc} | {dec} |\n",
            spec.id(),
            spec.bits(),
            spec.info().domain.map_or("", |d| d.name()),
            st.mean,
            st.max,
            st.mse,
            st.psnr()
        ));
    }
    s
}

/// The first seed's methods 6, 4 and 5 side by side: one mapping with Lambert's codes,
/// and five decoders (Lambert's, the seed's plain and optimized spheremap and CryEngine 3
/// ones), each with its error, ALU count and proven bound, from the same figures as
/// [`error_table`] (`stats` and `alu` indexed like [`codec_specs`]).
pub fn seed_methods_table(stats: &[Option<ErrorStats>], alu: &[[u32; 2]]) -> String {
    let specs = codec_specs();
    let mut s = String::from(
        "| bits | decoder | spec | mean | sample max | PSNR | decode ALU | proven `decode` bound (2^-24) |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    for bits in [16, 24, 32] {
        for (decoder, id) in [
            ("Lambert (method 6)", format!("lambert{bits}")),
            ("spheremap (method 4)", format!("spheremap{bits}")),
            ("spheremap, optimized", format!("spheremap{bits}_optimized")),
            ("CryEngine 3 (method 5)", format!("cry3_{bits}")),
            ("CryEngine 3, optimized", format!("cry3_{bits}_optimized")),
        ] {
            let i = specs
                .iter()
                .position(|s| s.id() == id)
                .unwrap_or_else(|| panic!("{id} is in the catalogue"));
            let st = stats[i].as_ref().expect("codecs have error statistics");
            let bound = decoder_bound(&specs[i], "decode")
                .map_or("—".to_string(), |b| b.units.to_string());
            s.push_str(&format!(
                "| {bits} | {decoder} | `{id}` | {:.5}° | {:.5}° | {:.2} dB | {} | {bound} |\n",
                st.mean,
                st.max,
                st.psnr(),
                alu[i][1]
            ));
        }
    }
    s
}

/// The proven bound of `spec`'s decoder function `name` ([`crate::measure::decode_bound`]).
fn decoder_bound(spec: &Spec, name: &str) -> Option<crate::measure::figures::Bound> {
    let e = spec.emitted();
    let f = e.functions.iter().find(|f| f.name == name)?;
    crate::measure::decode_bound::cached(&e.module, f)
}

/// The proven bound of every decoder ([`crate::measure::decode_bound`]).
pub fn bound_table() -> String {
    let mut s = String::from(
        "How far each decoder's output can move on a conformant implementation that takes \
         every latitude the guaranteed classes allow at once (`div`, `sqrt`, `fma`, \
         `denorm`, `zero`): the largest `|deviant − reference|` of an output component over \
         every code, in units of 2^-24, proven by interval evaluation. Where the search \
         spent its budget before one code reached the bound, the cell says what a code \
         reaches: the true bound lies between.\n\n\
         | spec | `decode` | `decode_float` |\n|---|---|---|\n",
    );
    let specs: Vec<Spec> = Spec::all()
        .into_iter()
        .filter(|s| s.info().domain.is_some())
        .collect();
    // On every core first; the cells below read the proven bounds.
    crate::measure::decode_bound::prove_all(&specs);
    for spec in specs {
        let cell = |name: &str| {
            decoder_bound(&spec, name).map_or("—".to_string(), |b| {
                let tight = if b.tight() {
                    String::new()
                } else {
                    format!(", not tight: a code reaches {}", b.reached)
                };
                format!(
                    "{} ({:.1e}{tight})",
                    b.units,
                    b.units * crate::measure::figures::UNIT
                )
            })
        };
        s.push_str(&format!(
            "| `{}` | {} | {} |\n",
            spec.id(),
            cell("decode"),
            cell("decode_float")
        ));
    }
    s
}

/// ALU counts of the non-portable forms of some functions (the model at commit
/// `c5990d3`, before codes were decided exactly): spec, then `encode`, `encode_float`,
/// `decode`, `decode_float`. A record, not a measurement this crate can repeat.
pub const NON_PORTABLE_ALU: &[(&str, [u32; 4])] = &[
    ("oct16", [37, 21, 24, 15]),
    ("oct16p", [160, 153, 24, 15]),
    ("oct24:layout=rgb8", [51, 38, 28, 26]),
    ("oct24p:layout=rgb8", [167, 161, 28, 26]),
    ("hemioct16", [61, 45, 20, 11]),
    ("hemioct16p", [188, 181, 20, 11]),
    ("snorm8x3", [40, 18, 18, 8]),
    ("spherical16", [127, 111, 75, 66]),
    ("spherical16p", [454, 447, 75, 66]),
    ("lambert16", [35, 25, 16, 12]),
    ("lambert16p", [138, 135, 16, 12]),
    ("stereo_scaled16", [36, 26, 13, 9]),
    ("stereo_scaled16p", [127, 124, 13, 9]),
    ("xy16", [54, 38, 15, 6]),
    ("xy16p", [161, 154, 15, 6]),
];

/// [`NON_PORTABLE_ALU`] beside today's counts, `count(spec, function)`: one cell per
/// function, `before → now` where they differ.
pub fn portability_cost_table(count: impl Fn(&Spec, &str) -> u32) -> String {
    let mut s = String::from(
        "| spec | `encode` | `encode_float` | `decode` | `decode_float` |\n|---|---|---|---|---|\n",
    );
    for (text, before) in NON_PORTABLE_ALU {
        let spec: Spec = text
            .parse()
            .unwrap_or_else(|e| panic!("{text} is a spec: {e}"));
        s.push_str(&format!("| `{text}` |"));
        for (f, b) in ["encode", "encode_float", "decode", "decode_float"]
            .iter()
            .zip(before)
        {
            let now = count(&spec, f);
            if now == *b {
                s.push_str(&format!(" {now} |"));
            } else {
                s.push_str(&format!(" {b} → {now} |"));
            }
        }
        s.push('\n');
    }
    s
}

/// The specs whose families have a lean tier, as the tier table lists them.
pub const TIER_SPECS: [&str; 5] = ["oct16", "hemioct16", "lambert16", "stereo_scaled16", "xy16"];

/// The ALU price of the guarantee: each of [`TIER_SPECS`]' encoders in the default tier
/// (`guarantee=portable`) and the lean one (`guarantee=ieee`), `count(spec, function)`.
pub fn tier_table(count: impl Fn(&Spec, &str) -> u32) -> String {
    let mut s = String::from(
        "| spec | `encode` portable | `encode` ieee | `encode_float` portable | `encode_float` ieee |\n|---|---|---|---|---|\n",
    );
    for text in TIER_SPECS {
        let parse =
            |t: &str| -> Spec { t.parse().unwrap_or_else(|e| panic!("{t} is a spec: {e}")) };
        let (portable, ieee) = (parse(text), parse(&format!("{text}:guarantee=ieee")));
        s.push_str(&format!("| `{text}` |"));
        for f in ["encode", "encode_float"] {
            s.push_str(&format!(" {} | {} |", count(&portable, f), count(&ieee, f)));
        }
        s.push('\n');
    }
    s
}

/// `text` with the block called `name`, written by `tests/{test}.rs`, replaced by `body`;
/// `None` without its markers.
pub fn replace_block(text: &str, test: &str, name: &str, body: &str) -> Option<String> {
    let (begin, end) = markers(test, name);
    let start = text.find(&begin)? + begin.len();
    let stop = start + text[start..].find(&end)?;
    Some(format!("{}\n{}{}", &text[..start], body, &text[stop..]))
}
