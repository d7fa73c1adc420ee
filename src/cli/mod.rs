//! The `unitpack` command line: list, choose, report, gen, generate, encode, decode,
//! verify, convert-normal-map.
//!
//! Output never goes through `print!` (it panics on a closed or full stdout): see
//! [`output`]. Files are replaced atomically and only when they are the user's to replace:
//! see [`crate::support::atomic`] and `manifest`.

mod choose;
mod convert;
pub mod figure_cache;
mod generate;
mod gltf;
pub mod grammar;
mod include;
mod list;
mod manifest;
pub mod output;
mod report;
pub mod runtime_dir;
mod sample;
mod stream;
mod verify;

use crate::api::RoundTrip;
use crate::codecs::Spec;
use crate::emit::{DEFAULT_PREFIX, Lang, validate_prefix};
use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use std::io::{BufRead, BufReader, Write};
use std::path::PathBuf;

pub use crate::support::atomic::{AtomicFile, write_atomic, write_atomic_with};
pub use generate::{generate, generate_with};
pub use include::gen_text;
pub use list::{GRAMMAR, list_json, list_text, list_text_of};
pub use manifest::{HEADER, MANIFEST};
pub use stream::{Direction, Format, MAX_LINE, filter, transcode};

/// Help of every SPEC argument: the grammar (src/codecs/spec.rs) with examples.
const SPEC_HELP: &str = "A codec spec: NAME[BITS][p][:key=value,...]. BITS is the total \
size (oct16) or, for snorm, bits per component (snorm8x3); p selects the precise encoder \
(oct24p); options follow a colon (oct24:layout=rgb8, stereo_scaled16:scale=1.7777). \
Case does not matter. `unitpack list` shows every family, size and option";

const STREAM_FORMATS: &str = "\
Formats (--format, or --input-format/--output-format for one side):
  text    vectors: one `x y z` line, three f32 numbers (1, -0.5, 1e-3, inf, nan);
          a finite number beyond the f32 range (1e39) is an error. Tangent-frame
          specs (qtangent64, godot_axis_angle) read and write frames instead: one
          `nx ny nz tx ty tz w` line, the normal, the tangent and the bitangent's sign.
          codes: one per line, 0x followed by hex digits (0x7f) or decimal digits (127);
          nothing else (no sign, 0b, 0o or _). A code with bits set above the spec's
          width (oct16: 16 bits) is an error. Codes are written as 0x + one hex digit
          per 4 bits (8 for 32-bit specs, 12 for snorm16x3, 24 for float32x3),
          vectors as shortest round-trip decimals.
          Output line N answers input line N: blank lines and lines starting with #
          are copied unchanged. A UTF-8 byte-order mark at the start and \\r\\n line
          ends are accepted; a line may be at most 1 MiB.
  binary  raw little-endian records: a vector is 12 bytes (3 × f32), a frame 28
          (7 × f32), a code one little-endian u32 per word: 4 bytes, 8 above 32 bits
          (snorm16x3, float16x3, qtangent64), 12 above 64 (float32x3). Blank and
          comment lines of text input produce no record.

Errors: the first bad line or record ends the run with a one-line error naming it
(exit status 2). With --out FILE nothing is written (FILE is replaced atomically, only
on success); on stdout, the output for every line before the bad one has been written.
Memory use stays bounded whatever the input size.";

