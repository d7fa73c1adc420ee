//! `report`: the whole catalogue's HTML report, its numbers held to `list --json`, its
//! folder policy, its determinism, and its pages opened in headless Chromium.

use crate::common::*;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

/// One report of the whole catalogue, written once for every test here, in the test
/// binary's folder under `target/` (a temporary folder in a static is never removed).
fn report() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("report-test");
        // The last run's report, if any: this test's own folder.
        let _ = std::fs::remove_dir_all(&dir);
        let out = dir.join("report");
        let r = ok(&["report", "--out", out.to_str().unwrap()]);
        assert!(r.stdout.contains("index.html"), "{r:?}");
        dir
    })
}

fn page(rel: &str) -> String {
    std::fs::read_to_string(report().join("report").join(rel))
        .unwrap_or_else(|e| panic!("the report has {rel}: {e}"))
}

#[test]
fn the_report_has_an_index_and_a_page_per_family_with_maps_and_charts() {
    let dir = report().join("report");
    let index = page("index.html");
    let list: Value = serde_json::from_str(&ok(&["list", "--json"]).stdout).unwrap();
    let mut families: Vec<&str> = list["specs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["family"].as_str().unwrap())
        .collect();
    families.dedup();
    for fam in &families {
        assert!(
            index.contains(&format!("href=\"family/{fam}.html\"")),
            "{fam}"
        );
        let p = page(&format!("family/{fam}.html"));
        assert!(p.contains("<svg"), "{fam}: a histogram");
        assert!(
            p.contains("_equirect.png") && p.contains("_octahedral.png"),
            "{fam}"
        );
    }
    // Five trade-off charts.
    assert_eq!(index.matches("<svg").count(), 5);
    // One colour scale on every family page.
    for fam in &families {
        let p = page(&format!("family/{fam}.html"));
        assert!(
            p.contains("≤ 0.001°")
                && p.contains("≥ 10°")
                && p.contains("One colour scale for every spec of every family"),
            "{fam}: the shared scale"
        );
    }
    for e in list["specs"].as_array().unwrap() {
        let id = e["spec"].as_str().unwrap();
        for view in ["equirect", "octahedral"] {
            let png = dir.join(format!("maps/{id}_{view}.png"));
            let bytes = std::fs::read(&png).unwrap_or_else(|_| panic!("{}", png.display()));
            assert!(bytes.starts_with(b"\x89PNG"), "{}", png.display());
        }
    }
}

/// Every number of the index's table is `list --json`'s, value for value.
#[test]
fn the_reports_numbers_equal_list_json() {
    let index = page("index.html");
    let list: Value = serde_json::from_str(&ok(&["list", "--json"]).stdout).unwrap();
    let specs = list["specs"].as_array().unwrap();
    let rows: Vec<&str> = index
        .lines()
        .filter(|l| l.starts_with("<tr data-spec="))
        .collect();
    assert_eq!(rows.len(), specs.len());
    for (row, e) in rows.iter().zip(specs) {
        let id = e["spec"].as_str().unwrap();
        assert!(row.starts_with(&format!("<tr data-spec=\"{id}\"")), "{row}");
        let v = values(row);
        let num = |i: usize| v[i].parse::<f64>().unwrap();
        assert_eq!(num(0), e["bits"].as_f64().unwrap(), "{id} bits");
        assert_eq!(num(1), e["mean"].as_f64().unwrap(), "{id} mean");
        assert_eq!(num(2), e["max"].as_f64().unwrap(), "{id} max");
        assert_eq!(num(3), e["alu"]["encode"].as_f64().unwrap(), "{id} encode");
        assert_eq!(num(4), e["alu"]["decode"].as_f64().unwrap(), "{id} decode");
        if let Some(b) = e["bounds"]["decode"].as_f64() {
            assert_eq!(num(5), b, "{id} bound");
        }
    }
    // A family page's figures too: oct16's mean.
    let oct = page("family/oct.html");
    let mean = specs.iter().find(|e| e["spec"] == "oct16").unwrap()["mean"]
        .as_f64()
        .unwrap();
    let section = &oct[oct.find("id=\"oct16\"").unwrap()..];
    let row = section.lines().find(|l| l.contains("mean error")).unwrap();
    assert_eq!(values(row)[0].parse::<f64>().unwrap(), mean);
    // Every page's MSE cell shows its value to four significant digits (a fixed count of
    // decimals showed meshopt_oct16's as 0.000000000).
    let meshopt = page("family/meshopt_oct16.html");
    let mut cells = 0;
    for p in [oct, meshopt] {
        for row in p.lines().filter(|l| l.starts_with("<tr><th>MSE</th>")) {
            let value: f64 = values(row)[0].parse().unwrap();
            let shown: f64 = row
                .split('>')
                .nth(4)
                .unwrap()
                .split('<')
                .next()
                .unwrap()
                .parse()
                .unwrap();
            assert!(value > 0.0, "{row}");
            assert!((shown / value - 1.0).abs() < 1e-3, "{row}");
            cells += 1;
        }
    }
    assert!(cells > 10, "{cells} MSE cells");
}

/// The texts of an SVG's `<text>` elements, trimmed.
fn svg_texts(svg: &str) -> Vec<String> {
    svg.split("</text>")
        .filter_map(|s| s.rfind("<text").map(|at| &s[at..]))
        .map(|s| s[s.find('>').unwrap() + 1..].trim().to_string())
        .collect()
}

/// Every chart point names its spec in an SVG `<title>`; the Pareto front of mean error
/// against bits, recomputed here from `list --json`, is labelled; tick labels are short
/// (no `9.999999999999999e-5`); the bits axis is fitted to the data.
#[test]
fn every_chart_point_is_identifiable() {
    let index = page("index.html");
    let list: Value = serde_json::from_str(&ok(&["list", "--json"]).stdout).unwrap();
    let specs = list["specs"].as_array().unwrap();
    let charts: Vec<&str> = index
        .split("<svg")
        .skip(1)
        .map(|s| s.split("</svg>").next().unwrap())
        .collect();
    assert_eq!(charts.len(), 5);
    for c in &charts {
        let circles = c.matches("<circle").count();
        assert!(circles > 50, "{circles} points");
        assert_eq!(
            c.matches("</title></circle>").count(),
            circles,
            "a title per point"
        );
    }
    // The mean-against-bits chart holds every spec, each titled `id: bits, mean`.
    for e in specs {
        let id = e["spec"].as_str().unwrap();
        assert!(
            charts[0].contains(&format!("<title>{id}: {}, ", e["bits"])),
            "{id}"
        );
    }
    // Each domain's front: no spec of its domain has both fewer-or-equal bits and a
    // lower mean.
    let point = |e: &Value| (e["bits"].as_f64().unwrap(), e["mean"].as_f64().unwrap());
    let texts = svg_texts(charts[0]);
    let mut front = 0;
    for e in specs {
        let (b, m) = point(e);
        let beaten = specs
            .iter()
            .filter(|o| o["domain"] == e["domain"])
            .any(|o| {
                let (ob, om) = point(o);
                (ob < b && om <= m) || (ob == b && om < m)
            });
        if !beaten {
            front += 1;
            // Of specs at the same point, one label names the point.
            let id = e["spec"].as_str().unwrap();
            let labelled = specs
                .iter()
                .filter(|o| o["domain"] == e["domain"] && point(o) == point(e))
                .any(|o| texts.iter().any(|t| t == o["spec"].as_str().unwrap()));
            assert!(labelled, "{id} on the front is labelled");
        }
    }
    assert!(front >= 5, "{front} on the front");
    for c in &charts {
        for t in svg_texts(c) {
            if t.parse::<f64>().is_ok() {
                assert!(t.len() <= 6, "a tick label {t:?}");
            }
        }
    }
    let ticks: Vec<f64> = svg_texts(charts[0])
        .iter()
        .filter_map(|t| t.parse().ok())
        .collect();
    let smallest_bits = specs
        .iter()
        .map(|e| e["bits"].as_f64().unwrap())
        .fold(f64::INFINITY, f64::min);
    assert!(
        ticks
            .iter()
            .all(|&t| t < 1e-3 || t >= smallest_bits - 10.0 || t <= 1.0),
        "the bits axis starts near the smallest spec: {ticks:?}"
    );
    assert!(
        !ticks.contains(&0.0),
        "the bits axis does not start at 0: {ticks:?}"
    );
}

/// The index opens with each use's first choice, as `choose --use` answers it, and the
/// frames page lists every frame spec with `list --json`'s figures.
#[test]
fn the_report_picks_by_use_and_ranks_frames() {
    let index = page("index.html");
    for (args, page_of) in [
        (["--use", "gbuffer", "--bits", "32"], "family/"),
        (["--use", "vertex", "--bits", "16"], "family/"),
        (["--use", "frame", "--bits", "64"], "frames.html#"),
    ] {
        let r = ok(&[&["choose"][..], &args, &["--json", "--limit", "1"]].concat());
        let v: Value = serde_json::from_str(&r.stdout).unwrap();
        let id = v[0]["spec"].as_str().unwrap();
        let row = index
            .lines()
            .find(|l| l.contains(&format!("<code>unitpack choose {}</code>", args.join(" "))))
            .unwrap_or_else(|| panic!("a pick for {args:?}"));
        assert!(
            row.contains(&format!("data-spec=\"{id}\"")),
            "{args:?}: {row}"
        );
        assert!(row.contains(page_of), "{row}");
        let why = v[0]["why"].as_str().unwrap();
        assert!(
            index.contains(why.split(';').next().unwrap()),
            "{args:?}: why"
        );
    }
    assert!(index.contains("href=\"frames.html\""));
    let frames = page("frames.html");
    let list: Value = serde_json::from_str(&ok(&["list", "--json"]).stdout).unwrap();
    for f in list["frames"].as_array().unwrap() {
        let id = f["spec"].as_str().unwrap();
        let v = frame_row_values(&frames, id);
        assert_eq!(
            v[0].parse::<f64>().unwrap(),
            f["bits"].as_f64().unwrap(),
            "{id}"
        );
        assert_eq!(
            v[2].parse::<f64>().unwrap(),
            f["normal"][1].as_f64().unwrap(),
            "{id}"
        );
        assert_eq!(
            v[4].parse::<f64>().unwrap(),
            f["tangent"][1].as_f64().unwrap(),
            "{id}"
        );
        assert_eq!(
            v[7].parse::<f64>().unwrap(),
            f["flips"].as_f64().unwrap(),
            "{id}"
        );
    }
}

/// A second run writes the same bytes (and so leaves every file as it was).
#[test]
fn the_report_is_deterministic_and_keeps_to_its_folder() {
    let first = report().join("report");
    let again = tempdir();
    let second = again.path().join("report");
    ok(&["report", "--out", second.to_str().unwrap()]);
    let (a, b) = (tree(&first), tree(&second));
    assert_eq!(a, b);
    for rel in &a {
        assert!(
            std::fs::read(first.join(rel)).unwrap() == std::fs::read(second.join(rel)).unwrap(),
            "{} differs between two runs",
            rel.display()
        );
    }
    // Into the same folder again: allowed (its manifest lists every file).
    ok(&["report", "--out", second.to_str().unwrap()]);
    // A folder with a file of someone else's is refused, and the file kept.
    let other = tempdir();
    std::fs::write(other.path().join("notes.txt"), "mine").unwrap();
    let err = fails(&["report", "--out", other.path().to_str().unwrap()], "");
    assert!(err.contains("holds no earlier report"), "{err}");
    assert_eq!(tree(other.path()).len(), 1);
    assert_eq!(
        std::fs::read_to_string(other.path().join("notes.txt")).unwrap(),
        "mine"
    );
}

/// Debian's Chromium.
fn chromium() -> PathBuf {
    let path = PathBuf::from("/usr/bin/chromium");
    assert!(
        path.exists(),
        "the report's browser test needs Chromium: install the Debian package `chromium`"
    );
    path
}

/// Runs headless Chromium on a file of the report with `args`; returns (stdout, stderr).
fn browse(rel: &str, args: &[&str]) -> (String, String) {
    let profile = tempdir();
    let url = format!("file://{}", report().join("report").join(rel).display());
    let out = Command::new(chromium())
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--enable-logging=stderr",
            "--v=0",
            "--virtual-time-budget=10000",
            &format!("--user-data-dir={}", profile.path().display()),
        ])
        .args(args)
        .arg(&url)
        .output()
        .expect("chromium runs");
    assert!(out.status.success(), "chromium on {rel}: {out:?}");
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The index and a family page render in Chromium with no console message, every
/// image loaded, the charts in the DOM and a screenshot that is not blank.
#[test]
fn the_report_renders_in_chromium() {
    for (rel, images) in [
        ("index.html", 0),
        ("family/oct.html", 1),
        ("frames.html", 0),
    ] {
        let (dom, log) = browse(rel, &["--dump-dom"]);
        if rel == "index.html" {
            // The charts' points keep their titles in the DOM, the picks are there, and
            // the table's script ran (it titles each heading with how it sorts).
            let file = page(rel);
            let titled = file.matches("</title></circle>").count();
            assert!(titled > 250, "{titled} titled points");
            assert_eq!(dom.matches("</title></circle>").count(), titled);
            assert!(dom.contains("<tr class=\"pick\""), "the picks");
            assert!(dom.contains("title=\"sort by spec\""), "table.js ran");
        }
        let console: Vec<&str> = log.lines().filter(|l| l.contains("CONSOLE")).collect();
        assert!(console.is_empty(), "{rel}: console messages {console:?}");
        let loaded = dom
            .split("data-images-loaded=\"")
            .nth(1)
            .and_then(|s| s.split('"').next())
            .unwrap_or_else(|| panic!("{rel}: check.js ran: {dom:.400}"));
        assert!(
            dom.contains("data-images-broken=\"0\""),
            "{rel}: a broken image"
        );
        let n: usize = loaded.parse().unwrap();
        assert!(n >= images, "{rel}: {n} images loaded");
        if images > 0 {
            // Two maps and a legend for each spec of the page.
            assert_eq!(n, dom.matches("<img").count(), "{rel}");
            assert!(n >= 3, "{rel}");
        }
        if rel == "frames.html" {
            // A table page: its DOM says all (a screenshot costs a browser start).
            assert!(dom.contains("<tr id=\"qtangent64\""), "{rel}: the frames");
            continue;
        }
        assert!(dom.contains("<svg"), "{rel}: the charts are in the DOM");
        let shot = tempdir();
        let png_path = shot.path().join("shot.png");
        browse(
            rel,
            &[
                &format!("--screenshot={}", png_path.display()),
                "--window-size=1200,900",
                "--hide-scrollbars",
            ],
        );
        let decoder = png::Decoder::new(std::io::BufReader::new(
            std::fs::File::open(&png_path).expect("a screenshot"),
        ));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        let px = &buf[..info.buffer_size()];
        let channels = info.color_type.samples();
        let colours: std::collections::BTreeSet<&[u8]> =
            px.chunks_exact(channels).map(|p| &p[..3]).collect();
        assert!(
            colours.len() > 50,
            "{rel}: the screenshot is blank ({} colours)",
            colours.len()
        );
    }
}

