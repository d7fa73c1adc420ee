//! Verification: every emitted function, on every path to the driver, run on
//! lavapipe over storage-buffer inputs and compared as raw bits with the `f32` model.
//! Static checks ride along: naga validates WGSL and GLSL and writes the WGSL as GLSL 4.30
//! and ES 3.10 for glslang, glslang compiles GLSL (also as `#version 330` and `#version 300
//! es`) and HLSL (`-Od` and default), spirv-val checks
//! every SPIR-V module. Each spec compiles one program per path for all its functions (a
//! selecting kernel, [`gpu`]'s module docs; a C driver taking the function's index) and
//! runs it once per function.

pub mod gl;
pub mod gpu;
/// Lives with the codecs so that the portability report, which needs no GPU, can use it.
pub use crate::codecs::functions::inputs;
pub mod alu;
pub mod browser;
pub mod literals;
pub mod native;
pub mod slang;
pub mod tools;
pub mod web;

use crate::codecs::Spec;
use crate::codecs::functions::function::Emitted;
use crate::codecs::functions::function::first_with_same_code;
use crate::codecs::functions::function::{Eval, Function, Inputs, Width};
use crate::emit::lang::glsl::precise_macro;
use crate::emit::lang::{KernelFn, Returns};
use crate::emit::{DEFAULT_PREFIX, Lang, render};
use crate::model::Kind;
use crate::model::avx2_lanes;
use crate::model::trace::{Func, Ty};
use anyhow::Result;
use gpu::{Adapter, Gpu, Shader};
use std::collections::HashMap;
use std::fmt;
use std::sync::Arc;
use tools::{GlslangInput, HlslOpt};

/// One way emitted code reaches the driver.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Path {
    WgslNaga,
    GlslNaga,
    GlslGlslang,
    HlslGlslangOd,
    HlslGlslangDefault,
    /// The HLSL include through Slang's direct SPIR-V backend ([`slang`]), `-O0`.
    HlslSlangO0,
    /// The same at Slang's default optimization.
    HlslSlang,
    /// The same at `-O3`.
    HlslSlangO3,
    /// Through Slang's `-emit-spirv-via-glsl`, the route that keeps `precise`.
    HlslSlangViaGlsl,
    /// The GLSL include through the OpenGL driver's own GLSL compiler (EGL; Mesa's
    /// llvmpipe on the CPU adapter), without `precise`: what a user who leaves
    /// `UNITPACK_PRECISE` undefined gets ([`gl`]).
    GlslGl,
    /// The same with `#define UNITPACK_PRECISE precise`.
    GlslGlPrecise,
    /// The C header through the system C compiler (C99).
    CC,
    /// The same header compiled as C++.
    CCpp,
    /// No emitted code: the model itself on four SSE2 lanes ([`Function::eval_lanes`]),
    /// what the CPU batches run without AVX2. Verified whatever the languages asked for.
    Lanes,
    /// The model on eight AVX2 lanes ([`Function::eval_lanes8`]), what the CPU batches run
    /// where the processor has AVX2. Verified whatever the languages asked for; an error
    /// on a processor without AVX2.
    Lanes8,
    /// The WGSL include through WebGPU in headless Chromium: Tint compiles it, Dawn runs
    /// it on the browser's adapter (SwiftShader without a GPU) ([`browser`]).
    WgslTint,
    /// The GLSL include as GLSL ES 3.00 through WebGL 2 in headless Chromium: ANGLE
    /// translates it for the browser's GL backend (SwiftShader's Vulkan without a GPU).
    GlslAngle,
}

impl Path {
    pub const ALL: [Path; 17] = [
        Path::WgslNaga,
        Path::GlslNaga,
        Path::GlslGlslang,
        Path::HlslGlslangOd,
        Path::HlslGlslangDefault,
        Path::HlslSlangO0,
        Path::HlslSlang,
        Path::HlslSlangO3,
        Path::HlslSlangViaGlsl,
        Path::GlslGl,
        Path::GlslGlPrecise,
        Path::CC,
        Path::CCpp,
        Path::Lanes,
        Path::Lanes8,
        Path::WgslTint,
        Path::GlslAngle,
    ];
    /// The emitted language the path runs, if any.
    pub fn lang(self) -> Option<Lang> {
        match self {
            Path::WgslNaga | Path::WgslTint => Some(Lang::Wgsl),
            Path::GlslNaga
            | Path::GlslGlslang
            | Path::GlslGl
            | Path::GlslGlPrecise
            | Path::GlslAngle => Some(Lang::Glsl),
            Path::HlslGlslangOd
            | Path::HlslGlslangDefault
            | Path::HlslSlangO0
            | Path::HlslSlang
            | Path::HlslSlangO3
            | Path::HlslSlangViaGlsl => Some(Lang::Hlsl),
            Path::CC | Path::CCpp => Some(Lang::C),
            Path::Lanes | Path::Lanes8 => None,
        }
    }
    /// Whether the path runs a shader on the Vulkan adapter.
    pub fn on_vulkan(self) -> bool {
        self.lang().is_some_and(|l| l != Lang::C) && !self.on_gl() && !self.in_browser()
    }
    /// Whether the path runs in headless Chromium ([`browser`]).
    pub fn in_browser(self) -> bool {
        matches!(self, Path::WgslTint | Path::GlslAngle)
    }
    /// Whether the path runs a shader through OpenGL.
    fn on_gl(self) -> bool {
        matches!(self, Path::GlslGl | Path::GlslGlPrecise)
    }
    /// How many items of each function the path runs where it runs a sample
    /// ([`sample`]): the paths whose arithmetic another path already runs on every item
    /// with the same code generator, so that what they add is their front end's reading
    /// of the text. `None`: every item.
    pub fn sampled(self) -> Option<usize> {
        match self {
            Path::GlslGl
            | Path::GlslGlPrecise
            | Path::HlslSlangO0
            | Path::HlslSlang
            | Path::HlslSlangO3
            | Path::HlslSlangViaGlsl
            | Path::WgslTint
            | Path::GlslAngle => Some(GL_ITEMS),
            Path::CCpp => Some(CPP_ITEMS),
            _ => None,
        }
    }
    /// Whether the path's compiler regroups float products itself, which the doc comments
    /// exclude ("not where a compiler may reassociate"): Slang's direct SPIR-V at its
    /// default optimization and at `-O3` (it drops `precise`, then its optimizer turns
    /// `(x·k)·(x·k)` into `(x·x)·k²` and the like). There a function with float outputs is
    /// measured, not held to the model's bits; packed codes and indices still are, but for
    /// the lean tier's (an engine format's), whose promise excludes reassociation.
    pub fn regroups(self) -> bool {
        matches!(self, Path::HlslSlang | Path::HlslSlangO3)
    }
    /// Whether the path's compiler contracts float operations the include leaves
    /// unmarked where no other path's does: OpenGL's own GLSL compiler without `precise`
    /// (Mesa fuses `a*b + c` there). A family whose lean-tier arithmetic is contracted
    /// there ([`crate::codecs::Family::contracted`]) is measured there, not held.
    pub fn contracts(self) -> bool {
        self == Path::GlslGl
    }
}

