//! `gen`: one include for the given specs, on stdout, in a file, or one file per language
//! in a directory.

use super::atomic::AtomicFile;
use super::output;
use crate::codecs::Spec;
use crate::emit::{DEFAULT_PREFIX, Lang, render};
use crate::quality::{self, ErrorStats};
use anyhow::{Context, Result, bail};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Samples behind the error figures printed in doc comments. Fewer than the accuracy
/// tests use (2^20), so that generating everything stays well under a second.
pub const DOC_SAMPLES: usize = 1 << 16;

/// Error statistics of every spec, measured in parallel (deterministic: fixed seed).
pub fn stats_for(specs: &[Spec]) -> Vec<Option<ErrorStats>> {
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(specs.len().max(1));
    let per = specs.len().div_ceil(threads).max(1);
    let mut out = vec![None; specs.len()];
    std::thread::scope(|s| {
        for (o, sp) in out.chunks_mut(per).zip(specs.chunks(per)) {
            s.spawn(move || {
                for (o, spec) in o.iter_mut().zip(sp) {
                    *o = quality::measure(spec, DOC_SAMPLES);
                }
            });
        }
    });
    out
}

/// The include for `specs` (duplicates dropped: one name, one definition).
pub fn gen_text(specs: &[Spec], lang: Lang, prefix: &str) -> String {
    let mut unique: Vec<Spec> = Vec::new();
    for s in specs {
        if !unique.iter().any(|u| u.id() == s.id()) {
            unique.push(s.clone());
        }
    }
    let specs = &unique[..];
    let stats = stats_for(specs);
    let ids: Vec<String> = specs.iter().map(|s| s.to_string()).collect();
    let prefix_arg = if prefix == DEFAULT_PREFIX {
        String::new()
    } else {
        format!(" --prefix {prefix}")
    };
    let cmd = format!("unitpack gen {} --lang {lang}{prefix_arg}", ids.join(" "));
    let pairs: Vec<_> = specs.iter().cloned().zip(stats).collect();
    render(&pairs, lang, prefix, &cmd)
}

/// Where `gen` writes.
pub struct Target<'a> {
    pub out: Option<&'a Path>,
    /// File name stem in directory mode (default: the spec ids joined by `-`).
    pub name: Option<&'a str>,
    pub force: bool,
}

/// Whether `--out` names a directory: it ends in `/`, it is one, or several languages
/// need one file each.
fn is_dir_target(out: &Path, langs: usize) -> bool {
    let s = out.as_os_str().to_string_lossy();
    langs > 1 || s.ends_with('/') || s.ends_with(std::path::MAIN_SEPARATOR) || out.is_dir()
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
pub fn run(specs: &[Spec], langs: &[Lang], prefix: &str, target: Target) -> Result<i32> {
    let mut unique: Vec<Lang> = Vec::new();
    for l in langs {
        if !unique.contains(l) {
            unique.push(*l);
        }
    }
    let langs = &unique[..];
    let Some(out) = target.out else {
        let [lang] = langs else {
            bail!(
                "--lang {} writes one file per language: add --out DIR/",
                langs.iter().map(|l| l.ext()).collect::<Vec<_>>().join(",")
            );
        };
        output::print(&gen_text(specs, *lang, prefix))?;
        return Ok(0);
    };
    if !is_dir_target(out, langs.len()) {
        if target.name.is_some() {
            bail!(
                "--name names the files written into a directory: make --out a directory (end it with /)"
            );
        }
        let mut f = AtomicFile::create(out, target.force)?;
        f.write_all(gen_text(specs, langs[0], prefix).as_bytes())
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
        f.write_all(gen_text(specs, *lang, prefix).as_bytes())
            .with_context(|| format!("cannot write {}", path.display()))?;
        staged.push(f);
    }
    for f in staged {
        f.commit()?;
    }
    Ok(0)
}
