//! `generate`: the whole catalogue as `DIR/<lang>/<id>.<lang>` and as WESL modules
//! `DIR/wesl/<id>.wesl`, the lookup tables some specs read as `DIR/lut/<stem>.png` and
//! `.bin`, plus the manifest that lets a later run
//! prune only what it wrote (see [`super::manifest`]; a table is known by the hash the
//! manifest records for it, having no header).
//!
//! Nothing the user wrote is ever replaced or removed without `--force`, and `--force`
//! only lets a catalogue path be replaced; it never makes `generate` remove a file.
//!
//! The report (what was written, kept, removed) goes to stdout, the same wherever it
//! goes. On a terminal, stderr also shows what `generate` is doing while it works (a
//! first run proves every bound and measures every figure, which takes a while) and, at
//! the end, what it wrote and how long it took: see [`Progress`].

use super::manifest::{self, HEADER, MANIFEST};
use super::output;
use crate::codecs::Spec;
use crate::codecs::core::spec::{Table, TableFormat};
use crate::emit::{DEFAULT_PREFIX, Lang, render, render_wesl};
use crate::generator::DOC_SAMPLES;
use crate::measure::figures::Measured;
use crate::support::atomic::AtomicFile;
use anyhow::{Context, Result, bail};
use indicatif::{ProgressBar, ProgressStyle};
use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::io::{self, IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Every generated file: relative path → contents. The includes, the WESL modules, and
/// the lookup tables
/// of the specs that read one (`lut/<stem>.png`, and the same texels as raw bytes in
/// `lut/<stem>.bin`).
fn catalogue_files(progress: &Progress) -> Result<Vec<(PathBuf, Vec<u8>)>> {
    let specs = Spec::all();
    progress.stage(format!(
        "measuring the error figures of {} specs and proving their decoders' bounds",
        specs.len()
    ));
    let measured = crate::measure::measure(&specs, Some(DOC_SAMPLES));
    progress.stage(format!(
        "rendering {} includes and {} WESL modules",
        specs.len() * Lang::ALL.len(),
        specs.len()
    ));
    // Every include and module on every core, in the order written here.
    let jobs: Vec<(Option<Lang>, &Measured)> = Lang::ALL
        .into_iter()
        .map(Some)
        .chain([None])
        .flat_map(|lang| measured.iter().map(move |m| (lang, m)))
        .collect();
    let mut files = crate::support::par::map(&jobs, |&(lang, m)| match lang {
        Some(lang) => {
            let spec = &m.spec;
            // The same command `gen` writes, so that running it reproduces the file.
            let cmd = format!("unitpack gen {spec} --lang {lang}");
            let text = render(std::slice::from_ref(m), lang, DEFAULT_PREFIX, &cmd);
            (
                PathBuf::from(lang.name()).join(format!("{}.{}", spec.id(), lang.ext())),
                text.into_bytes(),
            )
        }
        // The WGSL includes again as WESL modules, imported as `unitpack::<stem>`.
        None => (
            PathBuf::from(manifest::WESL).join(format!("{}.wesl", m.spec.id())),
            render_wesl(m, "unitpack generate").into_bytes(),
        ),
    });
    files.push((PathBuf::from(manifest::INDEX), index(&specs).into_bytes()));
    // A precise spec reads its fast spec's tables: each file is written once.
    let mut stems = std::collections::HashSet::new();
    let tables = specs.iter().flat_map(|s| s.family().tables(s));
    for table in tables.filter(|t| stems.insert(t.stem.clone())) {
        let dir = PathBuf::from(manifest::TABLES);
        if table.format == TableFormat::Unorm8 {
            files.push((dir.join(format!("{}.png", table.stem)), png(&table)?));
        }
        files.push((dir.join(format!("{}.bin", table.stem)), table.bytes));
    }
    Ok(files)
}

/// `README.md` of the output folder: every spec with its family, bits, what it encodes,
/// model file, and its file in each language, so that a reader of the folder finds the
/// include for a spec without knowing the naming rule.
fn index(specs: &[Spec]) -> String {
    let mut s = format!(
        "{}\n\n# unitpack's generated includes\n\n\
         One include per spec and language (`<lang>/<spec>.<ext>`), the WGSL again as a WESL \
         module (`wesl/<spec>.wesl`, imported as `unitpack::<spec>`), and the lookup tables \
         some specs read (`lut/`). `unitpack list` describes every family and option; each \
         include's header says what its functions guarantee.\n\n\
         | spec | family | bits | encodes | WGSL | GLSL | HLSL | C | WESL | tables |\n\
         |---|---|---:|---|---|---|---|---|---|---|\n",
        manifest::INDEX_HEADER
    );
    for spec in specs {
        let id = spec.id();
        let family = spec.family();
        let files: Vec<String> = Lang::ALL
            .iter()
            .map(|l| {
                format!(
                    "[{id}.{ext}]({dir}/{id}.{ext})",
                    dir = l.name(),
                    ext = l.ext()
                )
            })
            .chain([format!("[{id}.wesl]({}/{id}.wesl)", manifest::WESL)])
            .collect();
        let tables: Vec<String> = family
            .tables(spec)
            .iter()
            .map(|t| format!("`{}/{}.bin`", manifest::TABLES, t.stem))
            .collect();
        let _ = writeln!(
            s,
            "| `{spec}` | {} | {} | {} | {} | {} |",
            family.info().name,
            spec.bits(),
            family.takes().unwrap_or("-"),
            files.join(" | "),
            if tables.is_empty() {
                "-".to_string()
            } else {
                tables.join(", ")
            }
        );
    }
    s
}

/// A table as an 8-bit grayscale or RGBA PNG (deterministic for a given encoder version).
fn png(t: &Table) -> Result<Vec<u8>> {
    let color = match t.channels {
        1 => png::ColorType::Grayscale,
        _ => png::ColorType::Rgba,
    };
    crate::support::png_file::encode(t.width, t.height, color, png::BitDepth::Eight, &t.bytes)
        .with_context(|| format!("encoding {} as PNG", t.stem))
}

/// What is on disk at a path `generate` writes.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum State {
    Current,
    Missing,
    /// Ours (it has the header), with other contents.
    Changed,
    /// Not written by unitpack: no header. Replaced only with `--force`.
    Foreign,
    /// A directory or something else that is not a file: never replaced.
    NotAFile,
}