#[derive(Parser)]
#[command(
    name = "unitpack",
    version,
    about = "Compact unit-vector (normal) codecs for WGSL, GLSL and HLSL, bit-exact with a Rust model",
    after_help = "Exit status: 0 success, 1 verify or generate --check found a difference, 2 error. \
A closed stdout (`unitpack list | head -1`) ends a command quietly."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand)]
pub enum Command {
    /// List every codec: domain, precise encoder, the specs to type, options and source.
    List {
        /// Print JSON instead of the table.
        #[arg(long)]
        json: bool,
    },
    /// Rank the specs that meet constraints: the figures of `list`, best first.
    ///
    /// Constraints apply in this order: --bits, --format, --domain, --filterable,
    /// --max-encode-alu, --max-decode-alu, --portable; when nothing is left, the error
    /// names the constraint that emptied the list and what was left before it. Each row
    /// is followed by a line saying why the spec is there.
    ///
    /// --use gbuffer|vertex|asset|normal-map|frame ranks for what the normals are for:
    /// each spec is stored where that use stores it (within --bits, a texel's or a
    /// vertex's), and scored as error × (1 + ALU/100) with the instructions that use runs
    /// per pixel or per vertex; the line under each row names what decided it and what
    /// the next row trades.
    Choose {
        #[command(flatten)]
        query: crate::choice::query::Query,
        /// What to rank by, best first (default: max); `--use` ranks by its own score.
        #[arg(long, value_enum)]
        by: Option<crate::choice::choose::Order>,
        /// Print JSON instead of the table.
        #[arg(long)]
        json: bool,
        /// Show at most N specs (0: all).
        #[arg(long, value_name = "N", default_value_t = 10)]
        limit: usize,
        /// Measure the errors over FILE's vectors instead of the seeded uniform ones: a
        /// glTF asset's normals (.gltf or .glb, every primitive's NORMAL), a tangent-space
        /// normal map (.png, RGB8 or RGB16, n·½ + ½) or vectors as encode
        /// reads them (x y z lines; raw little-endian f32 triples if FILE ends in .bin,
        /// .f32 or .raw). With --use frame, FILE's tangent frames: a glTF asset's
        /// primitives with both NORMAL and TANGENT, or frames as encode reads them (nx ny
        /// nz tx ty tz w lines; raw records of seven f32). Above 2^20 items a seeded
        /// uniform subsample is measured, and the figures say so.
        #[arg(long, value_name = "FILE")]
        sample: Option<PathBuf>,
    },
    /// Write an HTML report of the catalogue that a browser opens from disk: trade-off
    /// charts, every spec's figures, and a page per family with sphere error maps, error
    /// histograms, filtering figures, guarantees, formats and signatures.
    ///
    /// DIR must be new, empty, or hold an earlier report (its .unitpack-report manifest);
    /// only the files that report wrote are replaced, each atomically.
    Report {
        #[arg(long, value_name = "DIR", default_value = "unitpack-report")]
        out: PathBuf,
        /// Every spec's errors over FILE's vectors instead of the seeded uniform ones (a
        /// glTF asset, a normal map or a vector stream, as `choose --sample` reads them),
        /// and the sample's density maps beside each spec's error maps.
        #[arg(long, value_name = "FILE")]
        sample: Option<PathBuf>,
    },
    /// Print the include for one or more specs.
    ///
    /// With one language the include goes to stdout or to --out FILE. With several (or
    /// with --out naming a directory: existing, or ending in /) each language is written
    /// to DIR/NAME.<lang>, NAME being --name or the spec ids joined by '-':
    /// `unitpack gen oct16 hemioct24p --lang wgsl,glsl --out shaders/` writes
    /// shaders/oct16-hemioct24p.wgsl and shaders/oct16-hemioct24p.glsl.
    ///
    /// Files are replaced atomically; missing directories are created; a symlink's target
    /// is replaced and the link kept; a read-only file is replaced only with --force.
    ///
    /// The proven bounds and error figures the include states are cached as for generate.
    Gen {
        #[arg(required = true, value_name = "SPEC", help = SPEC_HELP)]
        specs: Vec<String>,
        /// Languages, comma-separated (wgsl,glsl,hlsl,c, or wesl: one spec's WESL
        /// module); several need --out DIR/.
        #[arg(long, value_enum, value_delimiter = ',', required = true)]
        lang: Vec<include::GenLang>,
        /// Prefix of every function name (WGSL has no preprocessor to avoid clashes).
        #[arg(long, default_value = DEFAULT_PREFIX)]
        prefix: String,
        /// Write to FILE, or into a directory (see above), instead of stdout (`-`: stdout).
        #[arg(long, value_name = "FILE|DIR/")]
        out: Option<PathBuf>,
        /// File name stem of the files written into a directory.
        #[arg(long)]
        name: Option<String>,
        /// Replace read-only files too.
        #[arg(long)]
        force: bool,
        /// Start WGSL output with `#define_import_path PATH` (naga_oil, Bevy), e.g.
        /// unitpack::normals.
        #[arg(long, value_name = "PATH")]
        wgsl_import_path: Option<String>,
    },
    /// Write every codec × language into DIR/<lang>/<id>.<ext> (C: DIR/c/<id>.h), every
    /// WGSL include again as a WESL module DIR/wesl/<id>.wesl, and the lookup tables some
    /// codecs read into DIR/lut/<name>.png and .bin.
    ///
    /// Also writes DIR/.unitpack-manifest, the list of files it wrote. A file at a path
    /// it writes is replaced only if it starts with "// Generated by unitpack" (a table:
    /// only if it still has the contents hash the manifest recorded), or with --force. It
    /// removes a file only if all three hold: an earlier run listed it in
    /// DIR/.unitpack-manifest, it is no longer in the catalogue, and it still starts with
    /// "// Generated by unitpack" (a table: still has its recorded hash). Every other file
    /// in DIR/wgsl, DIR/glsl, DIR/hlsl, DIR/c, DIR/wesl and DIR/lut is kept and reported as kept. Every file is prepared before any is replaced, so an
    /// unwritable folder leaves the tree as it was. Unchanged files are not rewritten.
    ///
    /// The proven bounds and error figures the includes state are kept for the next run
    /// of the same executable in $UNITPACK_CACHE_DIR/figures.txt (default: the platform's
    /// cache folder, ~/.cache/unitpack on Linux; set empty: no cache).
    ///
    /// On a terminal, stderr shows what it is doing and, at the end, what it wrote and how
    /// long it took; piped, only the report (stdout) is printed.
    Generate {
        #[arg(long, value_name = "DIR", default_value = "generated")]
        out: PathBuf,
        /// Write nothing; exit 1 and name every file that would change or be removed.
        #[arg(long)]
        check: bool,
        /// Also replace files at catalogue paths that unitpack did not write, and read-only
        /// files. Never makes generate remove anything.
        #[arg(long)]
        force: bool,
    },
    /// Rewrite a glTF asset's normals and tangent frames with specs: IN and OUT are both .gltf or both .glb.
    ///
    /// With gltf_normal8 or gltf_normal16 every mesh primitive's NORMAL becomes a normalized
    /// BYTE or SHORT accessor (KHR_mesh_quantization, declared used and required): any
    /// viewer loads it. With any other vector spec the codes go to a new attribute
    /// _UNITPACK_<ID> (UNSIGNED_SHORT VEC2 for a 32-bit code, VEC4 for 64 bits) beside the
    /// original NORMAL, for a renderer that decodes with the emitted functions. Everything
    /// else is kept; the codes are appended (to the GLB's BIN chunk, or as a data: URI
    /// buffer), and the error over the asset's normals is printed. --tangents FRAME_SPEC
    /// encodes each primitive's NORMAL and TANGENT as tangent frames into _UNITPACK_<ID>
    /// the same way, both attributes kept, and prints their errors. OUT is written
    /// atomically, beside IN for a .gltf (its buffers and images are relative paths); an
    /// existing OUT is replaced only with --force.
    Gltf {
        /// The asset to read (.gltf with its buffers, or .glb).
        #[arg(value_name = "IN")]
        input: PathBuf,
        /// The asset to write.
        #[arg(value_name = "OUT")]
        output: PathBuf,
        /// The vector spec the normals are encoded with.
        #[arg(long, value_name = "SPEC", required_unless_present = "tangents")]
        normals: Option<String>,
        /// The tangent-frame spec each primitive's NORMAL and TANGENT are encoded with,
        /// as a new attribute _UNITPACK_<ID> beside them.
        #[arg(long, value_name = "SPEC")]
        tangents: Option<String>,
        /// Replace an existing OUT (read-only too).
        #[arg(long)]
        force: bool,
    },
    /// Convert a tangent-space normal map between its conventional form and a texel layout.
    ///
    /// --to SPEC reads a conventional map (PNG, RGB8 or RGB16, each component n·½ + ½;
    /// an alpha channel is ignored) and writes the RGBA8 texels of SPEC, a texel layout
    /// (`xy16:layout=dxt5nm`, `hemioct16p_rg`, …: `unitpack list` shows the layout option).
    /// --from SPEC reads such texels (RGBA8 PNG) and writes the conventional map (RGB8, or
    /// RGB16 with --depth 16). Each texel goes through the CPU encoder or decoder, which
    /// computes what the emitted shader functions compute. OUT is written atomically; it
    /// may not be IN, and an existing OUT is replaced only with --force (so swapped
    /// arguments cannot destroy a map); OUT `-` writes the PNG to stdout. A progress bar
    /// shows on a terminal for maps of a million texels or more.
    ///
    /// A map whose channels show it already holds texels (B = 0 in every texel, as rg,
    /// dxt5nm and xra store them; R = 1 in every texel, as rxgb; R = G = B, as latc) is
    /// refused by --to: its vectors are not normals.
    #[command(group = clap::ArgGroup::new("direction").required(true).args(["to", "from"]))]
    ConvertNormalMap {
        /// The map to read (PNG).
        #[arg(value_name = "IN")]
        input: PathBuf,
        /// The PNG file to write (`-`: stdout).
        #[arg(value_name = "OUT")]
        output: PathBuf,
        /// Write the texels of this layout spec.
        #[arg(long, value_name = "SPEC")]
        to: Option<String>,
        /// Read the texels of this layout spec and write the conventional map.
        #[arg(long, value_name = "SPEC")]
        from: Option<String>,
        /// Bits per channel of the conventional map --from writes: 8 (the default) or 16.
        #[arg(long, value_parser = ["8", "16"])]
        depth: Option<String>,
        /// With an xra spec and --to: write the DXT1 texel (x in R, A = 1) instead of the
        /// DXT5 one (x in A, R = 1).
        #[arg(long)]
        dxt1: bool,
        /// Replace an existing OUT (read-only too).
        #[arg(long)]
        force: bool,
    },
    /// Encode vectors (or tangent frames) read from stdin to codes, one output line (or
    /// record) per input.
    #[command(after_help = STREAM_FORMATS)]
    Encode(StreamArgs),
    /// Decode codes read from stdin to vectors (or tangent frames), one output line (or
    /// record) per input.
    #[command(after_help = STREAM_FORMATS)]
    Decode(StreamArgs),
    /// Move codes read from stdin to another spec: each decoded by --from and encoded by
    /// --to, one output line (or record) per input; the angle each vector moved is
    /// summed up on stderr.
    #[command(after_help = STREAM_FORMATS)]
    Transcode {
        #[arg(long, value_name = "SPEC", help = format!("The spec of the codes read. {SPEC_HELP}"))]
        from: String,
        /// The spec of the codes written, in the same grammar.
        #[arg(long, value_name = "SPEC")]
        to: String,
        #[command(flatten)]
        io: StreamIo,
    },
    /// Prove emitted code bit-exact: static checks (naga, glslang, spirv-val, literals
    /// read back) and execution on the Vulkan CPU adapter (lavapipe) through naga, glslang
    /// and Slang, the same SPIR-V on SwiftShader, WGSL through WebGPU (Tint) and GLSL ES
    /// through WebGL 2 (ANGLE) in headless Chromium, on the OpenGL driver and through the C
    /// compilers, compared as raw bits with the model.
    Verify {
        /// Specs to verify (default: all).
        #[arg(value_name = "SPEC", help = format!("{SPEC_HELP} (default: every spec)"))]
        specs: Vec<String>,
        /// Languages to verify, comma-separated (default: all).
        #[arg(long, value_enum, value_delimiter = ',')]
        lang: Vec<Lang>,
        /// Print the report as JSON instead of the table.
        #[arg(long)]
        json: bool,
        /// The Vulkan adapter that runs the shader paths: `cpu` is lavapipe, where the
        /// canonical arithmetic is proven; `gpu` is this machine's own GPU, which the
        /// graphics APIs allow to round, flush and fuse differently: mismatches there are
        /// what this GPU changes, and for float outputs the report gives the largest
        /// difference, to hold against the bound in each function's doc comment.
        #[arg(long, value_enum, default_value_t = crate::verify::gpu::Adapter::Cpu)]
        adapter: crate::verify::gpu::Adapter,
        /// Instead of running the emitted code, evaluate the model under every deviation
        /// the graphics APIs allow (division and sqrt within their ULP bounds, fused
        /// multiply-adds, denormal flushing, lost signs of zero, excess precision,
        /// reassociation, either-neighbour rounding, contraction into comparisons and
        /// products), one class at a time and fma+reassoc+contract together, with 3
        /// seeds, 3 per-site choices, both worst-case ends and the deviation taken
        /// everywhere (denorm: SwiftShader's flushing), over 2^14 inputs per
        /// function. Reports changed outputs per function and
        /// class; exits 1 if any packed code changes under a class the portability
        /// guarantee covers (div, sqrt, fma, denorm, zero).
        #[arg(long)]
        portable: bool,
        /// List up to N mismatches of each function per path instead of 5, e.g. to keep
        /// what a GPU changed as regression data. Float outputs also give their largest
        /// difference.
        #[arg(long, value_name = "N", default_value_t = crate::verify::FIRST)]
        keep: usize,
        /// Instead of verifying here, write DIR/index.html: one self-contained page that
        /// runs the specs' WGSL through WebGPU on the GPU of whatever browser opens it
        /// (Metal, D3D12, Vulkan) and shows each function's result, with a button to save
        /// it as `--json` does.
        #[arg(long, value_name = "DIR")]
        web: Option<std::path::PathBuf>,
    },
}

