//! `gen`: one include for the given specs, on stdout, in a file, or one file per language
//! in a directory.

use super::output;
use crate::codecs::Spec;
use crate::emit::Lang;
use crate::generator::Generator;
use crate::support::atomic::AtomicFile;
use anyhow::{Context, Result, bail};
use std::io::Write;
use std::path::{Path, PathBuf};

/// What `gen --lang` writes: an include in one of the four languages, or a spec's WESL
/// module.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum GenLang {
    Wgsl,
    Glsl,
    Hlsl,
    /// C99, also valid C++: headers for CPU asset pipelines.
    C,
    /// One spec's WESL module, its functions named by their own names (imported as
    /// `unitpack::<id>`), as `generate` writes into wesl/.
    Wesl,
}

impl GenLang {
    /// The include language, or `None` for a WESL module.
    pub fn lang(self) -> Option<Lang> {
        match self {
            GenLang::Wgsl => Some(Lang::Wgsl),
            GenLang::Glsl => Some(Lang::Glsl),
            GenLang::Hlsl => Some(Lang::Hlsl),
            GenLang::C => Some(Lang::C),
            GenLang::Wesl => None,
        }
    }
    /// The `--lang` value.
    pub fn name(self) -> &'static str {
        self.lang().map_or("wesl", Lang::name)
    }
    /// The extension of a file written into a directory.
    fn ext(self) -> &'static str {
        self.lang().map_or("wesl", Lang::ext)
    }
}

/// The WESL module of the one spec in `specs`, whose header names the `gen` command that
/// writes it again.
fn wesl_text(specs: &[Spec], prefix: &str) -> Result<String> {
    let [spec] = specs else {
        bail!(
            "a WESL module holds one spec (imported as unitpack::<id>): give one spec for --lang wesl, or run generate for every module"
        );
    };
    if prefix != crate::emit::DEFAULT_PREFIX {
        bail!(
            "a WESL module's functions are named by their own names (the module path names the spec): --prefix does not apply to --lang wesl"
        );
    }
    let m = crate::measure::measure(
        std::slice::from_ref(spec),
        Some(crate::generator::DOC_SAMPLES),
    )
    .remove(0);
    Ok(crate::emit::render_wesl(
        &m,
        &format!("unitpack gen {spec} --lang wesl"),
    ))
}

/// The include for `specs` (duplicates dropped: one name, one definition).
pub fn gen_text(specs: &[Spec], lang: Lang, prefix: &str) -> String {
    gen_text_with(specs, lang, prefix, None).expect("a validated prefix renders")
}

/// [`gen_text`] with a WGSL `#define_import_path`: the library's [`Generator`] renders it.
pub fn gen_text_with(
    specs: &[Spec],
    lang: Lang,
    prefix: &str,
    import_path: Option<&str>,
) -> Result<String> {
    let mut g = Generator::new()
        .specs(specs.iter().cloned())
        .lang(lang)
        .prefix(prefix);
    if let Some(p) = import_path {
        g = g.wgsl_import_path(p);
    }
    Ok(g.render(lang)?)
}

/// Where `gen` writes.
pub struct Target<'a> {
    pub out: Option<&'a Path>,
    /// File name stem in directory mode (default: the spec ids joined by `-`).
    pub name: Option<&'a str>,
    pub force: bool,
    /// WGSL `#define_import_path`.
    pub import_path: Option<&'a str>,
}

/// Whether `--out` names a directory: it ends in `/`, it is one, or several languages
/// need one file each.
fn is_dir_target(out: &Path, langs: usize) -> bool {
    langs > 1 || ends_in_separator(out) || out.is_dir()
}

/// Whether the path as typed ends in `/` (the user's way of saying "a directory").
fn ends_in_separator(out: &Path) -> bool {
    let s = out.as_os_str().to_string_lossy();
    s.ends_with('/') || s.ends_with(std::path::MAIN_SEPARATOR)
}

/// The languages as `--lang` takes them: `wgsl,glsl`.
fn lang_list(langs: &[GenLang]) -> String {
    langs.iter().map(|l| l.name()).collect::<Vec<_>>().join(",")
}

fn check_name(name: &str) -> Result<()> {
    let ok = !name.is_empty()
        && name != "."
        && name != ".."
        && !name.contains(['/', '\\', '\0'])
        && !name.starts_with('.');
    if !ok {
        bail!("invalid --name '{name}': give a file name stem without '/' or a leading '.'");
    }
    Ok(())
}

/// Runs `gen`: one language to stdout or a file; any number into a directory as
/// `DIR/<name>.<ext>`, all written or (on an error before the first rename) none.
pub fn run(specs: &[Spec], langs: &[GenLang], prefix: &str, target: Target) -> Result<i32> {
    let mut unique: Vec<GenLang> = Vec::new();
    for l in langs {
        if !unique.contains(l) {
            unique.push(*l);
        }
    }
    let langs = &unique[..];
    let text = |lang: GenLang| match lang.lang() {
        Some(lang) => gen_text_with(specs, lang, prefix, target.import_path),
        None => wesl_text(specs, prefix),
    };
    // `--out -` is standard output, as no --out is.
    let Some(out) = target.out.filter(|o| !output::is_stdout(o)) else {
        let [lang] = langs else {
            bail!(
                "--lang {} writes one file per language: add --out DIR/",
                lang_list(langs)
            );
        };
        output::print(&text(*lang)?)?;
        return Ok(0);
    };
    if langs.len() > 1 && !ends_in_separator(out) && !out.is_dir() && out.extension().is_some() {
        // `--lang wgsl,glsl --out x.txt` would otherwise make a directory named x.txt.
        let dir = out.with_extension("");
        bail!(
            "--lang {} writes one file per language into a directory, and {} names a file; \
             give a directory (--out {}/) or one language",
            lang_list(langs),
            out.display(),
            dir.display()
        );
    }
    if !is_dir_target(out, langs.len()) {
        if target.name.is_some() {
            bail!(
                "--name names the files written into a directory: make --out a directory (end it with /)"
            );
        }
        let mut f = AtomicFile::create(out, target.force)?;
        f.write_all(text(langs[0])?.as_bytes())
            .with_context(|| format!("cannot write {}", out.display()))?;
        f.commit()?;
        return Ok(0);
    }
    let stem = match target.name {
        Some(n) => {
            check_name(n)?;
            n.to_string()
        }
        None => {
            let mut ids: Vec<String> = Vec::new();
            for s in specs {
                if !ids.contains(&s.id()) {
                    ids.push(s.id());
                }
            }
            ids.join("-")
        }
    };
    // Stage every file before renaming any, so that an unwritable target leaves none.
    let mut staged = Vec::new();
    for lang in langs {
        let path: PathBuf = out.join(format!("{stem}.{}", lang.ext()));
        let mut f = AtomicFile::create(&path, target.force)?;
        f.write_all(text(*lang)?.as_bytes())
            .with_context(|| format!("cannot write {}", path.display()))?;
        staged.push(f);
    }
    for f in staged {
        f.commit()?;
    }
    Ok(0)
}
