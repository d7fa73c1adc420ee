//! The static checks: each path's compile of a kernel (naga, glslang, Slang, spirv-val),
//! and the whole-include checks every compiler and browser runs on an include.

use super::*;
use crate::emit::lang::glsl::precise_macro;
use crate::emit::{DEFAULT_PREFIX, Lang};
use anyhow::Result;
use std::collections::HashMap;
use tools::{GlslangInput, HlslOpt};

/// Compiles the shader kernel for `path`, running the static checks on the way.
pub(super) fn compile_shader(path: Path, kernel: &str) -> Result<Option<Vec<u32>>> {
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
pub(super) enum Check {
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
pub(super) fn browser_check(
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
pub(super) fn literal_check_path(lang: Lang) -> &'static str {
    match lang {
        Lang::Wgsl => "wgsl/literals",
        Lang::Glsl => "glsl/literals",
        Lang::Hlsl => "hlsl/literals",
        Lang::C => "c/literals",
    }
}

/// The compilers' checks of one include ([`whole_includes`]).
pub(super) fn compiler_checks(lang: Lang, include: &str) -> Vec<(&'static str, Check)> {
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