#[derive(clap::Args)]
pub struct StreamArgs {
    #[arg(value_name = "SPEC", help = SPEC_HELP)]
    pub spec: String,
    #[command(flatten)]
    pub io: StreamIo,
}

/// Where a stream verb reads and writes, and in which format.
#[derive(clap::Args)]
pub struct StreamIo {
    /// Format of input and output (see below).
    #[arg(long, value_enum, default_value = "text")]
    pub format: Format,
    /// Format of the input, if it differs from --format.
    #[arg(long, value_enum)]
    pub input_format: Option<Format>,
    /// Format of the output, if it differs from --format.
    #[arg(long, value_enum)]
    pub output_format: Option<Format>,
    /// Write to FILE atomically (only if every input line is good) instead of stdout
    /// (`-`: stdout).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Replace a read-only FILE too.
    #[arg(long)]
    pub force: bool,
}

pub fn parse_specs(specs: &[String]) -> Result<Vec<Spec>> {
    specs
        .iter()
        .map(|s| s.parse::<Spec>().map_err(anyhow::Error::from))
        .collect()
}

pub fn run(cli: Cli) -> Result<i32> {
    match cli.command {
        Command::List { json } => {
            output::print(&if json { list_json() } else { list_text() })?;
            Ok(0)
        }
        Command::Choose {
            query,
            by,
            json,
            limit,
            sample,
        } => {
            if let Some(d) = query.filterable
                && !(d.is_finite() && d > 0.0)
            {
                anyhow::bail!("--filterable takes a positive number of degrees, not {d}");
            }
            output::print(&choose::run(&query, by, json, limit, sample.as_deref())?)?;
            Ok(0)
        }
        Command::Report { out, sample } => {
            if output::is_stdout(&out) {
                anyhow::bail!("report writes a folder of files: name a folder, not -");
            }
            output::print(&report::run(&out, sample.as_deref())?)?;
            Ok(0)
        }
        Command::Gen {
            specs,
            lang,
            prefix,
            out,
            name,
            force,
            wgsl_import_path,
        } => {
            validate_prefix(&prefix).map_err(anyhow::Error::msg)?;
            if wgsl_import_path.is_some() && !lang.contains(&include::GenLang::Wgsl) {
                anyhow::bail!(
                    "--wgsl-import-path starts WGSL output, and --lang {} writes none: add wgsl to --lang or leave the option out",
                    lang.iter().map(|l| l.name()).collect::<Vec<_>>().join(",")
                );
            }
            let specs = parse_specs(&specs)?;
            let target = include::Target {
                out: out.as_deref(),
                name: name.as_deref(),
                force,
                import_path: wgsl_import_path.as_deref(),
            };
            with_figure_cache(|| include::run(&specs, &lang, &prefix, target))
        }
        Command::Generate { out, check, force } => {
            if output::is_stdout(&out) {
                anyhow::bail!(
                    "generate writes a folder of files, which standard output (--out -) cannot hold: name a folder"
                );
            }
            with_figure_cache(|| generate_with(&out, check, force))
        }
        Command::Gltf {
            input,
            output,
            normals,
            tangents,
            force,
        } => {
            output::print(&gltf::run(
                &input,
                &output,
                normals.as_deref(),
                tangents.as_deref(),
                force,
            )?)?;
            Ok(0)
        }
        Command::ConvertNormalMap {
            input,
            output,
            to,
            from,
            depth,
            dxt1,
            force,
        } => {
            // clap's `requires` would yield to the group that makes --to and --from
            // exclusive, so these pairings are checked here.
            if depth.is_some() && from.is_none() {
                anyhow::bail!(
                    "--depth sets the conventional map --from writes; --to reads its depth from IN"
                );
            }
            if dxt1 && to.is_none() {
                anyhow::bail!("--dxt1 chooses the texel --to writes; --from reads either");
            }
            let dir = match (&to, &from) {
                (Some(spec), _) => convert::Direction::To(spec, dxt1),
                (None, Some(spec)) => {
                    convert::Direction::From(spec, depth.as_deref() == Some("16"))
                }
                (None, None) => unreachable!("clap requires one of --to and --from"),
            };
            convert::run(&input, &output, dir, force)?;
            Ok(0)
        }
        Command::Encode(a) => {
            let spec = a.spec.parse()?;
            run_stream(&a.io, |i, o, f| {
                filter(&spec, Direction::Encode, f.0, f.1, i, o).map(drop)
            })
        }
        Command::Decode(a) => {
            let spec = a.spec.parse()?;
            run_stream(&a.io, |i, o, f| {
                filter(&spec, Direction::Decode, f.0, f.1, i, o).map(drop)
            })
        }
        Command::Transcode { from, to, io } => {
            let specs: (Spec, Spec) = (from.parse()?, to.parse()?);
            let mut error = RoundTrip::default();
            run_stream(&io, |i, o, f| {
                error = transcode((&specs.0, &specs.1), f.0, f.1, i, o)?;
                Ok(())
            })?;
            // Codes are counted, not lines: in text, comments and blank lines have none.
            match error.records {
                0 => eprintln!("no codes moved from {} to {}", specs.0, specs.1),
                n => eprintln!(
                    "{n} code{} moved from {} to {}: each vector moved by {:.6}° on average, \
                     at most {:.6}° (code {})",
                    if n == 1 { "" } else { "s" },
                    specs.0,
                    specs.1,
                    error.mean(),
                    error.max,
                    error.max_at
                ),
            }
            Ok(0)
        }
        Command::Verify {
            specs,
            lang,
            json,
            adapter,
            portable,
            keep,
            web,
        } => {
            let specs = if specs.is_empty() {
                Spec::all()
            } else {
                parse_specs(&specs)?
            };
            if let Some(dir) = web {
                return with_figure_cache(|| {
                    let page = crate::verify::web::write(&dir, &specs)?;
                    output::print(&format!("{}\n", page.display()))?;
                    Ok(0)
                });
            }
            if portable {
                let report = crate::measure::portability::run(
                    &specs,
                    &crate::measure::portability::cli_classes(),
                    &crate::measure::portability::Options::cli(),
                );
                output::print(&if json { report.json() } else { report.table() })?;
                return Ok(if report.guarantees_hold() { 0 } else { 1 });
            }
            let langs = if lang.is_empty() {
                Lang::ALL.to_vec()
            } else {
                lang
            };
            let report = crate::verify::run_on(&specs, &langs, true, adapter, keep)
                .context("verification could not run")?;
            output::print(&if json {
                verify::report_json(&report)
            } else {
                report.table()
            })?;
            Ok(if report.all_passed() { 0 } else { 1 })
        }
    }
}

