//! The `unitpack` command line: list, gen, generate, encode, decode, verify.

mod generate;
mod stream;

use crate::codecs::{FAMILIES, Spec};
use crate::emit::{DEFAULT_PREFIX, Lang, validate_prefix};
use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use std::path::PathBuf;

pub use generate::{gen_text, generate, write_atomic};

#[derive(Parser)]
#[command(
    name = "unitpack",
    version,
    about = "Compact unit-vector (normal) codecs for WGSL, GLSL and HLSL, bit-exact with a Rust model"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand)]
pub enum Command {
    /// List every codec: bit sizes, domain, precise encoder, options and source document.
    List,
    /// Print the include for one or more specs.
    ///
    /// SPEC is NAME[BITS][p][:key=value,...]: `oct24p` (precise encoder), `hemioct16`,
    /// `snorm8x3`, `stereo_scaled16:scale=1.7777`, `oct24:layout=rgb8`, `snorm12x2`.
    Gen {
        #[arg(required = true)]
        specs: Vec<String>,
        #[arg(long, value_enum)]
        lang: Lang,
        /// Prefix of every function name (WGSL has no preprocessor to avoid clashes).
        #[arg(long, default_value = DEFAULT_PREFIX)]
        prefix: String,
        /// Write to FILE (atomically) instead of stdout.
        #[arg(long, value_name = "FILE")]
        out: Option<PathBuf>,
    },
    /// Write every codec × language into DIR/<lang>/<id>.<lang>.
    Generate {
        #[arg(long, default_value = "generated")]
        out: PathBuf,
        /// Write nothing; exit non-zero and name every file that would change.
        #[arg(long)]
        check: bool,
    },
    /// Encode vectors read from stdin (`x y z` per line) to hex codes, one per line.
    Encode { spec: String },
    /// Decode hex codes read from stdin (one per line) to `x y z` lines.
    Decode { spec: String },
    /// Prove emitted code bit-exact: static checks (naga, glslang, spirv-val) and
    /// execution on the Vulkan CPU adapter (lavapipe), compared as raw bits with the model.
    Verify {
        /// Specs to verify (default: all).
        specs: Vec<String>,
        /// Languages to verify (default: all).
        #[arg(long, value_enum)]
        lang: Vec<Lang>,
    },
}

pub fn parse_specs(specs: &[String]) -> Result<Vec<Spec>> {
    specs
        .iter()
        .map(|s| s.parse::<Spec>().map_err(anyhow::Error::from))
        .collect()
}

pub fn run(cli: Cli) -> Result<i32> {
    match cli.command {
        Command::List => {
            print!("{}", list_text());
            Ok(0)
        }
        Command::Gen {
            specs,
            lang,
            prefix,
            out,
        } => {
            validate_prefix(&prefix).map_err(anyhow::Error::msg)?;
            let specs = parse_specs(&specs)?;
            let text = generate::gen_text(&specs, lang, &prefix);
            match out {
                Some(path) => write_atomic(&path, text.as_bytes())?,
                None => print!("{text}"),
            }
            Ok(0)
        }
        Command::Generate { out, check } => generate(&out, check),
        Command::Encode { spec } => {
            let spec: Spec = spec.parse()?;
            stream::run(&spec, true)
        }
        Command::Decode { spec } => {
            let spec: Spec = spec.parse()?;
            stream::run(&spec, false)
        }
        Command::Verify { specs, lang } => {
            let specs = if specs.is_empty() {
                Spec::all()
            } else {
                parse_specs(&specs)?
            };
            let langs = if lang.is_empty() {
                Lang::ALL.to_vec()
            } else {
                lang
            };
            let report =
                crate::verify::run(&specs, &langs, true).context("verification could not run")?;
            print!("{}", report.table());
            Ok(if report.all_passed() { 0 } else { 1 })
        }
    }
}

/// The `list` table: each family with the specs a user types.
pub fn list_text() -> String {
    let mut s = format!(
        "{:<14} {:<11} {:<8} {}\n",
        "codec", "domain", "precise", "source"
    );
    for f in FAMILIES {
        let c = f.info();
        let domain = c.domain.map_or("-", |d| d.name());
        let precise = if c.precise { "yes" } else { "no" };
        s.push_str(&format!(
            "{:<14} {:<11} {:<8} {}\n",
            c.name, domain, precise, c.source
        ));
        s.push_str(&format!("{:<14} {}\n", "", c.title));
        let specs: Vec<String> = c.spellings().into_iter().map(|s| s.0).collect();
        let p = if c.precise { " (add p: precise)" } else { "" };
        s.push_str(&format!("{:<14} specs: {}{p}\n", "", specs.join(", ")));
        for o in c.options {
            s.push_str(&format!("{:<14} option {}\n", "", o.usage()));
        }
    }
    s
}