/// The state of `out/rel`, whose catalogue contents are `text`. A text file is ours when
/// it has the header (the manifest always is); a table, which has no header, when it
/// still has the hash the previous manifest recorded for it (`recorded`).
fn state_of(out: &Path, rel: &Path, text: &[u8], recorded: Option<u64>) -> Result<State> {
    let path = &out.join(rel);
    let cannot = || format!("cannot read {}", path.display());
    match std::fs::metadata(path) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(State::Missing),
        Err(e) => return Err(e).with_context(cannot),
        // Never opened: reading a FIFO would block.
        Ok(m) if !m.is_file() => return Ok(State::NotAFile),
        Ok(_) => {}
    }
    let cur = std::fs::read(path).with_context(cannot)?;
    let ours = if manifest::is_table_path(rel) {
        recorded.is_some_and(|h| manifest::hash(&cur) == h)
    } else {
        rel == Path::new(MANIFEST)
            || cur.starts_with(HEADER.as_bytes())
            || rel == Path::new(manifest::INDEX)
                && cur.starts_with(manifest::INDEX_HEADER.as_bytes())
    };
    Ok(if cur == text {
        State::Current
    } else if ours {
        State::Changed
    } else {
        State::Foreign
    })
}

/// Everything `generate` would do in `out`, worked out before anything is written.
struct Plan {
    /// The includes, the tables and the manifest (last), with their state on disk.
    files: Vec<(PathBuf, Vec<u8>, State)>,
    /// Files to remove: listed in the old manifest, not in the catalogue, with the header.
    prune: Vec<PathBuf>,
    /// Files left alone in the language folders, with the reason.
    kept: Vec<(PathBuf, &'static str)>,
}

fn plan(out: &Path, progress: &Progress) -> Result<Plan> {
    let mut files = catalogue_files(progress)?;
    progress.stage(format!("comparing with {}", out.display()));
    let listed = manifest::text(files.iter().map(|(p, b)| (p.as_path(), b.as_slice())));
    files.push((PathBuf::from(MANIFEST), listed.into_bytes()));
    let ours: BTreeSet<PathBuf> = files.iter().map(|(p, _)| p.clone()).collect();
    let old = manifest::read(out)
        .with_context(|| format!("cannot read {}", out.join(MANIFEST).display()))?;
    let mut prune = Vec::new();
    let mut kept = Vec::new();
    let folders = Lang::ALL
        .iter()
        .map(|l| l.name())
        .chain([manifest::WESL, manifest::TABLES]);
    for folder in folders {
        let dir = out.join(folder);
        let rd = match std::fs::read_dir(&dir) {
            Ok(rd) => rd,
            Err(e) if e.kind() == io::ErrorKind::NotFound => continue,
            Err(e) => return Err(e).with_context(|| format!("cannot list {}", dir.display())),
        };
        for e in rd {
            let e = e.with_context(|| format!("cannot list {}", dir.display()))?;
            let name = e.file_name();
            // Hidden files include other runs' temporary files.
            if name.to_string_lossy().starts_with('.') {
                continue;
            }
            let rel = PathBuf::from(folder).join(&name);
            if ours.contains(&rel) {
                continue;
            }
            let path = out.join(&rel);
            let why = if !path.is_file() {
                "not a file"
            } else if !old.contains_key(&rel) {
                "not in the manifest: unitpack generate did not write it"
            } else if manifest::is_table_path(&rel) {
                if manifest::is_recorded_table(&path, old[&rel]) {
                    prune.push(rel);
                    continue;
                }
                "listed in the manifest, but no longer the table generate wrote"
            } else {
                match manifest::has_header(&path) {
                    Ok(true) => {
                        prune.push(rel);
                        continue;
                    }
                    Ok(false) => "listed in the manifest, but it no longer has the unitpack header",
                    Err(_) => "unreadable",
                }
            };
            kept.push((rel, why));
        }
    }
    prune.sort();
    kept.sort();
    let files = files
        .into_iter()
        .map(|(rel, text)| {
            let recorded = old.get(&rel).copied().flatten();
            let state = state_of(out, &rel, &text, recorded)?;
            Ok((rel, text, state))
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(Plan { files, prune, kept })
}

/// A short list of paths for a one-line message.
fn some_paths(out: &Path, paths: &[&PathBuf]) -> String {
    let mut s: Vec<String> = paths
        .iter()
        .take(5)
        .map(|p| out.join(p).display().to_string())
        .collect();
    if paths.len() > 5 {
        s.push(format!("and {} more", paths.len() - 5));
    }
    s.join(", ")
}

/// `generate --out out [--check]`: see [`generate_with`]; never replaces files it did
/// not write.
pub fn generate(out: &Path, check: bool) -> Result<i32> {
    generate_with(out, check, false)
}

/// Writes (or with `check`, compares) the catalogue in `out`; `force` lets it replace
/// catalogue paths that hold files unitpack did not write. Returns the exit status.
pub fn generate_with(out: &Path, check: bool, force: bool) -> Result<i32> {
    let progress = Progress::start();
    let plan = plan(out, &progress)?;
    let mut report = String::new();
    for (rel, why) in &plan.kept {
        let _ = writeln!(report, "kept: {} ({why})", out.join(rel).display());
    }
    if check {
        return check_report(out, &plan, report, progress);
    }
    let bad: Vec<&PathBuf> = plan
        .files
        .iter()
        .filter(|f| f.2 == State::NotAFile)
        .map(|f| &f.0)
        .collect();
    if !bad.is_empty() {
        bail!(
            "nothing written: {} must be files, but are not (directories?)",
            some_paths(out, &bad)
        );
    }
    let foreign: Vec<&PathBuf> = plan
        .files
        .iter()
        .filter(|f| f.2 == State::Foreign)
        .map(|f| &f.0)
        .collect();
    if !foreign.is_empty() && !force {
        bail!(
            "nothing written: {} file(s) at paths generate writes lack the \"{HEADER}\" header (a table in lut/: the contents hash the manifest recorded), so unitpack did not write them: {}; move them away or pass --force",
            foreign.len(),
            some_paths(out, &foreign)
        );
    }
    // Stage every changed file before renaming any: an unwritable folder (or full disk)
    // fails here, and dropping the staged files leaves the tree as it was.
    let changed: Vec<&PathBuf> = plan
        .files
        .iter()
        .filter(|f| f.2 != State::Current)
        .map(|f| &f.0)
        .collect();
    progress.stage(format!("writing {} files", changed.len()));
    let mut staged = Vec::new();
    for (rel, text, state) in &plan.files {
        if *state == State::Current {
            continue;
        }
        let path = out.join(rel);
        let mut f = AtomicFile::create(&path, force).context("nothing written")?;
        f.write_all(text)
            .with_context(|| format!("nothing written: cannot write {}", path.display()))?;
        staged.push(f);
    }
    let written = staged.len();
    for f in staged {
        f.commit()?;
    }
    let mut failed = Vec::new();
    for rel in &plan.prune {
        let path = out.join(rel);
        match std::fs::remove_file(&path) {
            Ok(()) => {
                let _ = writeln!(report, "removed {}", path.display());
            }
            // Another `generate` running on the same folder removed it first.
            Err(e) if e.kind() == io::ErrorKind::NotFound => {}
            Err(e) => failed.push(format!("cannot remove {}: {e}", path.display())),
        }
    }
    let _ = writeln!(
        report,
        "{} files in {}: {written} written, {} already up to date",
        plan.files.len(),
        out.display(),
        plan.files.len() - written
    );
    progress.clear();
    output::print(&report)?;
    progress.summary(&if written == 0 {
        format!(
            "wrote nothing: all {} files in {} were up to date",
            plan.files.len(),
            out.display()
        )
    } else {
        let files = if written == 1 { "file" } else { "files" };
        format!("wrote {written} {files}: {}", some_paths(out, &changed))
    });
    if !failed.is_empty() {
        bail!("{}", failed.join("; "));
    }
    Ok(0)
}

/// `generate`'s words to a person watching it, on stderr, where stderr is a terminal:
/// while it works, a spinner naming the stage; at the end, one line saying what it wrote
/// and how long it took. Elsewhere (a pipe, a file, CI) nothing: the stdout report is
/// the same either way, so a script sees exactly what it saw before.
struct Progress {
    bar: ProgressBar,
    start: Instant,
    /// Whether stderr is a terminal.
    attended: bool,
}

impl Progress {
    fn start() -> Progress {
        if !io::stderr().is_terminal() {
            return Progress::hidden();
        }
        let bar = ProgressBar::new_spinner();
        bar.set_style(
            ProgressStyle::with_template("{spinner} generate: {msg} ({elapsed})")
                .expect("a valid template"),
        );
        bar.enable_steady_tick(Duration::from_millis(100));
        Progress {
            bar,
            start: Instant::now(),
            attended: true,
        }
    }

    /// Says nothing: stderr is not a terminal.
    fn hidden() -> Progress {
        Progress {
            bar: ProgressBar::hidden(),
            start: Instant::now(),
            attended: false,
        }
    }

    /// What `generate` is doing now.
    fn stage(&self, what: String) {
        self.bar.set_message(what);
    }

    /// Removes the spinner, so that the report on stdout is not drawn over.
    fn clear(&self) {
        self.bar.finish_and_clear();
    }

    /// The last line: `generate: <what> in 1.2 s`.
    fn summary(&self, what: &str) {
        if self.attended {
            let secs = self.start.elapsed().as_secs_f64();
            let _ = writeln!(io::stderr(), "generate: {what} in {secs:.1} s");
        }
    }
}

fn check_report(out: &Path, plan: &Plan, mut report: String, progress: Progress) -> Result<i32> {
    let mut stale = 0;
    for (rel, _, state) in &plan.files {
        let p = out.join(rel).display().to_string();
        let line = match state {
            State::Current => continue,
            State::Missing => format!("missing: {p}"),
            State::Changed => format!("changed: {p}"),
            State::Foreign => format!(
                "changed: {p} (not written by unitpack: generate replaces it only with --force)"
            ),
            State::NotAFile => format!("changed: {p} (not a file: generate cannot replace it)"),
        };
        stale += 1;
        let _ = writeln!(report, "{line}");
    }
    for rel in &plan.prune {
        let _ = writeln!(
            report,
            "extra: {} (generate removes it)",
            out.join(rel).display()
        );
    }
    let total = plan.files.len();
    let summary = format!("compared {total} files with {}", out.display());
    progress.clear();
    if stale == 0 && plan.prune.is_empty() {
        let _ = writeln!(report, "{total} files in {} are up to date", out.display());
        output::print(&report)?;
        progress.summary(&summary);
        return Ok(0);
    }
    let run = if plan.files.iter().any(|f| f.2 == State::Foreign) {
        "`unitpack generate --force` (it replaces files unitpack did not write)"
    } else {
        "`unitpack generate`"
    };
    let _ = writeln!(
        report,
        "{stale} of {total} generated files are out of date, {} files are extra; run {run}",
        plan.prune.len()
    );
    output::print(&report)?;
    progress.summary(&summary);
    Ok(1)
}
