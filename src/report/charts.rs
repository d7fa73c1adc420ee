//! The report's charts, drawn by plotters' SVG backend and inlined into the pages.
//! Text is laid out with plotters' own estimate (no font files), so the same figures give
//! the same SVG on every machine.

use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::prelude::*;

/// A chart point: `(x, y, label)`, the label being what its SVG `<title>` names (a spec
/// id).
pub type Point = (f64, f64, String);

/// One series of points: its name, colour and points.
pub struct Series {
    pub name: &'static str,
    pub colour: RGBColor,
    pub points: Vec<Point>,
}

/// The series' colours, by kind.
pub const SPHERE: RGBColor = RGBColor(31, 119, 180);
pub const HEMISPHERE: RGBColor = RGBColor(214, 39, 40);

const SIZE: (u32, u32) = (560, 380);

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

/// The range of `values`, widened by a margin: 5% of the span (at least ½) on a linear
/// axis (fitted to the data, not to zero), a factor of 1.5 on a logarithmic one.
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
        let pad = ((hi - lo) * 0.05).max(0.5);
        (lo - pad, hi + pad)
    }
}

/// A number with `digits` significant digits, trailing zeros dropped, in scientific
/// notation outside `[1e-3, 1e5)`: `0.25`, `1500`, `1e-4` (never `9.999999999999999e-5`).
fn significant(v: f64, digits: usize) -> String {
    let a = v.abs();
    if a == 0.0 {
        return "0".into();
    }
    let trim = |t: String| {
        if t.contains('.') {
            t.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            t
        }
    };
    if !(1e-3..1e5).contains(&a) {
        let t = format!("{v:.prec$e}", prec = digits - 1);
        let (m, e) = t.split_once('e').unwrap_or((&t, "0"));
        return format!("{}e{e}", trim(m.to_string()));
    }
    let decimals = (digits as i32 - 1 - a.log10().floor() as i32).max(0) as usize;
    trim(format!("{v:.decimals$}"))
}

/// A tick label: three significant digits.
pub fn tick(v: f64) -> String {
    significant(v, 3)
}

/// The points no other point beats on both axes (lower is better on each), by x; of
/// points at the same place, the first id.
pub fn pareto(points: &[(f64, f64, String)]) -> Vec<(f64, f64, String)> {
    let mut sorted: Vec<&(f64, f64, String)> = points.iter().collect();
    sorted.sort_by(|a, b| {
        a.0.total_cmp(&b.0)
            .then(a.1.total_cmp(&b.1))
            .then(a.2.cmp(&b.2))
    });
    let mut front: Vec<(f64, f64, String)> = Vec::new();
    for p in sorted {
        if front.last().is_none_or(|l| p.1 < l.1) {
            front.push(p.clone());
        }
    }
    front
}

/// A scatter chart, each axis linear or logarithmic. Every point carries an SVG `<title>`
/// (plotters draws no per-element title, so the chart's circles, which are the points in
/// the order drawn, are given theirs afterwards); each series' Pareto front is drawn as a
/// line and its points labelled. No legend is drawn over the data: the page says what the colours
/// are ([`legend_html`]).
pub fn scatter(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    log_x: bool,
    log_y: bool,
    series: &[Series],
) -> Result<String> {
    let shown = |p: &&(f64, f64, String)| {
        p.0.is_finite() && p.1.is_finite() && (!log_x || p.0 > 0.0) && (!log_y || p.1 > 0.0)
    };
    let all: Vec<(f64, f64, String)> = series
        .iter()
        .flat_map(|s| s.points.iter().filter(shown).cloned())
        .collect();
    let (x0, x1) = range(all.iter().map(|p| p.0), log_x);
    let (y0, y1) = range(all.iter().map(|p| p.1), log_y);
    // One front per series: a hemisphere codec does not compete with a sphere codec.
    let fronts: Vec<(RGBColor, Vec<Point>)> = series
        .iter()
        .map(|s| {
            let shown: Vec<Point> = s.points.iter().filter(shown).cloned().collect();
            (s.colour, pareto(&shown))
        })
        .collect();
    let fmt = |v: &f64| tick(*v);
    let text = svg(|root| {
        let mut b = ChartBuilder::on(root);
        b.caption(title, ("sans-serif", 18))
            .margin(12)
            .margin_right(24)
            .x_label_area_size(40)
            .y_label_area_size(72);
        // The four axis kinds are four chart types; one body draws them all.
        macro_rules! body {
            ($chart:expr) => {{
                let mut chart = $chart.map_err(err)?;
                chart
                    .configure_mesh()
                    .x_desc(x_desc)
                    .y_desc(y_desc)
                    .x_label_formatter(&fmt)
                    .y_label_formatter(&fmt)
                    .draw()
                    .map_err(err)?;
                for s in series {
                    let c = s.colour;
                    chart
                        .draw_series(
                            s.points
                                .iter()
                                .filter(shown)
                                .map(|p| Circle::new((p.0, p.1), 3, c.mix(0.7).filled())),
                        )
                        .map_err(err)?;
                }
                for (c, front) in &fronts {
                    chart
                        .draw_series(LineSeries::new(
                            front.iter().map(|p| (p.0, p.1)),
                            c.mix(0.6),
                        ))
                        .map_err(err)?;
                    chart
                        .draw_series(front.iter().map(|p| {
                            EmptyElement::at((p.0, p.1))
                                + Text::new(p.2.clone(), (5, -12), ("sans-serif", 11))
                        }))
                        .map_err(err)?;
                }
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
    })?;
    titled(&text, &all)
}

/// `svg` with each `<circle .../>`, in order, given the `<title>` of the point drawn.
fn titled(svg: &str, points: &[(f64, f64, String)]) -> Result<String> {
    let mut out = String::with_capacity(svg.len() + points.len() * 64);
    let mut rest = svg;
    let mut names = points.iter();
    while let Some(at) = rest.find("<circle") {
        let end = rest[at..]
            .find("/>")
            .ok_or_else(|| anyhow!("an unclosed circle in the chart"))?;
        let p = names
            .next()
            .ok_or_else(|| anyhow!("the chart has more circles than points"))?;
        out.push_str(&rest[..at + end]);
        out.push_str(&format!(
            "><title>{}: {}, {}</title></circle>",
            super::escape(&p.2),
            significant(p.0, 6),
            significant(p.1, 6)
        ));
        rest = &rest[at + end + 2..];
    }
    if names.next().is_some() {
        return Err(anyhow!("the chart drew fewer circles than it has points"));
    }
    out.push_str(rest);
    Ok(out)
}

/// What a chart's colours and line mean, as HTML under it.
pub fn legend_html(series: &[(&str, RGBColor)]) -> String {
    let mut s = String::from("<figcaption class=\"chart-legend\">");
    for (name, c) in series {
        s.push_str(&format!(
            "<span><span class=\"dot\" style=\"background:#{:02X}{:02X}{:02X}\"></span> {name}</span> ",
            c.0, c.1, c.2
        ));
    }
    s.push_str("<span>lines: each kind's Pareto front (nothing of its kind is better on both axes), labelled; hover a point for its spec</span></figcaption>");
    s
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
