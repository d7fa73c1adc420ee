//! Thin, well-errored wrappers over the external shader tools (`glslangValidator`,
//! `spirv-val`) and over naga's WGSL / GLSL frontends plus validator.
//!
//! Every failure carries the tool's complete output (or naga's rendered diagnostic, which
//! quotes the offending source line), because these errors are read by a person trying to
//! fix an emitted shader. A missing binary names the Debian package that provides it.

use std::io::{ErrorKind, Write};
use std::path::Path;
use std::process::{Command, Output};

use anyhow::{Context, anyhow, bail};

/// What glslang is asked to compile.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GlslangInput {
    /// GLSL; `stage` is glslang's stage name and file extension (`"comp"`, `"frag"`, ...).
    Glsl { stage: &'static str },
    /// HLSL (`-D`); `stage` as for GLSL, `entry` the entry-point function (`-e`).
    Hlsl {
        stage: &'static str,
        entry: &'static str,
    },
}

/// Optimisation setting for HLSL compiles. glslang's HLSL frontend runs its own legalisation
/// and optimisation passes by default; `-Od` turns them off. Both are verified because a
/// shader author might ship either, and an optimiser may change floating-point results.
/// (Ignored for GLSL: glslang does not optimise GLSL without `-Os`.)
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HlslOpt {
    /// `-Od`: no optimisation.
    Od,
    /// glslang's default.
    Default,
}

const GLSLANG: &str = "glslangValidator";
const SPIRV_VAL: &str = "spirv-val";

/// Runs a tool, mapping "binary not found" to an error naming the Debian package.
fn run_tool(cmd: &mut Command, tool: &str, package: &str) -> anyhow::Result<Output> {
    match cmd.output() {
        Ok(out) => Ok(out),
        Err(e) if e.kind() == ErrorKind::NotFound => Err(anyhow!(
            "`{tool}` not found on PATH; install the Debian package `{package}`"
        )),
        Err(e) => Err(anyhow!(e).context(format!("running `{tool}`"))),
    }
}

/// Runs the tool and fails, with its full output, unless it succeeds.
fn run_ok(cmd: &mut Command, tool: &str, package: &str) -> anyhow::Result<Output> {
    let out = run_tool(cmd, tool, package)?;
    if !out.status.success() {
        bail!(
            "{} failed ({}):\n{}",
            describe_cmd(cmd),
            out.status,
            tool_output(&out)
        );
    }
    Ok(out)
}

/// The tool's stdout and stderr, labelled, for error messages. glslang prints its
/// diagnostics on stdout, spirv-val on stderr, so both are always included.
fn tool_output(out: &Output) -> String {
    let mut text = String::new();
    for (name, bytes) in [("stdout", &out.stdout), ("stderr", &out.stderr)] {
        let s = String::from_utf8_lossy(bytes);
        let s = s.trim_end();
        if !s.is_empty() {
            text.push_str(&format!("--- {name} ---\n{s}\n"));
        }
    }
    if text.is_empty() {
        text.push_str("(no output)\n");
    }
    text
}

/// Writes `contents` to a fresh temporary file whose name ends in `.{ext}`.
pub(crate) fn temp_file(ext: &str, contents: &[u8]) -> anyhow::Result<tempfile::NamedTempFile> {
    let mut file = tempfile::Builder::new()
        .prefix("unitpack-")
        .suffix(&format!(".{ext}"))
        .tempfile()
        .context("creating a temporary file")?;
    file.write_all(contents)
        .and_then(|()| file.flush())
        .context("writing a temporary file")?;
    Ok(file)
}