impl fmt::Display for Path {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Path::WgslNaga => "wgsl/naga",
            Path::GlslNaga => "glsl/naga",
            Path::GlslGlslang => "glsl/glslang",
            Path::HlslGlslangOd => "hlsl/glslang -Od",
            Path::HlslGlslangDefault => "hlsl/glslang",
            Path::HlslSlangO0 => "hlsl/slang -O0",
            Path::HlslSlang => "hlsl/slang",
            Path::HlslSlangO3 => "hlsl/slang -O3",
            Path::HlslSlangViaGlsl => "hlsl/slang via glsl",
            Path::GlslGl => "glsl/gl",
            Path::GlslGlPrecise => "glsl/gl precise",
            Path::CC => "c/cc -O2",
            Path::CCpp => "c/c++ -O2",
            Path::Lanes => "cpu/4 lanes",
            Path::Lanes8 => "cpu/8 lanes",
            Path::WgslTint => "wgsl/tint",
            Path::GlslAngle => "glsl/angle",
        })
    }
}

/// Where a Vulkan path's module runs: on the run's adapter, or on SwiftShader beside it
/// (a default run on lavapipe runs every SPIR-V route on both).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Device {
    Main,
    SwiftShader,
}

/// One path on one device: a row's `path` column.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Run {
    pub path: Path,
    pub device: Device,
}

impl Run {
    /// How many items of each function the run takes ([`Path::sampled`]); SwiftShader
    /// reads the same module as lavapipe, which runs every item, so it takes a sample.
    fn sampled(self) -> Option<usize> {
        match self.device {
            Device::SwiftShader => Some(GL_ITEMS),
            Device::Main => self.path.sampled(),
        }
    }
    /// Whether the run's implementation flushes denormals to zero (SwiftShader, and the
    /// browsers, which run on it without a GPU or on a GPU that may flush), where the model
    /// keeps them: float forms, which take float inputs, are measured there, not held.
    fn flushes(self) -> bool {
        self.device == Device::SwiftShader || self.path.in_browser()
    }
}

impl fmt::Display for Run {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.device {
            Device::Main => write!(f, "{}", self.path),
            Device::SwiftShader => write!(f, "{} on swiftshader", self.path),
        }
    }
}

/// One mismatching item: its input words, expected and actual output words, and whether
/// the input and output words are floats (printed as value and hex) or codes (hex).
#[derive(Clone, Debug)]
pub struct Mismatch {
    pub input: Vec<u32>,
    pub expected: Vec<u32>,
    pub actual: Vec<u32>,
    pub input_float: bool,
    pub output_float: bool,
}

/// One row of the report.
#[derive(Clone, Debug)]
pub struct Row {
    pub spec: String,
    pub function: String,
    pub path: String,
    pub tested: usize,
    pub mismatches: usize,
    pub first: Vec<Mismatch>,
    /// Compilation or validation failure, if any.
    pub error: Option<String>,
    /// The function (`spec function`) whose code and inputs this one shares exactly,
    /// verified once on the path; this row repeats that row's result.
    pub same_as: Option<String>,
    /// For float outputs that mismatched: the mismatch farthest from the model's value.
    /// On lavapipe there is none; on a hardware adapter it says how far the GPU's
    /// division, roots, contractions and flushes moved the outputs.
    pub largest: Option<Largest>,
    /// Float outputs on a path that regroups products ([`Path::regroups`]): the
    /// mismatches are reported, and are not a failure.
    pub measured: bool,
}

/// The largest difference of one function's float outputs from the model's on a path.
#[derive(Clone, Debug)]
pub struct Largest {
    /// `|expected - actual|` of the lane that differs most, in f64: 0 when only the sign
    /// of a zero differs, infinite when one side is NaN or their infinities differ.
    pub difference: f64,
    pub at: Mismatch,
}

/// `|a - b|` of two f32 words, as [`Largest::difference`] defines it.
fn difference(a: u32, b: u32) -> f64 {
    let (a, b) = (f64::from(f32::from_bits(a)), f64::from(f32::from_bits(b)));
    match (a.is_nan(), b.is_nan()) {
        (true, true) => 0.0,
        (false, false) if a == b => 0.0,
        (false, false) => {
            let d = (a - b).abs();
            if d.is_nan() { f64::INFINITY } else { d }
        }
        _ => f64::INFINITY,
    }
}

impl Row {
    pub fn passed(&self) -> bool {
        self.error.is_none() && (self.mismatches == 0 || self.measured)
    }
}

pub struct Report {
    pub adapter: String,
    pub driver: String,
    pub rows: Vec<Row>,
}