/// `report --sample FILE`: every figure over the file's vectors (the index's rows those
/// of `choose --sample FILE --json`), the sample named, and its density maps beside each
/// spec's error maps, coloured only where its vectors lie: a sample within 20° of +Z
/// leaves every cell below latitude 60° grey.
#[test]
fn a_report_over_a_sample_shows_its_figures_and_where_it_lies() {
    let dir = tempdir();
    let mut s = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f64 / (1u64 << 24) as f64
    };
    let mut text = String::new();
    for _ in 0..500 {
        // Within 20° of +Z: z ≥ cos 20°.
        let z = 1.0 - next() * (1.0 - 20f64.to_radians().cos());
        let a = next() * std::f64::consts::TAU;
        let r = (1.0 - z * z).sqrt();
        text.push_str(&format!("{} {} {}\n", r * a.cos(), r * a.sin(), z));
    }
    let file = dir.path().join("cap.txt");
    std::fs::write(&file, text).unwrap();
    let out = dir.path().join("report");
    let f = file.to_str().unwrap();
    ok(&["report", "--out", out.to_str().unwrap(), "--sample", f]);
    let index = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(
        index.contains(&format!("the 500 vectors of {f}")),
        "the sample is named"
    );
    let chosen = chosen(&["--sample", f]);
    let rows: Vec<&str> = index
        .lines()
        .filter(|l| l.starts_with("<tr data-spec="))
        .collect();
    assert_eq!(
        rows.len(),
        chosen.len(),
        "every spec, measured over the sample"
    );
    for row in rows {
        let id = row.split('"').nth(1).unwrap();
        let e = chosen.iter().find(|e| e["spec"] == id).unwrap();
        let v = values(row);
        assert_eq!(
            v[1].parse::<f64>().unwrap(),
            e["mean"].as_f64().unwrap(),
            "{id} mean"
        );
        assert_eq!(
            v[2].parse::<f64>().unwrap(),
            e["max"].as_f64().unwrap(),
            "{id} max"
        );
    }
    // A pick's command names the sample its figures are over, and gives the same first
    // choice; a stream of vectors has no tangent frames, whose figures stay seeded.
    let args = ["--use", "gbuffer", "--bits", "32", "--sample", f];
    let first = &crate::common::chosen(&args)[0]["spec"];
    let pick = index
        .lines()
        .find(|l| l.contains(&format!("<code>unitpack choose {}</code>", args.join(" "))))
        .unwrap_or_else(|| panic!("a pick for {args:?}"));
    assert!(pick.contains(&format!("data-spec={first}")), "{pick}");
    let frames = std::fs::read_to_string(out.join("frames.html")).unwrap();
    assert!(
        frames.contains(&format!(
            "seeded orthonormal frames, not over the sample: {f} is not a glTF asset"
        )),
        "{frames}"
    );
    assert!(
        frames.contains("<code>unitpack choose --use frame --bits 64</code>"),
        "{frames}"
    );
    let oct = std::fs::read_to_string(out.join("family/oct.html")).unwrap();
    assert!(oct.contains("maps/sample_equirect.png") && oct.contains("Where your sample lies"));
    assert!(oct.contains("99th percentile"), "the percentile row");
    // The equirectangular density: rows run from +90° down to −90°, so every pixel row
    // below latitude 60° (a sixth of the height from the top) is grey; above 70° (a ninth)
    // some are not.
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(out.join("maps/sample_equirect.png")).unwrap(),
    ));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let (w, h) = (info.width as usize, info.height as usize);
    let px = |x: usize, y: usize| &buf[(y * w + x) * 3..][..3];
    let grey: &[u8] = &[200, 200, 200];
    for y in h / 6..h {
        for x in 0..w {
            assert_eq!(px(x, y), grey, "pixel ({x}, {y}) below 60° latitude");
        }
    }
    assert!(
        (0..h / 9).any(|y| (0..w).any(|x| px(x, y) != grey)),
        "the cap is coloured"
    );
}