/// Compiles with `glslangValidator -V` (Vulkan SPIR-V) and returns the SPIR-V words.
///
/// GLSL is compiled as `glslangValidator -V -S <stage> file.<stage>`; HLSL as
/// `glslangValidator -V -D -e <entry> -S <stage> file.hlsl`, plus `-Od` for [`HlslOpt::Od`].
/// On failure the error holds glslang's full stdout/stderr. If the binary is missing the
/// error says to install the Debian package `glslang-tools`.
pub fn glslang_spirv(source: &str, input: GlslangInput, opt: HlslOpt) -> anyhow::Result<Vec<u32>> {
    let (ext, stage) = match input {
        GlslangInput::Glsl { stage } => (stage, stage),
        GlslangInput::Hlsl { stage, .. } => ("hlsl", stage),
    };
    let src = temp_file(ext, source.as_bytes())?;
    let dir = tempfile::tempdir().context("creating a temporary directory")?;
    let spv = dir.path().join("out.spv");

    let mut cmd = Command::new(GLSLANG);
    cmd.arg("-V");
    if let GlslangInput::Hlsl { entry, .. } = input {
        cmd.args(["-D", "-e", entry]);
        if opt == HlslOpt::Od {
            cmd.arg("-Od");
        }
    }
    cmd.args(["-S", stage]).arg("-o").arg(&spv).arg(src.path());
    let out = run_ok(&mut cmd, GLSLANG, "glslang-tools")?;
    let words = read_spirv(&spv).with_context(|| {
        format!(
            "{} succeeded but its SPIR-V is unusable; its output:\n{}",
            describe_cmd(&cmd),
            tool_output(&out)
        )
    })?;
    Ok(words)
}

fn read_spirv(path: &Path) -> anyhow::Result<Vec<u32>> {
    let bytes = std::fs::read(path).with_context(|| format!("reading {}", path.display()))?;
    if bytes.len() % 4 != 0 || bytes.len() < 20 {
        bail!(
            "{} is {} bytes, not a SPIR-V module",
            path.display(),
            bytes.len()
        );
    }
    let words: Vec<u32> = bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    if words[0] != 0x0723_0203 {
        bail!(
            "{} does not start with the SPIR-V magic number (found {:#010x})",
            path.display(),
            words[0]
        );
    }
    Ok(words)
}

fn describe_cmd(cmd: &Command) -> String {
    let mut s = cmd.get_program().to_string_lossy().into_owned();
    for a in cmd.get_args() {
        s.push(' ');
        s.push_str(&a.to_string_lossy());
    }
    format!("`{s}`")
}

/// Validates GLSL with glslangValidator without producing Vulkan SPIR-V
/// (`glslangValidator -S <stage> file.<stage>`), e.g. to check that an include also compiles
/// as `#version 330` or `#version 300 es`. `source` must contain its own `#version` line.
pub fn glslang_check(source: &str, stage: &'static str) -> anyhow::Result<()> {
    let mut results = glslang_check_many(stage, &[("include".into(), source.into())]);
    results.pop().expect("one result per source")
}

/// Files one glslang run checks at most: its start-up, which reads the built-in
/// declarations of every version and stage it meets, costs more than checking a small
/// include, so the checks of many includes share a run.
const CHECKS_PER_RUN: usize = 64;

/// [`glslang_check`] of many sources of one stage, each given with the file name (without
/// extension) that its diagnostics are to name, in runs of up to [`CHECKS_PER_RUN`] files on
/// every core. Without `-V` glslang compiles each file on its own, not linking them. A run
/// that fails is repeated file by file, so that each error holds only its own file's
/// diagnostics.
pub fn glslang_check_many(
    stage: &'static str,
    sources: &[(String, String)],
) -> Vec<anyhow::Result<()>> {
    let written = (|| {
        let dir = tempfile::tempdir().context("creating a temporary directory")?;
        let mut files = Vec::new();
        for (k, (name, text)) in sources.iter().enumerate() {
            // A folder per source: names may repeat, and a diagnostic names the file.
            let folder = dir.path().join(k.to_string());
            let file = folder.join(format!("{name}.{stage}"));
            std::fs::create_dir(&folder)
                .and_then(|()| std::fs::write(&file, text))
                .with_context(|| format!("writing {}", file.display()))?;
            files.push(file);
        }
        anyhow::Ok((dir, files))
    })();
    let (_dir, files) = match written {
        Ok(w) => w,
        Err(e) => return sources.iter().map(|_| Err(anyhow!("{e:#}"))).collect(),
    };
    let runs: Vec<&[std::path::PathBuf]> = files.chunks(CHECKS_PER_RUN).collect();
    crate::support::par::map(&runs, |run| -> Vec<anyhow::Result<()>> {
        let mut cmd = Command::new(GLSLANG);
        cmd.args(["-S", stage]).args(run.iter());
        match run_tool(&mut cmd, GLSLANG, "glslang-tools") {
            Ok(out) if out.status.success() => run.iter().map(|_| Ok(())).collect(),
            Ok(_) => run
                .iter()
                .map(|file| {
                    let mut cmd = Command::new(GLSLANG);
                    cmd.args(["-S", stage]).arg(file);
                    run_ok(&mut cmd, GLSLANG, "glslang-tools").map(drop)
                })
                .collect(),
            Err(e) => run.iter().map(|_| Err(anyhow!("{e:#}"))).collect(),
        }
    })
    .into_iter()
    .flatten()
    .collect()
}

