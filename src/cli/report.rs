//! `report`: the HTML report of the catalogue into a folder, with a progress bar on a
//! terminal while the maps are measured.

use crate::choice::catalogue::Catalogue;
use crate::report::UserSample;
use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::Path;
use std::time::Instant;

/// Writes the report into `dir`; returns the summary line for stdout.
/// The report of the catalogue, or with `sample` (`report --sample FILE`) of every spec's
/// errors over that file's vectors, beside their density maps, and of every frame spec's
/// over its tangent frames where it is a glTF asset that has them.
pub fn run(dir: &Path, sample: Option<&Path>) -> Result<String> {
    let start = Instant::now();
    let mut catalogue = Catalogue::load();
    let mut shown = None;
    if let Some(path) = sample {
        let (vectors, frames) = super::sample::read_with_frames(path)?;
        catalogue = super::sample::remeasure(&catalogue, |_| true, &vectors);
        let frames_seeded = match frames {
            Ok(frames) => {
                catalogue = super::sample::remeasure_frames(&catalogue, &frames);
                None
            }
            Err(why) => Some(format!("{why:#}")),
        };
        shown = Some(UserSample {
            file: path.display().to_string(),
            density: crate::report::maps::density(&vectors.vectors),
            frames_seeded,
        });
    }
    let bar = if std::io::stderr().is_terminal() {
        let bar = ProgressBar::new(catalogue.specs.len() as u64);
        bar.set_style(
            ProgressStyle::with_template("report: measuring maps {bar:30} {pos}/{len} ({elapsed})")
                .expect("a valid template"),
        );
        bar
    } else {
        ProgressBar::hidden()
    };
    let files = crate::report::render(&catalogue, shown.as_ref(), &|| bar.inc(1))?;
    bar.finish_and_clear();
    let n = crate::report::write(dir, &files)?;
    Ok(format!(
        "wrote {} ({n} files: index.html and a page per family) in {:.1} s\n",
        dir.join("index.html").display(),
        start.elapsed().as_secs_f64()
    ))
}