fn words_hex(w: &[u32], as_float: bool) -> String {
    w.iter()
        .map(|b| {
            if as_float {
                format!("{:?} (0x{b:08x})", f32::from_bits(*b))
            } else {
                format!("0x{b:08x}")
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

impl Report {
    pub fn all_passed(&self) -> bool {
        self.rows.iter().all(Row::passed)
    }

    pub fn table(&self) -> String {
        let mut s = format!("adapter: {} — driver: {}\n", self.adapter, self.driver);
        // Each column is as wide as its longest entry (`glsl es 300/glslang` is wider
        // than the usual 18), so that no row shifts the columns after it.
        let width = |min: usize, field: fn(&Row) -> &str| {
            let longest = self.rows.iter().map(|r| field(r).chars().count()).max();
            longest.unwrap_or(0).max(min)
        };
        let (ws, wf, wp) = (
            width(22, |r| &r.spec),
            width(28, |r| &r.function),
            width(18, |r| &r.path),
        );
        s.push_str(&format!(
            "{:<ws$} {:<wf$} {:<wp$} {:>10} {:>10}\n",
            "spec", "function", "path", "tested", "mismatches"
        ));
        for r in &self.rows {
            let mm = if r.error.is_some() {
                "ERROR".to_string()
            } else if r.measured && r.mismatches > 0 {
                format!("{}~", r.mismatches)
            } else {
                r.mismatches.to_string()
            };
            let shared = r
                .same_as
                .as_ref()
                .map_or(String::new(), |o| format!("  (same code as {o})"));
            s.push_str(&format!(
                "{:<ws$} {:<wf$} {:<wp$} {:>10} {:>10}{shared}\n",
                r.spec, r.function, r.path, r.tested, mm
            ));
        }
        let failed: Vec<&Row> = self.rows.iter().filter(|r| !r.passed()).collect();
        for r in &failed {
            s.push_str(&format!(
                "\nFAILED {} {} on {}:\n",
                r.spec, r.function, r.path
            ));
            if let Some(e) = &r.error {
                s.push_str(&format!("  {e}\n"));
            }
            if let Some(l) = &r.largest {
                s.push_str(&format!(
                    "  largest difference {:e}, at input [{}]\n    expected [{}]\n    actual   [{}]\n  first mismatches:\n",
                    l.difference,
                    words_hex(&l.at.input, l.at.input_float),
                    words_hex(&l.at.expected, l.at.output_float),
                    words_hex(&l.at.actual, l.at.output_float)
                ));
            }
            for m in &r.first {
                s.push_str(&format!(
                    "  input [{}]\n    expected [{}]\n    actual   [{}]\n",
                    words_hex(&m.input, m.input_float),
                    words_hex(&m.expected, m.output_float),
                    words_hex(&m.actual, m.output_float)
                ));
            }
        }
        for r in self.rows.iter().filter(|r| r.measured && r.mismatches > 0) {
            let largest = r.largest.as_ref().map_or(String::new(), |l| {
                format!(", largest difference {:e}", l.difference)
            });
            s.push_str(&format!(
                "\nmeasured {} {} on {}: {} of {} differ{largest}",
                r.spec, r.function, r.path, r.mismatches, r.tested
            ));
        }
        if self.rows.iter().any(|r| r.measured && r.mismatches > 0) {
            s.push_str(
                "\nN~: measured, not held to the model's bits: float outputs on a path that \
                 regroups products (Slang's direct SPIR-V at its default and -O3); float forms, \
                 and the lean tier's codes, where denormals are flushed (SwiftShader, the \
                 browsers); an engine's contracted arithmetic where OpenGL's compiler contracts \
                 it (without precise)\n",
            );
        }
        let shared = self.rows.iter().filter(|r| r.same_as.is_some()).count();
        s.push_str(&format!(
            "\n{} checks ({shared} shared with identical code), {} items run, {} failed\n",
            self.rows.len(),
            self.items_run(),
            failed.len()
        ));
        s
    }

    /// The items actually run: rows that share another's result add none.
    pub fn items_run(&self) -> usize {
        self.rows
            .iter()
            .filter(|r| r.same_as.is_none())
            .map(|r| r.tested)
            .sum()
    }
}

/// Expected outputs of the model, computed on all cores.
pub fn expected(f: &Function, input: &[u32]) -> Vec<u32> {
    let mut out = Vec::new();
    expected_into(f, input, &mut out);
    out
}

/// [`expected`] into `out`, whose allocation a worker keeps from one function to the
/// next: a fresh one for each (up to 200 MB) had the kernel map and zero new pages.
fn expected_into(f: &Function, input: &[u32], out: &mut Vec<u32>) {
    out.clear();
    out.resize(input.len() / f.in_words * f.out_words, 0);
    on_all_cores(input, out, f.in_words, f.out_words, |i, o| (f.eval)(i, o));
}

/// The outputs of [`Function::eval_many_on`] the given lanes for `input`, on all cores,
/// into `out`.
fn lanes(f: &Function, width: Width, input: &[u32], out: &mut [u32]) {
    on_all_cores(input, out, f.in_words, f.out_words, |i, o| {
        f.eval_many_on(width, i, o)
    });
}

/// Items a CPU path (the lanes, the C driver) computes at a time before the comparison
/// takes them: a whole function's outputs at once (up to 200 MB for a 24-bit decoder) had
/// the kernel map and zero fresh pages for every function and path. A multiple of 256, so
/// that the lanes meet the same neighbours as in one call.
const CPU_CHUNK: usize = 1 << 18;

/// Runs `fill` over `input` a [`CPU_CHUNK`] at a time, into one reused buffer, and hands
/// each chunk's outputs to the comparison.
fn in_chunks(
    f: &Function,
    input: &[u32],
    cmp: &mut Comparison,
    mut fill: impl FnMut(&[u32], &mut [u32]) -> Result<()>,
) -> Result<()> {
    let mut out = vec![0u32; CPU_CHUNK.min(input.len() / f.in_words) * f.out_words];
    for items in input.chunks(CPU_CHUNK * f.in_words) {
        let out = &mut out[..items.len() / f.in_words * f.out_words];
        fill(items, out)?;
        cmp.take(out);
    }
    Ok(())
}

/// Runs `run` over `input` (items of `in_words`) split into one contiguous share per
/// core, each writing its items' `out_words` to the same share of `output`. While one
/// spec's shader runs on the adapter or its C driver compiles, the other cores would
/// otherwise idle on a single-threaded path.
pub(crate) fn on_all_cores(
    input: &[u32],
    output: &mut [u32],
    in_words: usize,
    out_words: usize,
    run: impl Fn(&[u32], &mut [u32]) + Sync,
) {
    let n = input.len() / in_words;
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get());
    // Whole blocks of the four-lane batches, so that each item meets the same lane
    // neighbours as in one call over everything.
    let per = n.div_ceil(threads).max(1).next_multiple_of(256);
    let run = &run;
    std::thread::scope(|s| {
        for (o, i) in output
            .chunks_mut(per * out_words)
            .zip(input.chunks(per * in_words))
        {
            s.spawn(move || run(i, o));
        }
    });
}

/// A function's outputs on one path compared with the model's as they arrive, chunk by
/// chunk: the mismatch count and the first few mismatches, with their inputs.
pub struct Comparison<'a> {
    f: &'a Function,
    /// The parameters' types and the kind of the result's words.
    types: (&'a [Ty], Kind),
    input: &'a [u32],
    want: &'a [u32],
    /// Output words received so far.
    words: usize,
    count: usize,
    first: Vec<Mismatch>,
    /// How many mismatches `first` lists.
    keep: usize,
    largest: Option<Largest>,
}

/// What a [`Comparison`] found.
#[derive(Debug)]
pub struct Outcome {
    pub count: usize,
    /// The first few mismatches, in input order.
    pub first: Vec<Mismatch>,
    /// For float outputs, the mismatch farthest from the model.
    pub largest: Option<Largest>,
}

impl<'a> Comparison<'a> {
    pub fn new(
        f: &'a Function,
        types: (&'a [Ty], Kind),
        input: &'a [u32],
        want: &'a [u32],
    ) -> Self {
        Comparison {
            f,
            types,
            input,
            want,
            words: 0,
            count: 0,
            first: Vec::new(),
            keep: FIRST,
            largest: None,
        }
    }

    /// Lists up to `keep` mismatches (at least [`FIRST`]).
    pub fn keeping(mut self, keep: usize) -> Self {
        self.keep = keep.max(FIRST);
        self
    }

    /// The next `got` words of output, continuing from the words already received.
    pub fn take(&mut self, got: &[u32]) {
        let at = self.words;
        self.words += got.len();
        let Some(want) = self.want.get(at..self.words) else {
            return; // More words than expected: `finish` says so.
        };
        // Nearly every check matches: one comparison of the whole chunk settles it.
        if want == got {
            return;
        }
        let (f, first_item) = (self.f, at / self.f.out_words);
        for (k, (w, g)) in want
            .chunks(f.out_words)
            .zip(got.chunks(f.out_words))
            .enumerate()
        {
            if w != g {
                self.count += 1;
                let item = first_item + k;
                let mismatch = || Mismatch {
                    input: self.input[item * f.in_words..(item + 1) * f.in_words].to_vec(),
                    expected: w.to_vec(),
                    actual: g.to_vec(),
                    input_float: self.types.0.iter().all(|t| t.kind == Kind::F32),
                    output_float: self.types.1 == Kind::F32,
                };
                if self.types.1 == Kind::F32 {
                    let d = w
                        .iter()
                        .zip(g)
                        .map(|(&w, &g)| difference(w, g))
                        .fold(0.0, f64::max);
                    if self.largest.as_ref().is_none_or(|l| d > l.difference) {
                        self.largest = Some(Largest {
                            difference: d,
                            at: mismatch(),
                        });
                    }
                }
                if self.first.len() < self.keep {
                    self.first.push(mismatch());
                }
            }
        }
    }

    /// What was found, or an error if the path returned another number of words than
    /// the model.
    pub fn finish(self) -> std::result::Result<Outcome, String> {
        if self.words != self.want.len() {
            return Err(format!(
                "returned {} words for {} expected",
                self.words,
                self.want.len()
            ));
        }
        Ok(Outcome {
            count: self.count,
            first: self.first,
            largest: self.largest,
        })
    }
}

/// Compiles the shader kernel for `path`, running the static checks on the way.
fn compile_shader(path: Path, kernel: &str) -> Result<Option<Vec<u32>>> {
    Ok(match path {
        Path::WgslNaga => {
            tools::naga_wgsl(kernel)?;
            None
        }
        Path::GlslNaga => {
            tools::naga_glsl(kernel)?;
            None
        }
        Path::GlslGlslang => {
            // glslang knows `precise` (naga does not): compile with it, as a user would.
            // As GLSL 4.30, the first version with compute shaders: the kernel needs
            // nothing later, and glslang starts in half the time of a 4.50 compile.
            let define = format!(
                "#version 430\n#define {} precise\n",
                precise_macro(DEFAULT_PREFIX)
            );
            let kernel = kernel.replacen("#version 450\n", &define, 1);
            let spv = tools::glslang_spirv(
                &kernel,
                GlslangInput::Glsl { stage: "comp" },
                HlslOpt::Default,
            )?;
            tools::spirv_val(&spv)?;
            tools::spirv_float_ops_precise(&spv)?;
            Some(spv)
        }
        Path::HlslGlslangOd | Path::HlslGlslangDefault => {
            let opt = if path == Path::HlslGlslangOd {
                HlslOpt::Od
            } else {
                HlslOpt::Default
            };
            let spv = tools::glslang_spirv(
                kernel,
                GlslangInput::Hlsl {
                    stage: "comp",
                    entry: "main",
                },
                opt,
            )?;
            tools::spirv_val(&spv)?;
            tools::spirv_float_ops_precise(&spv)?;
            Some(spv)
        }
        Path::HlslSlangO0 | Path::HlslSlang | Path::HlslSlangO3 | Path::HlslSlangViaGlsl => {
            let route = match path {
                Path::HlslSlangO0 => slang::Route::O0,
                Path::HlslSlang => slang::Route::Default,
                Path::HlslSlangO3 => slang::Route::O3,
                _ => slang::Route::ViaGlsl,
            };
            let spv = slang::Slang::shared()?.spirv(kernel, route)?;
            tools::spirv_val(&spv)?;
            Some(spv)
        }
        Path::GlslGl | Path::GlslGlPrecise => unreachable!("compiled by the OpenGL driver"),
        Path::WgslTint | Path::GlslAngle => unreachable!("compiled in the browser"),
        Path::CC | Path::CCpp | Path::Lanes | Path::Lanes8 => {
            unreachable!("not a shader path")
        }
    })
}

/// The static checks of a whole include: naga validates the WGSL and writes it as GLSL
/// 4.30 and ES 3.10, which glslang compiles ([`tools::naga_glsl_sources`]); glslang compiles the
/// HLSL (beside an empty entry point) and the GLSL as a GLSL 330 and a GLSL ES 300 fragment
/// shader. (The C paths compile the whole header into the driver every function runs in.)
pub fn whole_include(lang: Lang, include: &str) -> Vec<(String, Result<()>)> {
    whole_includes(&[(lang, include)], None)
        .pop()
        .expect("the checks of one include")
}

/// A check of [`whole_includes`]: done, or GLSL sources of one stage for glslang to check,
/// all of which must compile.
enum Check {
    Done(Result<()>),
    Glsl(&'static str, Vec<(String, String)>),
}

/// [`whole_include`] of each include, on every core. The GLSL that glslang checks without
/// SPIR-V (naga's output, the 330 and ES 300 forms) is checked in shared runs
/// ([`tools::glslang_check_many`]); the HLSL needs SPIR-V, which glslang makes by linking
/// every file of a run into one module, so each HLSL include has a run of its own.
///
/// With `browser`, Tint also validates each WGSL include and ANGLE compiles each GLSL
/// include as GLSL ES 3.00, warnings failing ([`browser_check`]): the browser paths run
/// only the functions a spec owns, and this covers the includes of the others.
pub fn whole_includes(
    items: &[(Lang, &str)],
    browser: Option<&browser::Browser>,
) -> Vec<Vec<(String, Result<()>)>> {
    let mut checks: Vec<Vec<(&str, Check)>> =
        crate::support::par::map(items, |&(lang, include)| {
            let mut checks = compiler_checks(lang, include);
            // Every float literal read back as each compiler reads it (naga and glslang accept
            // some that Tint and ANGLE do not).
            let literals = Check::Done(literals::check(lang, include, None).map(drop));
            checks.push((literal_check_path(lang), literals));
            checks
        });
    // The page compiles one source at a time: ask it from here, in order.
    if let Some(b) = browser {
        for (&(lang, include), checks) in items.iter().zip(&mut checks) {
            if let Some((path, check)) = browser_check(b, lang, include) {
                checks.push((path, Check::Done(check)));
            }
        }
    }
    // Every source glslang is to check, by stage, and the results in the same order.
    let mut results = HashMap::new();
    for stage in ["comp", "frag"] {
        let sources: Vec<(String, String)> = checks
            .iter()
            .flatten()
            .filter_map(|(_, c)| match c {
                Check::Glsl(s, sources) if *s == stage => Some(sources.iter().cloned()),
                _ => None,
            })
            .flatten()
            .collect();
        results.insert(
            stage,
            tools::glslang_check_many(stage, &sources).into_iter(),
        );
    }
    checks
        .into_iter()
        .map(|of_item| {
            of_item
                .into_iter()
                .map(|(path, check)| {
                    let r = match check {
                        Check::Done(r) => r,
                        Check::Glsl(stage, sources) => {
                            let of_stage = results.get_mut(stage).expect("checked by stage");
                            tools::all_ok(of_stage.take(sources.len()).collect())
                        }
                    };
                    (path.to_string(), r)
                })
                .collect()
        })
        .collect()
}

/// The browser's compilation of a whole include, for the languages it takes: WGSL by
/// Tint (`wgsl/tint`), GLSL as a GLSL ES 3.00 vertex shader by ANGLE (`glsl/angle`).
fn browser_check(
    b: &browser::Browser,
    lang: Lang,
    include: &str,
) -> Option<(&'static str, Result<()>)> {
    match lang {
        Lang::Wgsl => Some(("wgsl/tint", b.compile(browser::Api::WebGpu, include))),
        Lang::Glsl => Some((
            "glsl/angle",
            b.compile(browser::Api::WebGl, &browser::webgl_include_shader(include)),
        )),
        Lang::Hlsl | Lang::C => None,
    }
}

/// The `(whole include)` path of [`literals::check`] in `lang`.
fn literal_check_path(lang: Lang) -> &'static str {
    match lang {
        Lang::Wgsl => "wgsl/literals",
        Lang::Glsl => "glsl/literals",
        Lang::Hlsl => "hlsl/literals",
        Lang::C => "c/literals",
    }
}

/// The compilers' checks of one include ([`whole_includes`]).
fn compiler_checks(lang: Lang, include: &str) -> Vec<(&'static str, Check)> {
    match lang {
        Lang::Wgsl => vec![
            ("wgsl/naga", Check::Done(tools::naga_wgsl(include))),
            (
                "wgsl/naga glsl-out",
                match tools::naga_glsl_sources(include) {
                    Ok(sources) => Check::Glsl("comp", sources),
                    Err(e) => Check::Done(Err(e)),
                },
            ),
        ],
        Lang::Hlsl => {
            let entry = "unitpack_include_check";
            let source = format!("{include}\n[numthreads(1, 1, 1)]\nvoid {entry}() {{}}\n");
            let input = GlslangInput::Hlsl {
                stage: "comp",
                entry,
            };
            let r = tools::glslang_spirv(&source, input, HlslOpt::Default).map(drop);
            vec![("hlsl/glslang", Check::Done(r))]
        }
        Lang::Glsl => {
            let form = |version: &str, color: &str| {
                let main = format!("out {color} color;\nvoid main() {{ color = vec4(0.0); }}\n");
                let text = format!("#version {version}\n{include}\n{main}");
                Check::Glsl(
                    "frag",
                    vec![(format!("glsl-{}", version.replace(' ', "-")), text)],
                )
            };
            vec![
                ("glsl 330/glslang", form("330", "vec4")),
                ("glsl es 300/glslang", form("300 es", "highp vec4")),
            ]
        }
        Lang::C => vec![],
    }
}

/// A traced function's parameter types and results, its names carrying `prefix`
/// ([`Returns::of`]).
pub fn func_types(f: &Func, prefix: &str) -> (Vec<Ty>, Returns) {
    (
        f.params.iter().map(|p| p.1).collect(),
        Returns::of(f, prefix),
    )
}

/// Verifies `specs` on every path of `langs`, with a progress bar when `progress`, on the
/// Vulkan CPU adapter.
pub fn run(specs: &[Spec], langs: &[Lang], progress: bool) -> Result<Report> {
    run_on(specs, langs, progress, Adapter::Cpu, FIRST)
}

/// How many mismatches a row lists by default ([`Row::first`]).
pub const FIRST: usize = 5;

/// [`run`] with the shader paths on the Vulkan adapter `adapter` asks for, listing up to
/// `keep` mismatches of each function per path (float outputs also their largest): a
/// hardware run's changed codes, and SwiftShader's flushed float outputs, are regression
/// data for the deviation model.
pub fn run_on(
    specs: &[Spec],
    langs: &[Lang],
    progress: bool,
    adapter: Adapter,
    keep: usize,
) -> Result<Report> {
    let paths: Vec<Path> = Path::ALL
        .into_iter()
        .filter(|p| p.lang().is_none_or(|l| langs.contains(&l)))
        .collect();
    // The C and CPU paths need no GPU: only ask for the adapter when a shader path is run.
    let gpu = if paths.iter().any(|p| p.on_vulkan()) {
        Some(Gpu::shared_on(adapter)?)
    } else {
        None
    };
    // Beside lavapipe, every SPIR-V route also runs on SwiftShader, what browsers without
    // a GPU run.
    let swift = if adapter == Adapter::Cpu && gpu.is_some() {
        Some(Gpu::shared_on(Adapter::SwiftShader)?)
    } else {
        None
    };
    let runs: Vec<Run> = paths
        .iter()
        .map(|&path| Run {
            path,
            device: Device::Main,
        })
        .chain(
            paths
                .iter()
                .filter(|p| swift.is_some() && p.on_vulkan())
                .map(|&path| Run {
                    path,
                    device: Device::SwiftShader,
                }),
        )
        .collect();
    let browser = if paths.iter().any(|p| p.in_browser()) {
        let b = browser::Browser::start()?;
        b.adapters()?;
        Some(b)
    } else {
        None
    };
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let gl = if paths.iter().any(|p| p.on_gl()) {
        Some(gl::Gl::shared(adapter == Adapter::Cpu, threads)?)
    } else {
        None
    };
    let emitted: Vec<_> = specs.iter().map(|s| s.emitted()).collect();
    let owners = owners(specs, &emitted);
    // Each spec's include in each language, and the static checks of every include, ahead
    // of the workers: glslang checks many includes in one run ([`whole_includes`]).
    let includes: Vec<Vec<(Lang, String)>> = crate::support::par::map(specs, |spec| {
        langs
            .iter()
            .map(|&l| {
                let include = render(
                    &[crate::measure::measured(spec, None)],
                    l,
                    DEFAULT_PREFIX,
                    "unitpack verify",
                );
                (l, include)
            })
            .collect()
    });
    let items: Vec<(Lang, &str)> = includes
        .iter()
        .flatten()
        .map(|(l, include)| (*l, include.as_str()))
        .collect();
    let mut checks = whole_includes(&items, browser.as_ref()).into_iter();
    let checks: Vec<Vec<(String, Option<String>)>> = includes
        .iter()
        .map(|of_spec| {
            (&mut checks)
                .take(of_spec.len())
                .flatten()
                .map(|(path, r)| (path, r.err().map(|e| format!("{e:#}"))))
                .collect()
        })
        .collect();
    let total: usize = emitted.iter().map(|e| e.functions.len() * runs.len()).sum();
    let bar = if progress {
        indicatif::ProgressBar::new(total as u64)
    } else {
        indicatif::ProgressBar::hidden()
    };
    bar.set_style(
        indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} {msg} [{elapsed}]")
            .expect("progress template"),
    );
    // Specs are independent: verify them on as many threads as there are cores, each
    // taking the next spec, and keep the report in spec order. The shader paths share
    // the one device; the model's expected values and the C compilers use the rest.
    let on = On {
        runs: &runs,
        gpu,
        swift,
        gl,
        browser: browser.as_ref(),
        keep,
    };
    // The largest specs first (every code of a 24-bit decoder runs on every path), so
    // that no large one is left to a single core at the end; the report keeps spec order.
    let mut order: Vec<usize> = (0..specs.len()).collect();
    order.sort_by_key(|&i| std::cmp::Reverse(specs[i].bits().min(24)));
    let next = std::sync::atomic::AtomicUsize::new(0);
    let mut per_spec: Vec<(usize, Vec<Row>)> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads.min(specs.len()).max(1))
            .map(|_| {
                scope.spawn(|| {
                    let mut done = Vec::new();
                    // The model's outputs of the function at hand, one allocation kept.
                    let mut want = Vec::new();
                    loop {
                        let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        let Some(&i) = order.get(k) else { break };
                        let spec = &specs[i];
                        let spec = Verified {
                            spec,
                            emitted: &emitted[i],
                            shared: &owners[i],
                            includes: &includes[i],
                            checks: &checks[i],
                        };
                        done.push((i, verify_spec(&spec, &on, &bar, &mut want)));
                    }
                    done
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().expect("a verify worker panicked"))
            .collect()
    });
    per_spec.sort_by_key(|(i, _)| *i);
    let mut rows: Vec<Row> = per_spec.into_iter().flat_map(|(_, rows)| rows).collect();
    copy_shared_results(&mut rows);
    bar.finish_and_clear();
    let mut adapter = gpu.map_or("none (C paths only)".into(), |g| {
        g.adapter_name().to_string()
    });
    if let Some(s) = swift {
        adapter.push_str(&format!(" and {}", s.adapter_name()));
    }
    if let Some(b) = &browser {
        adapter.push_str(&format!("; headless Chromium: {}", b.describe()));
    }
    Ok(Report {
        adapter,
        driver: gpu.map_or("-".into(), |g| g.driver().to_string()),
        rows,
    })
}

/// For each function of each spec, the earlier function (`spec function`) with the same
/// code and inputs ([`first_with_same_code`]), if there is one: every path compiles and
/// runs that one only, no compiler computing with names and the model being the same
/// traced computation (each spec's whole include is still checked on its own, and its C
/// driver compiles every function of the header).
fn owners(specs: &[Spec], emitted: &[Arc<Emitted>]) -> Vec<Vec<Option<String>>> {
    first_with_same_code(emitted)
        .into_iter()
        .map(|of_spec| {
            of_spec
                .into_iter()
                .map(|at| at.map(|(i, j)| format!("{} {}", specs[i], emitted[i].functions[j].name)))
                .collect()
        })
        .collect()
}

/// Fills each shared row with the result of the row it names on the same path.
fn copy_shared_results(rows: &mut [Row]) {
    let index: HashMap<(String, String), usize> = rows
        .iter()
        .enumerate()
        .filter(|(_, r)| r.same_as.is_none())
        .map(|(k, r)| ((format!("{} {}", r.spec, r.function), r.path.clone()), k))
        .collect();
    for k in 0..rows.len() {
        let Some(owner) = rows[k].same_as.clone() else {
            continue;
        };
        let o = index[&(owner, rows[k].path.clone())];
        let (tested, mismatches) = (rows[o].tested, rows[o].mismatches);
        let (first, error) = (rows[o].first.clone(), rows[o].error.clone());
        let measured = rows[o].measured;
        let r = &mut rows[k];
        (r.tested, r.mismatches, r.first, r.error) = (tested, mismatches, first, error);
        r.measured = measured;
    }
}

/// Items of each function the OpenGL paths run: every edge item (the inputs put them
/// first) and a seeded spread of the rest. Those paths check what the driver's GLSL
/// compiler makes of the text, with the arithmetic of the same backend as lavapipe's,
/// which the Vulkan paths check on every item.
pub const GL_ITEMS: usize = 1 << 16;

/// Items of each function the C++ path runs, chosen as for [`GL_ITEMS`]: g++ reads the
/// header with its own front end but optimizes and generates code with the same GCC back
/// end and flags as the C path, which runs every item; the sample holds every edge item
/// and every code of a function of up to 17 bits.
pub const CPP_ITEMS: usize = 1 << 17;

/// A sample's input words and the model's output words for them.
type Sample = (Vec<u32>, Vec<u32>);

/// The first `items / 2` items and a seeded, evenly spread choice of the others, with
/// their expected outputs; every item where there are no more.
fn sample(input: &[u32], want: &[u32], iw: usize, ow: usize, items: usize) -> Sample {
    let (mut i, mut o) = (Vec::new(), Vec::new());
    for k in picks(input.len() / iw, items) {
        i.extend_from_slice(&input[k * iw..][..iw]);
        o.extend_from_slice(&want[k * ow..][..ow]);
    }
    (i, o)
}

/// The items of `n` that [`sample`] takes: every one where there are at most `items`,
/// else the first `items / 2` and a seeded, evenly spread choice of the others.
pub fn picks(n: usize, items: usize) -> Vec<usize> {
    if n <= items {
        return (0..n).collect();
    }
    let head = items / 2;
    let rest = items - head;
    let step = (n - head) as f64 / rest as f64;
    (0..head)
        .chain((0..rest).map(|k| {
            // Jittered within each step, so that a field's low bits vary between picks.
            let jitter = (k as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 40;
            head + (k as f64 * step) as usize + (jitter as usize % step.max(1.0) as usize)
        }))
        .map(|k| k.min(n - 1))
        .collect()
}

/// Where a run verifies and what it lists: the paths, the adapter of the shader paths, and
/// how many mismatches a row keeps.
struct On<'a> {
    runs: &'a [Run],
    gpu: Option<&'a Gpu>,
    /// SwiftShader, where the Vulkan paths also run.
    swift: Option<&'a Gpu>,
    gl: Option<&'a gl::Gl>,
    browser: Option<&'a browser::Browser>,
    keep: usize,
}

/// One spec as [`verify_spec`] takes it: its emitted functions, the earlier function each
/// shares its code with ([`owners`]), its include in each language, and the static checks
/// of those includes (path, error).
struct Verified<'a> {
    spec: &'a Spec,
    emitted: &'a Emitted,
    shared: &'a [Option<String>],
    includes: &'a [(Lang, String)],
    checks: &'a [(String, Option<String>)],
}

/// Every row of one spec: its whole includes, then each function on each path.
/// `want_buf` holds each function's expected outputs in turn.
fn verify_spec(
    v: &Verified,
    on: &On,
    bar: &indicatif::ProgressBar,
    want_buf: &mut Vec<u32>,
) -> Vec<Row> {
    let (spec, e, shared, includes) = (v.spec, v.emitted, v.shared, v.includes);
    let (runs, gpu, keep) = (on.runs, on.gpu, on.keep);
    let paths: Vec<Path> = runs
        .iter()
        .filter(|r| r.device == Device::Main)
        .map(|r| r.path)
        .collect();
    // Every include on its own, whatever its functions share with another spec's: the
    // kernels below compile only the functions they call.
    let mut rows: Vec<Row> = v
        .checks
        .iter()
        .map(|(path, error)| Row {
            spec: spec.to_string(),
            function: "(whole include)".into(),
            path: path.clone(),
            tested: 0,
            mismatches: 0,
            first: vec![],
            error: error.clone(),
            same_as: None,
            largest: None,
            measured: false,
        })
        .collect();
    let include = |l: Lang| &includes.iter().find(|(x, _)| *x == l).expect("lang").1;
    let ns = if e.namespace.is_empty() {
        String::new()
    } else {
        format!("{}_", e.namespace)
    };
    // Every function as the programs below call it: full name, parameter and result types.
    let full_name = |f: &Function| format!("{DEFAULT_PREFIX}{ns}{}", f.name);
    let names: Vec<String> = e.functions.iter().map(full_name).collect();
    let all: Vec<KernelFn> = e
        .functions
        .iter()
        .zip(&names)
        .map(|(f, name)| {
            let prefix = format!("{DEFAULT_PREFIX}{ns}");
            let (params, ret) = func_types(e.module.func(f.name).expect("traced"), &prefix);
            (name.as_str(), params, ret)
        })
        .collect();
    // The C paths compile one driver per spec and compiler, for all its functions.
    let c_programs: Vec<(Path, Result<native::Program, String>)> = paths
        .iter()
        .filter(|p| p.lang() == Some(Lang::C))
        .map(|&p| {
            let source = crate::emit::lang::c::driver(include(Lang::C), &all);
            let compiler = if p == Path::CC {
                native::Compiler::C
            } else {
                native::Compiler::Cpp
            };
            (
                p,
                native::compile(compiler, &source).map_err(|e| format!("{e:#}")),
            )
        })
        .collect();
    // The shader paths compile one selecting kernel per spec and path for the functions
    // run here (not those sharing an earlier function's code): each front end reads the
    // include once per spec, and each function's pipeline is specialized from the one
    // module. A function's selector is its place in `own`.
    let own: Vec<usize> = (0..e.functions.len())
        .filter(|&i| shared[i].is_none())
        .collect();
    let funcs: Vec<KernelFn> = own.iter().map(|&i| all[i].clone()).collect();
    // Each language's selecting kernel, written once for every path that compiles it.
    let kernel_texts: Vec<(Lang, String)> = Lang::ALL
        .into_iter()
        .filter(|&l| l != Lang::C && includes.iter().any(|(x, _)| *x == l))
        .map(|l| (l, l.backend(DEFAULT_PREFIX).kernel(include(l), &funcs)))
        .collect();
    let kernel_text = |l: Lang| {
        &kernel_texts
            .iter()
            .find(|(x, _)| *x == l)
            .expect("a kernel per language")
            .1
    };
    // Each Vulkan path's module, compiled once and made a pipeline source on every device
    // it runs on.
    let kernels: Vec<(Run, Result<gpu::Selecting, String>)> = match gpu {
        Some(gpu) if !own.is_empty() => paths
            .iter()
            .filter(|p| p.on_vulkan())
            .flat_map(|&path| {
                let lang = path.lang().expect("a shader path");
                let kernel = kernel_text(lang);
                let spv = compile_shader(path, kernel).map_err(|e| format!("{e:#}"));
                runs.iter()
                    .filter(|r| r.path == path)
                    .map(|&run| {
                        let device = match run.device {
                            Device::Main => gpu,
                            Device::SwiftShader => on.swift.expect("SwiftShader opened"),
                        };
                        let module = spv.clone().and_then(|spv| {
                            device
                                .selecting(&match (&spv, lang) {
                                    (Some(words), _) => Shader::SpirV(words),
                                    (None, Lang::Wgsl) => Shader::Wgsl(kernel),
                                    (None, _) => Shader::GlslNaga(kernel),
                                })
                                .map_err(|e| format!("{e:#}"))
                        });
                        (run, module)
                    })
                    .collect::<Vec<_>>()
            })
            .collect(),
        _ => Vec::new(),
    };
    // The browser compiles a spec's WGSL kernel once (it caches by key); WebGL programs
    // are one per function.
    let key_of = |text: &str| {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        text.hash(&mut h);
        h.finish()
    };
    // The OpenGL paths compile the same functions once per form, as the driver's own
    // GLSL compiler reads them.
    let gl_programs: Vec<(Path, Result<gl::Program, String>)> = match on.gl {
        Some(ctx) if !own.is_empty() => {
            let glsl = crate::emit::lang::glsl::Glsl::new(DEFAULT_PREFIX);
            paths
                .iter()
                .filter(|p| p.on_gl())
                .map(|&path| {
                    let kernel =
                        glsl.gl_kernel(include(Lang::Glsl), &funcs, path == Path::GlslGlPrecise);
                    let program = ctx.program(&kernel, crate::emit::lang::KERNEL_SELECT);
                    (path, program.map_err(|e| format!("{e:#}")))
                })
                .collect()
        }
        _ => Vec::new(),
    };
    let mut last_inputs: Option<(Inputs, usize, Vec<u32>)> = None;
    // The first steps of chained functions ([`Stages`]) evaluated on the inputs drawn
    // last, with the model that computed them: a step several functions begin with runs
    // once for all of them.
    let mut firsts: Vec<(Eval, Vec<u32>)> = Vec::new();
    for (index, f) in e.functions.iter().enumerate() {
        bar.set_message(format!("{spec} {}", f.name));
        if let Some(owner) = &shared[index] {
            for &run in runs {
                rows.push(Row {
                    spec: spec.to_string(),
                    function: f.name.to_string(),
                    path: run.to_string(),
                    tested: 0,
                    mismatches: 0,
                    first: vec![],
                    error: None,
                    same_as: Some(owner.clone()),
                    largest: None,
                    measured: false,
                });
                bar.inc(1);
            }
            continue;
        }
        let (_, params, ret) = &all[index];
        // A spec's functions often take the same inputs (encode and encode_float the same
        // vectors): drawn once for them.
        if last_inputs
            .as_ref()
            .is_none_or(|(i, w, _)| *i != f.inputs || *w != f.in_words)
        {
            last_inputs = Some((
                f.inputs.clone(),
                f.in_words,
                inputs::generate(&f.inputs, f.in_words),
            ));
            firsts.clear();
        }
        let input: &[u32] = &last_inputs.as_ref().expect("drawn just above").2;
        match &f.stages {
            Some(s) => {
                let at = match firsts.iter().position(|(e, _)| Arc::ptr_eq(e, &s.first)) {
                    Some(at) => at,
                    None => {
                        let mut mid = vec![0; input.len() / f.in_words * s.mid_words];
                        on_all_cores(input, &mut mid, f.in_words, s.mid_words, |i, o| {
                            (s.first)(i, o)
                        });
                        firsts.push((s.first.clone(), mid));
                        firsts.len() - 1
                    }
                };
                want_buf.clear();
                want_buf.resize(input.len() / f.in_words * f.out_words, 0);
                on_all_cores(&firsts[at].1, want_buf, s.mid_words, f.out_words, |i, o| {
                    (s.then)(i, o)
                });
            }
            None => expected_into(f, input, want_buf),
        }
        // A later function that begins with this one finds its outputs.
        let begins_later = e.functions[index + 1..].iter().any(|g| {
            g.stages
                .as_ref()
                .is_some_and(|s| Arc::ptr_eq(&s.first, &f.eval))
        });
        if begins_later && !firsts.iter().any(|(e, _)| Arc::ptr_eq(e, &f.eval)) {
            firsts.push((f.eval.clone(), want_buf.clone()));
        }
        let want: &[u32] = want_buf;
        // Each sample size the paths ask for, drawn once.
        let mut samples: Vec<(usize, Sample)> = Vec::new();
        for items in runs.iter().filter_map(|r| r.sampled()) {
            if samples.iter().all(|(n, _)| *n != items) {
                samples.push((items, sample(input, want, f.in_words, f.out_words, items)));
            }
        }
        for &run in runs {
            let path = run.path;
            let (input, want) = match run.sampled() {
                Some(items) => {
                    let (_, (i, w)) = samples.iter().find(|(n, _)| *n == items).expect("drawn");
                    (i.as_slice(), w.as_slice())
                }
                None => (input, want),
            };
            let mut cmp = Comparison::new(f, (params, ret.kind()), input, want).keeping(keep);
            let result = if path == Path::Lanes {
                in_chunks(f, input, &mut cmp, |i, o| {
                    lanes(f, Width::Four, i, o);
                    Ok(())
                })
            } else if path == Path::Lanes8 {
                if avx2_lanes::available() {
                    in_chunks(f, input, &mut cmp, |i, o| {
                        lanes(f, Width::Eight, i, o);
                        Ok(())
                    })
                } else {
                    Err(anyhow::anyhow!(
                        "this processor has no AVX2: the eight-lane path cannot run here"
                    ))
                }
            } else if path.lang() == Some(Lang::C) {
                let (_, program) = c_programs
                    .iter()
                    .find(|(p, _)| *p == path)
                    .expect("a driver per C path");
                match program {
                    Ok(program) => in_chunks(f, input, &mut cmp, |i, o| {
                        program.run(index, i, f.in_words, f.out_words, o)
                    }),
                    Err(e) => Err(anyhow::anyhow!("{e}")),
                }
            } else if path.on_gl() {
                let (_, program) = gl_programs
                    .iter()
                    .find(|(p, _)| *p == path)
                    .expect("a program per OpenGL path");
                let selector = own.iter().position(|&i| i == index).expect("run here") as u32;
                match program {
                    Ok(program) => on.gl.expect("a context for OpenGL paths").run_selected(
                        program,
                        selector,
                        input,
                        f.in_words,
                        f.out_words,
                        &mut |got| cmp.take(got),
                    ),
                    Err(e) => Err(anyhow::anyhow!("{e}")),
                }
            } else if path.in_browser() {
                let selector = own.iter().position(|&i| i == index).expect("run here") as u32;
                let webgl;
                let (api, source) = match path {
                    Path::WgslTint => (browser::Api::WebGpu, kernel_text(Lang::Wgsl)),
                    _ => {
                        webgl = crate::emit::lang::glsl::Glsl::new(DEFAULT_PREFIX)
                            .webgl_kernel(include(Lang::Glsl), &all[index]);
                        (browser::Api::WebGl, &webgl)
                    }
                };
                let job = browser::Job {
                    api,
                    key: key_of(source),
                    source,
                    selector,
                    input,
                    in_words: f.in_words,
                    out_words: f.out_words,
                };
                on.browser
                    .expect("a browser for the browser paths")
                    .run(&job, &mut |got| cmp.take(got))
            } else {
                let (_, kernel) = kernels
                    .iter()
                    .find(|(r, _)| *r == run)
                    .expect("a kernel per shader path");
                let selector = own.iter().position(|&i| i == index).expect("run here") as u32;
                let device = match run.device {
                    Device::Main => gpu.expect("adapter for shader paths"),
                    Device::SwiftShader => on.swift.expect("SwiftShader opened"),
                };
                match kernel {
                    Ok(kernel) => device.run_selected(
                        kernel,
                        selector,
                        input,
                        f.in_words,
                        f.out_words,
                        &mut |got| cmp.take(got),
                    ),
                    Err(e) => Err(anyhow::anyhow!("{e}")),
                }
            };
            let mut row = Row {
                spec: spec.to_string(),
                function: f.name.to_string(),
                path: run.to_string(),
                tested: input.len() / f.in_words,
                mismatches: 0,
                first: vec![],
                error: None,
                same_as: None,
                largest: None,
                measured: (path.regroups() && ret.kind() == Kind::F32)
                    // A flushing implementation changes what a float input makes, not what
                    // a code decodes to: float forms are measured there, decoders held.
                    || (run.flushes()
                        && ret.kind() == Kind::F32
                        && params.iter().any(|t| t.kind == Kind::F32))
                    // The lean tier promises its codes only where denormals are kept.
                    || (run.flushes() && crate::codecs::core::ieee::asked(spec))
                    || (path.contracts()
                        && spec.family().contracted(spec)
                        && crate::codecs::core::ieee::asked(spec)),
            };
            match result
                .map_err(|err| format!("{err:#}"))
                .and_then(|()| cmp.finish())
            {
                Ok(o) => (row.mismatches, row.first, row.largest) = (o.count, o.first, o.largest),
                Err(err) => row.error = Some(err),
            }
            rows.push(row);
            bar.inc(1);
        }
    }
    if let Some(ctx) = on.gl {
        for (_, program) in gl_programs {
            if let Ok(p) = program {
                let _ = p.delete(ctx);
            }
        }
    }
    rows
}
