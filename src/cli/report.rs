//! `report`: the HTML report of the catalogue into a folder, with a progress bar on a
//! terminal while the maps are measured.

use crate::choice::catalogue::Catalogue;
use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::Path;
use std::time::Instant;

/// Writes the report into `dir`; returns the summary line for stdout.
pub fn run(dir: &Path) -> Result<String> {
    let start = Instant::now();
    let catalogue = Catalogue::load();
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
    let files = crate::report::render(&catalogue, &|| bar.inc(1))?;
    bar.finish_and_clear();
    let n = crate::report::write(dir, &files)?;
    Ok(format!(
        "wrote {} ({n} files: index.html and a page per family) in {:.1} s\n",
        dir.join("index.html").display(),
        start.elapsed().as_secs_f64()
    ))
}
