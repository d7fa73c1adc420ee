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

mod checks;
mod compare;
mod path;
mod report;
pub use checks::*;
pub use compare::*;
pub use path::*;
pub use report::*;

use crate::codecs::Spec;
use crate::codecs::functions::function::Emitted;
use crate::codecs::functions::function::first_with_same_code;
use crate::codecs::functions::function::{Eval, Function, Inputs, Width};
use crate::emit::lang::{KernelFn, Returns};
use crate::emit::{DEFAULT_PREFIX, Lang, render};
use crate::model::Kind;
use crate::model::avx2_lanes;
use crate::model::trace::{Func, Ty};
use anyhow::Result;
use gpu::{Adapter, Gpu, Shader};
use std::collections::HashMap;
use std::sync::Arc;

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