/// Runs a verb whose files state proven bounds and error figures with the figures an
/// earlier run of this executable saved, and saves what it adds ([`figure_cache`]).
fn with_figure_cache(verb: impl FnOnce() -> Result<i32>) -> Result<i32> {
    let cache = figure_cache::open();
    let result = verb();
    if let Some(c) = cache {
        c.save();
    }
    result
}

/// `encode`/`decode`/`transcode`: stdin to stdout or to an atomically replaced file,
/// through `run(input, output, (input format, output format))`.
fn run_stream(
    a: &StreamIo,
    mut run: impl FnMut(&mut dyn BufRead, &mut dyn Write, (Format, Format)) -> Result<()>,
) -> Result<i32> {
    let formats = (
        a.input_format.unwrap_or(a.format),
        a.output_format.unwrap_or(a.format),
    );
    let stdin = std::io::stdin();
    let mut input = BufReader::with_capacity(64 * 1024, stdin.lock());
    // `--out -` is standard output, as no --out is.
    match a.out.as_deref().filter(|p| !output::is_stdout(p)) {
        Some(path) => {
            let mut file = AtomicFile::create(path, a.force)?;
            run(&mut input, &mut file, formats)
                .map_err(|e| name_output(e, &path.display().to_string()))?;
            file.commit()?;
        }
        None => {
            let mut out = output::stdout();
            let result = run(&mut input, &mut out, formats);
            // The output for the lines before a bad one is written either way, as the
            // help says.
            let flushed = out.flush();
            result.map_err(|e| name_output(e, "to stdout"))?;
            flushed.context("cannot write to stdout")?;
        }
    }
    Ok(0)
}

/// Rewrites a [`stream::WriteError`] as `cannot write <name>: <cause>`, keeping the
/// `io::Error` in the chain (a closed stdout is recognized by it).
fn name_output(e: anyhow::Error, name: &str) -> anyhow::Error {
    match e.downcast::<stream::WriteError>() {
        Ok(w) => anyhow::Error::new(w.0).context(format!("cannot write {name}")),
        Err(e) => e,
    }
}
