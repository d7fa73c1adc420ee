//! The library a build script wants: choose specs, languages and names, then render or
//! write the includes. It needs no CLI and no GPU (`default-features = false`), errors are
//! typed, and files are written atomically.
//!
//! ```no_run
//! // build.rs
//! use unitpack::{Generator, Lang};
//!
//! fn main() -> Result<(), unitpack::GenerateError> {
//!     let out = std::path::PathBuf::from(std::env::var_os("OUT_DIR").unwrap());
//!     Generator::new()
//!         .spec("oct24p")
//!         .spec("hemioct16")
//!         .lang(Lang::Wgsl)
//!         .wgsl_import_path("unitpack::normals")
//!         .write_file(out.join("normals.wgsl"))?;
//!     Generator::new()
//!         .spec("oct24p")
//!         .lang(Lang::C)
//!         .write_file(out.join("normals.h"))?;
//!     Ok(())
//! }
//! ```

use crate::codecs::{Spec, SpecError};
use crate::emit::{DEFAULT_PREFIX, Lang, render_with, validate_prefix};
use std::path::{Path, PathBuf};

/// Samples behind the error figures printed in doc comments. Fewer than the accuracy
/// tests use (2^20), so that generating everything stays well under a second.
pub const DOC_SAMPLES: usize = 1 << 16;

/// Why a [`Generator`] could not render or write. Its `Debug` form is its message (see
/// the `impl`).
#[derive(thiserror::Error)]
pub enum GenerateError {
    #[error("invalid spec: {0}")]
    Spec(#[from] SpecError),
    #[error("{0}")]
    Prefix(String),
    #[error(
        "invalid WGSL import path '{0}': use identifiers separated by '::', e.g. unitpack::normals"
    )]
    ImportPath(String),
    #[error("no spec given: add at least one with .spec(\"oct16\")")]
    NoSpecs,
    #[error("{what} needs exactly one language, {count} chosen")]
    Languages { what: &'static str, count: usize },
    /// `source` names the path and what failed.
    #[error("{source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
}

/// The message, as `Display` gives it: a build script's `fn main() -> Result<(),
/// GenerateError>` (the pattern above) reports an error through `Debug`, and
/// `Error: invalid spec: oct has no 17-bit form; allowed sizes: 16, 20, 22, 24, 32` tells
/// its user what to fix where `Error: Spec(InvalidBits { codec: "oct", .. })` does not.
/// The variants remain for code to match on.
impl std::fmt::Debug for GenerateError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        std::fmt::Display::fmt(self, f)
    }
}

/// A spec as the caller gave it: text (parsed when rendering) or already parsed.
#[derive(Clone, Debug)]
pub enum SpecInput {
    Text(String),
    Parsed(Spec),
}

impl From<&str> for SpecInput {
    fn from(s: &str) -> SpecInput {
        SpecInput::Text(s.to_string())
    }
}
impl From<String> for SpecInput {
    fn from(s: String) -> SpecInput {
        SpecInput::Text(s)
    }
}
impl From<Spec> for SpecInput {
    fn from(s: Spec) -> SpecInput {
        SpecInput::Parsed(s)
    }
}

/// Builds includes: specs × languages, a name prefix and an optional WGSL import path.
#[derive(Clone, Debug)]
pub struct Generator {
    specs: Vec<SpecInput>,
    langs: Vec<Lang>,
    prefix: String,
    import_path: Option<String>,
    error_stats: bool,
}

impl Default for Generator {
    fn default() -> Self {
        Generator::new()
    }
}

impl Generator {
    /// No specs yet, no language, the default `unitpack_` prefix, error figures on.
    pub fn new() -> Generator {
        Generator {
            specs: Vec::new(),
            langs: Vec::new(),
            prefix: DEFAULT_PREFIX.to_string(),
            import_path: None,
            error_stats: true,
        }
    }
    /// Adds a spec (`"oct24p"`, `"oct24:layout=rgb8"`, or a parsed [`Spec`]).
    pub fn spec(mut self, spec: impl Into<SpecInput>) -> Generator {
        self.specs.push(spec.into());
        self
    }
    /// Adds several specs.
    pub fn specs<S: Into<SpecInput>>(mut self, specs: impl IntoIterator<Item = S>) -> Generator {
        self.specs.extend(specs.into_iter().map(Into::into));
        self
    }
    /// Adds a language.
    pub fn lang(mut self, lang: Lang) -> Generator {
        if !self.langs.contains(&lang) {
            self.langs.push(lang);
        }
        self
    }
    /// Adds several languages.
    pub fn langs(self, langs: impl IntoIterator<Item = Lang>) -> Generator {
        langs.into_iter().fold(self, Generator::lang)
    }
    /// The prefix of every name (default `unitpack_`).
    pub fn prefix(mut self, prefix: &str) -> Generator {
        self.prefix = prefix.to_string();
        self
    }
    /// Starts WGSL files with `#define_import_path PATH`, so that naga_oil (Bevy) users
    /// can `#import PATH::{unitpack_oct16_decode}`.
    pub fn wgsl_import_path(mut self, path: &str) -> Generator {
        self.import_path = Some(path.to_string());
        self
    }
    /// Whether doc comments carry measured round-trip error figures (on by default; off
    /// saves the measurement, about 2^16 encodes per spec).
    pub fn error_stats(mut self, on: bool) -> Generator {
        self.error_stats = on;
        self
    }

