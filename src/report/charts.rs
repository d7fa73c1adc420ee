//! The report's charts, drawn by plotters' SVG backend and inlined into the pages.
//! Text is laid out with plotters' own estimate (no font files), so the same figures give
//! the same SVG on every machine.

use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::prelude::*;

/// One series of points: its name, colour and `(x, y)` points.
pub struct Series {
    pub name: &'static str,
    pub colour: RGBColor,
    pub points: Vec<(f64, f64)>,
}

/// The series' colours, by kind.
pub const SPHERE: RGBColor = RGBColor(31, 119, 180);
pub const HEMISPHERE: RGBColor = RGBColor(214, 39, 40);

const SIZE: (u32, u32) = (560, 360);

fn err(e: impl std::fmt::Display) -> anyhow::Error {
    anyhow!("cannot draw a chart: {e}")
}

/// Draws into an SVG string of [`SIZE`].
fn svg(draw: impl FnOnce(&DrawingArea<SVGBackend, Shift>) -> Result<()>) -> Result<String> {
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        draw(&root)?;
        root.present().map_err(err)?;
    }
    Ok(text)
}

/// The range of `values`, widened by a margin; for a log axis, by a factor.
fn range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !lo.is_finite() {
        return if log { (1e-3, 1.0) } else { (0.0, 1.0) };
    }
    if log {
        (lo / 1.5, hi * 1.5)
    } else {
        let pad = ((hi - lo) * 0.05).max(1.0);
        ((lo - pad).min(0.0), hi + pad)
    }
}

/// A scatter chart: x linear, y linear or logarithmic.
pub fn scatter(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    log_x: bool,
    log_y: bool,
    series: &[Series],
) -> Result<String> {
    let all = || series.iter().flat_map(|s| s.points.iter().copied());
    let (x0, x1) = range(all().map(|p| p.0), log_x);
    let (y0, y1) = range(all().map(|p| p.1), log_y);
    svg(|root| {
        let mut b = ChartBuilder::on(root);
        b.caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(64);
        // The four axis kinds are four chart types; one body draws them all.
        macro_rules! body {
            ($chart:expr) => {{
                let mut chart = $chart.map_err(err)?;
                chart
                    .configure_mesh()
                    .x_desc(x_desc)
                    .y_desc(y_desc)
                    .draw()
                    .map_err(err)?;
                for s in series {
                    let c = s.colour;
                    chart
                        .draw_series(
                            s.points
                                .iter()
                                .filter(|p| p.0.is_finite() && p.1.is_finite())
                                .map(|&p| Circle::new(p, 3, c.mix(0.7).filled())),
                        )
                        .map_err(err)?
                        .label(s.name)
                        .legend(move |(x, y)| Circle::new((x, y), 4, c.filled()));
                }
                chart
                    .configure_series_labels()
                    .border_style(BLACK)
                    .background_style(WHITE.mix(0.9))
                    .draw()
                    .map_err(err)?;
            }};
        }
        match (log_x, log_y) {
            (false, false) => body!(b.build_cartesian_2d(x0..x1, y0..y1)),
            (false, true) => body!(b.build_cartesian_2d(x0..x1, (y0..y1).log_scale())),
            (true, false) => body!(b.build_cartesian_2d((x0..x1).log_scale(), y0..y1)),
            (true, true) => {
                body!(b.build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale()))
            }
        }
        Ok(())
    })
}

/// Bins of a histogram.
pub const BINS: usize = 40;

/// A histogram of `errors` (degrees) in [`BINS`] bins from 0 to their maximum.
pub fn histogram(title: &str, errors: &[f64]) -> Result<String> {
    let top = errors.iter().fold(0f64, |a, &b| a.max(b)).max(1e-9);
    let mut counts = [0u32; BINS];
    for &e in errors {
        let i = ((e / top) * BINS as f64) as usize;
        counts[i.min(BINS - 1)] += 1;
    }
    let most = counts.iter().copied().max().unwrap_or(1).max(1);
    svg(|root| {
        let mut chart = ChartBuilder::on(root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(64)
            .build_cartesian_2d(0f64..top, 0u32..most + most / 10 + 1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("round-trip error (degrees)")
            .y_desc("vectors")
            .draw()
            .map_err(err)?;
        let w = top / BINS as f64;
        chart
            .draw_series(counts.iter().enumerate().map(|(i, &c)| {
                let x = i as f64 * w;
                Rectangle::new([(x, 0), (x + w, c)], SPHERE.mix(0.8).filled())
            }))
            .map_err(err)?;
        Ok(())
    })
}
