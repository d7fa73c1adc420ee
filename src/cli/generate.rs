//! `gen` and `generate`: include files on stdout, in a file, or for the whole catalogue.

use crate::codecs::Spec;
use crate::emit::{DEFAULT_PREFIX, Lang, render};
use anyhow::{Context, Result, bail};
use std::io::Write;
use std::path::{Path, PathBuf};

pub use crate::generator::stats_for;

/// The include for `specs` (duplicates dropped: one name, one definition).
pub fn gen_text(specs: &[Spec], lang: Lang, prefix: &str) -> String {
    crate::generator::Generator::new()
        .specs(specs.iter().cloned())
        .lang(lang)
        .prefix(prefix)
        .render(lang)
        .expect("parsed specs and a validated prefix render")
}

/// Writes through a temporary file in the same directory and renames it over `path`, so
/// readers never see a half-written file and a failure leaves the old file intact.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut tmp = tempfile::NamedTempFile::new_in(dir).with_context(|| {
        format!(
            "cannot write {}: cannot create a file in {}",
            path.display(),
            dir.display()
        )
    })?;
    tmp.write_all(bytes)
        .with_context(|| format!("cannot write {}", path.display()))?;
    // Temporary files are private (0600); give the result the old file's mode, or the
    // usual 0644 for a new one.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(path).map_or(0o644, |m| m.permissions().mode() & 0o7777);
        tmp.as_file()
            .set_permissions(std::fs::Permissions::from_mode(mode))
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    tmp.persist(path)
        .map_err(|e| e.error)
        .with_context(|| format!("cannot write {}", path.display()))?;
    Ok(())
}

/// Every generated file: relative path → contents.
pub fn catalogue_files() -> Vec<(PathBuf, String)> {
    let specs = Spec::all();
    let stats = stats_for(&specs);
    let mut files = Vec::new();
    for lang in Lang::ALL {
        for (spec, st) in specs.iter().zip(&stats) {
            // The same command `gen` writes, so that running it reproduces the file.
            let cmd = format!("unitpack gen {spec} --lang {lang}");
            let text = render(&[(spec.clone(), *st)], lang, DEFAULT_PREFIX, &cmd);
            files.push((
                PathBuf::from(lang.name()).join(format!("{}.{}", spec.id(), lang.ext())),
                text,
            ));
        }
    }
    files
}

/// Files in `out`'s language folders that the catalogue no longer produces.
fn extra_files(out: &Path, files: &[(PathBuf, String)]) -> Vec<PathBuf> {
    let mut extra = Vec::new();
    for lang in Lang::ALL {
        let Ok(rd) = std::fs::read_dir(out.join(lang.name())) else {
            continue;
        };
        for e in rd.flatten() {
            let rel = PathBuf::from(lang.name()).join(e.file_name());
            let ours = rel.extension().is_some_and(|x| x == lang.ext());
            if ours && !files.iter().any(|(r, _)| *r == rel) {
                extra.push(out.join(rel));
            }
        }
    }
    extra.sort();
    extra
}

pub fn generate(out: &Path, check: bool) -> Result<i32> {
    let files = catalogue_files();
    let extra = extra_files(out, &files);
    if check {
        let mut stale = Vec::new();
        for (rel, text) in &files {
            let p = out.join(rel);
            match std::fs::read_to_string(&p) {
                Ok(cur) if cur == *text => {}
                Ok(_) => stale.push(format!("changed: {}", p.display())),
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                    stale.push(format!("missing: {}", p.display()))
                }
                Err(e) => stale.push(format!("unreadable: {} ({e})", p.display())),
            }
        }
        let out_of_date = stale.len();
        stale.extend(extra.iter().map(|p| format!("extra: {}", p.display())));
        if stale.is_empty() {
            println!("{} files in {} are up to date", files.len(), out.display());
            return Ok(0);
        }
        for s in &stale {
            println!("{s}");
        }
        println!(
            "{out_of_date} of {} generated files are out of date, {} files are extra; run `unitpack generate` (it also removes extra files)",
            files.len(),
            extra.len()
        );
        return Ok(1);
    }
    if files.is_empty() {
        bail!("nothing to generate");
    }
    for lang in Lang::ALL {
        let d = out.join(lang.name());
        std::fs::create_dir_all(&d).with_context(|| format!("cannot create {}", d.display()))?;
    }
    for (rel, text) in &files {
        write_atomic(&out.join(rel), text.as_bytes())?;
    }
    for p in &extra {
        std::fs::remove_file(p).with_context(|| format!("cannot remove stale {}", p.display()))?;
        println!("removed {}", p.display());
    }
    println!("wrote {} files to {}", files.len(), out.display());
    Ok(0)
}