    /// The parsed specs, duplicates dropped (one name, one definition).
    pub fn parsed_specs(&self) -> Result<Vec<Spec>, GenerateError> {
        let mut out: Vec<Spec> = Vec::new();
        for s in &self.specs {
            let spec = match s {
                SpecInput::Text(t) => t.parse()?,
                SpecInput::Parsed(p) => p.clone(),
            };
            if !out.iter().any(|u| u.id() == spec.id()) {
                out.push(spec);
            }
        }
        if out.is_empty() {
            return Err(GenerateError::NoSpecs);
        }
        Ok(out)
    }

    fn check(&self) -> Result<(), GenerateError> {
        validate_prefix(&self.prefix).map_err(GenerateError::Prefix)?;
        if let Some(p) = &self.import_path {
            let ident = |s: &str| {
                s.chars()
                    .next()
                    .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
                    && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            };
            if !p.split("::").all(ident) {
                return Err(GenerateError::ImportPath(p.clone()));
            }
        }
        Ok(())
    }

    /// The include for `lang`.
    pub fn render(&self, lang: Lang) -> Result<String, GenerateError> {
        Ok(self.render_each(&[lang])?.remove(0))
    }

    /// The include for each of `langs`, the specs parsed, proven and measured once for
    /// all of them (the measurement of a search encoder takes a noticeable fraction of a
    /// second).
    fn render_each(&self, langs: &[Lang]) -> Result<Vec<String>, GenerateError> {
        self.check()?;
        let specs = self.parsed_specs()?;
        let samples = self.error_stats.then_some(DOC_SAMPLES);
        let measured = crate::measure::measure(&specs, samples);
        let ids: Vec<String> = specs.iter().map(|s| s.to_string()).collect();
        Ok(langs
            .iter()
            .map(|&lang| {
                let mut cmd = format!("unitpack gen {} --lang {lang}", ids.join(" "));
                if self.prefix != DEFAULT_PREFIX {
                    cmd.push_str(&format!(" --prefix {}", self.prefix));
                }
                let import = self.import_path.as_deref().filter(|_| lang == Lang::Wgsl);
                if let Some(p) = import {
                    cmd.push_str(&format!(" --wgsl-import-path {p}"));
                }
                render_with(&measured, lang, &self.prefix, &cmd, import)
            })
            .collect())
    }

    /// Writes the include of the one chosen language to `path`, atomically, creating
    /// its parent directories.
    pub fn write_file(&self, path: impl AsRef<Path>) -> Result<(), GenerateError> {
        let [lang] = self.langs[..] else {
            return Err(GenerateError::Languages {
                what: "write_file",
                count: self.langs.len(),
            });
        };
        let text = self.render(lang)?;
        write(path.as_ref(), text.as_bytes())
    }

    /// Writes `dir/{stem}.{ext}` for every chosen language; returns the paths written.
    pub fn write_dir(
        &self,
        dir: impl AsRef<Path>,
        stem: &str,
    ) -> Result<Vec<PathBuf>, GenerateError> {
        if self.langs.is_empty() {
            return Err(GenerateError::Languages {
                what: "write_dir",
                count: 0,
            });
        }
        let texts = self.render_each(&self.langs)?;
        let mut written = Vec::new();
        for (&lang, text) in self.langs.iter().zip(texts) {
            let path = dir.as_ref().join(format!("{stem}.{}", lang.ext()));
            write(&path, text.as_bytes())?;
            written.push(path);
        }
        Ok(written)
    }
}

/// Writes atomically with the CLI's policy ([`crate::support::atomic`]): a symlink's target is
/// replaced, parent directories are created, a read-only file is refused.
fn write(path: &Path, bytes: &[u8]) -> Result<(), GenerateError> {
    crate::support::atomic::write_atomic(path, bytes).map_err(|source| GenerateError::Io {
        path: path.to_path_buf(),
        source,
    })
}