/// `spirv-opt -O` (which inlines every call into the entry point), then `spirv-dis`: the
/// optimised module as text. Missing binaries name the Debian package `spirv-tools`.
pub fn spirv_opt_dis(words: &[u32]) -> anyhow::Result<String> {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    let file = temp_file("spv", &bytes)?;
    let dir = tempfile::tempdir().context("creating a temporary directory")?;
    let opt = dir.path().join("opt.spv");
    let mut cmd = Command::new("spirv-opt");
    cmd.arg("-O").arg(file.path()).arg("-o").arg(&opt);
    run_ok(&mut cmd, "spirv-opt", "spirv-tools")?;
    let mut cmd = Command::new("spirv-dis");
    cmd.arg("--raw-id").arg(&opt);
    let out = run_ok(&mut cmd, "spirv-dis", "spirv-tools")?;
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// Runs `spirv-val` on the words. If the binary is missing the error names the Debian
/// package `spirv-tools`.
pub fn spirv_val(words: &[u32]) -> anyhow::Result<()> {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    let file = temp_file("spv", &bytes)?;
    let mut cmd = Command::new(SPIRV_VAL);
    cmd.arg(file.path());
    run_ok(&mut cmd, SPIRV_VAL, "spirv-tools")?;
    Ok(())
}

/// Checks that every float addition, subtraction, multiplication and division in the
/// SPIR-V carries `NoContraction`: what `precise` on every float declaration must give, now
/// that one declaration's initializer holds several operations (docs/design/printer.md).
/// The error names the first instruction without it, by its result id.
pub fn spirv_float_ops_precise(words: &[u32]) -> anyhow::Result<()> {
    const OP_DECORATE: u32 = 71;
    const NO_CONTRACTION: u32 = 42;
    // OpFAdd, OpFSub, OpFMul, OpFDiv, OpVectorTimesScalar.
    const ARITHMETIC: [u32; 5] = [129, 131, 133, 136, 142];
    let mut decorated = std::collections::HashSet::new();
    let mut arithmetic = Vec::new();
    let mut at = 5;
    while at < words.len() {
        let count = (words[at] >> 16) as usize;
        let op = words[at] & 0xffff;
        if count == 0 || at + count > words.len() {
            bail!("malformed SPIR-V at word {at}");
        }
        let inst = &words[at..at + count];
        if op == OP_DECORATE && count >= 3 && inst[2] == NO_CONTRACTION {
            decorated.insert(inst[1]);
        } else if ARITHMETIC.contains(&op) && count >= 3 {
            arithmetic.push((op, inst[2]));
        }
        at += count;
    }
    match arithmetic.iter().find(|(_, id)| !decorated.contains(id)) {
        Some((op, id)) => bail!(
            "float operation %{id} (opcode {op}) has no NoContraction: a float declaration's `precise` does not cover it"
        ),
        None => Ok(()),
    }
}

/// naga's validator with every check on. `Capabilities::all()` because this is a syntax and
/// typing gate for emitted code, not a portability check: the kernels only use core features,
/// and a capability error would hide the real diagnostics behind an unrelated one. (wgpu
/// itself validates against the device's real capabilities when the shader is run.)
fn validate(
    module: &naga::Module,
    language: &str,
    source: &str,
) -> anyhow::Result<naga::valid::ModuleInfo> {
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(module)
    .map_err(|e| {
        anyhow!(
            "naga {language} validation error:\n{}",
            e.emit_to_string(source)
        )
    })
}

/// naga: parses and validates WGSL. The error is naga's rendered diagnostic, which quotes
/// the source around the problem.
pub fn naga_wgsl(source: &str) -> anyhow::Result<()> {
    naga_wgsl_module(source).map(drop)
}

fn naga_wgsl_module(source: &str) -> anyhow::Result<(naga::Module, naga::valid::ModuleInfo)> {
    let module = naga::front::wgsl::parse_str(source)
        .map_err(|e| anyhow!("naga WGSL parse error:\n{}", e.emit_to_string(source)))?;
    let info = validate(&module, "WGSL", source)?;
    Ok((module, info))
}

/// The GLSL versions [`naga_glsl_sources`] has naga write: 4.30 and ES 3.10, the first with
/// compute shaders and the oldest that naga's GLSL back end (wgpu's OpenGL and GLES
/// backends) targets with them. Each lacks some built-ins later versions have, such as
/// `mix` on integer or boolean vectors (GLSL 4.50).
const NAGA_GLSL_VERSIONS: [naga::back::glsl::Version; 2] = [
    naga::back::glsl::Version::Desktop(430),
    naga::back::glsl::Version::Embedded {
        version: 310,
        is_webgl: false,
    },
];

/// Ok if every check is, else every error: a check of several files reports each one
/// that fails.
pub(crate) fn all_ok(checks: Vec<anyhow::Result<()>>) -> anyhow::Result<()> {
    let errors: Vec<String> = checks
        .into_iter()
        .filter_map(|r| r.err().map(|e| format!("{e:#}")))
        .collect();
    if errors.is_empty() {
        Ok(())
    } else {
        Err(anyhow!("{}", errors.join("\n")))
    }
}

/// naga's GLSL back end on a WGSL include: the include, with an empty compute entry point,
/// written by naga as each of [`NAGA_GLSL_VERSIONS`] with every function (not only those
/// the entry point calls), each named by its version (the name a diagnostic gives), for
/// glslang to check. This is the GLSL a user of the WGSL include gets on wgpu's OpenGL
/// backend; naga writes it without checking it.
pub fn naga_glsl_sources(include: &str) -> anyhow::Result<Vec<(String, String)>> {
    use naga::back::glsl;
    let entry = "unitpack_include_check";
    let source = format!("{include}\n@compute @workgroup_size(1)\nfn {entry}() {{}}\n");
    let (module, info) = naga_wgsl_module(&source)?;
    let pipeline = glsl::PipelineOptions {
        shader_stage: naga::ShaderStage::Compute,
        entry_point: entry.into(),
        multiview: None,
    };
    NAGA_GLSL_VERSIONS
        .into_iter()
        .map(|version| {
            let options = glsl::Options {
                version,
                writer_flags: glsl::WriterFlags::INCLUDE_UNUSED_ITEMS,
                ..glsl::Options::default()
            };
            let mut text = String::new();
            glsl::Writer::new(
                &mut text,
                &module,
                &info,
                &options,
                &pipeline,
                naga::proc::BoundsCheckPolicies::default(),
            )
            .and_then(|mut w| w.write())
            .map_err(|e| anyhow!("naga's GLSL back end, {version}: {e}"))?;
            let name = format!("naga-glsl-{}", version.to_string().replace(' ', "-"));
            Ok((name, text))
        })
        .collect()
}

/// naga: parses GLSL as a compute shader and validates it.
pub fn naga_glsl(source: &str) -> anyhow::Result<()> {
    let options = naga::front::glsl::Options::from(naga::ShaderStage::Compute);
    let module = naga::front::glsl::Frontend::default()
        .parse(&options, source)
        .map_err(|e| anyhow!("naga GLSL parse error:\n{}", e.emit_to_string(source)))?;
    validate(&module, "GLSL", source).map(drop)
}
