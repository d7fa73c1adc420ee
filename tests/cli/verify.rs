//! `verify` on lavapipe, on the hardware adapter, as JSON, and `--portable`.

use crate::common::*;
use std::collections::BTreeSet;

#[test]
fn verify_oct16_wgsl_on_lavapipe() {
    // Without XDG_RUNTIME_DIR Mesa complains on stderr; that noise is not unitpack's.
    let mut cmd = unitpack();
    cmd.args(["verify", "oct16", "--lang", "wgsl"])
        .env_remove("XDG_RUNTIME_DIR");
    let r = run_cmd(cmd, b"");
    assert_eq!(r.code, 0, "{r:?}");
    assert!(!r.stderr.contains("XDG_RUNTIME_DIR"), "{r:?}");
    assert!(r.stdout.lines().any(|l| l.starts_with("adapter:")), "{r:?}");
    let rows: Vec<&str> = r
        .stdout
        .lines()
        .filter(|l| l.starts_with("oct16 "))
        .collect();
    assert!(!rows.is_empty(), "{r:?}");
    // The WGSL paths (naga, its GLSL output, the literal read-back of the include, Tint in
    // headless Chromium, naga's SPIR-V on SwiftShader), and the model's own four- and
    // eight-lane paths, which need no language.
    let paths = [
        "wgsl/naga",
        "wgsl/naga glsl-out",
        "wgsl/literals",
        "wgsl/tint",
        "wgsl/naga on swiftshader",
        "cpu/4 lanes",
        "cpu/8 lanes",
    ];
    // A row: spec, function (or "(whole include)"), the path (words), items tested,
    // mismatches.
    let path_of = |l: &str| {
        let l = l.replace("(whole include)", "include");
        let w: Vec<&str> = l.split_whitespace().collect();
        w[2..w.len() - 2].join(" ")
    };
    for l in &rows {
        assert!(paths.contains(&path_of(l).as_str()), "{l}: {r:?}");
    }
    for p in paths {
        assert!(rows.iter().any(|l| path_of(l) == p), "no row on {p}: {r:?}");
    }
    // Where SwiftShader flushes denormals only the float form is measured; the codes and
    // the decoders hold.
    for l in rows.iter().filter(|l| l.ends_with('~')) {
        assert!(l.split_whitespace().nth(1) == Some("encode_float"), "{l}");
        assert!(
            l.contains("wgsl/tint") || l.contains("on swiftshader"),
            "{l}"
        );
    }
    for lanes in ["cpu/4 lanes", "cpu/8 lanes"] {
        assert!(rows.iter().any(|l| l.contains(lanes)), "{lanes}: {r:?}");
    }
    for f in ["encode", "decode"] {
        assert!(
            rows.iter().any(|l| l.split_whitespace().nth(1) == Some(f)),
            "no row for {f}: {r:?}"
        );
    }
    assert!(r.stdout.contains(" 0 failed"), "{r:?}");
}

/// `--adapter gpu` runs the shader paths on the machine's own GPU, never on lavapipe: where
/// there is none (CI), it fails naming the adapters it found and what to install.
#[test]
fn verify_on_the_hardware_adapter_never_falls_back_to_lavapipe() {
    let r = run(&["verify", "oct16", "--lang", "wgsl", "--adapter", "gpu"]);
    let adapter = r.stdout.lines().find(|l| l.starts_with("adapter:"));
    match adapter {
        Some(line) => assert!(!line.contains("llvmpipe"), "{r:?}"),
        None => {
            assert_eq!(r.code, 2, "{r:?}");
            assert!(
                r.stderr
                    .contains("no hardware Vulkan adapter found (adapters: ")
                    && r.stderr.contains("llvmpipe")
                    && r.stderr.contains("libvulkan1"),
                "{r:?}"
            );
        }
    }
    let err = fails(&["verify", "oct16", "--adapter", "npu"], "");
    assert!(err.contains("invalid value 'npu'"), "{err}");
}

#[test]
fn verify_rejects_bad_specs() {
    let err = fails(&["verify", "octt16", "--lang", "wgsl"], "");
    assert!(err.contains("unknown codec 'octt16'"), "{err}");
}

#[test]
fn verify_json_reports_every_row() {
    let r = ok(&["verify", "oct16", "oct16p", "--lang", "wgsl,glsl", "--json"]);
    assert!(!r.stderr.contains("XDG_RUNTIME_DIR"), "{r:?}");
    let v: serde_json::Value = serde_json::from_str(&r.stdout).expect("verify --json is JSON");
    assert_eq!(v["passed"], true, "{r:?}");
    assert_eq!(v["failed"], 0);
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(v["checks"].as_u64().unwrap() as usize, rows.len());
    // oct16p's decoders are oct16's code: run once per path, their rows repeat oct16's;
    // the items counted are those run.
    let shared = |r: &&serde_json::Value| !r["same_code_as"].is_null();
    let items: u64 = rows
        .iter()
        .filter(|r| !shared(r))
        .map(|r| r["tested"].as_u64().unwrap())
        .sum();
    assert_eq!(v["items"].as_u64().unwrap(), items);
    let copies: Vec<_> = rows.iter().filter(shared).collect();
    assert_eq!(
        copies.len(),
        2 * 12,
        "two decoders on three Vulkan shader paths on lavapipe and on SwiftShader, two \
         OpenGL paths, Tint, ANGLE and the four- and eight-lane paths"
    );
    for c in copies {
        assert_eq!(c["spec"], "oct16p");
        let owner = format!("oct16 {}", c["function"].as_str().unwrap());
        assert_eq!(c["same_code_as"].as_str(), Some(owner.as_str()));
    }
    let paths: BTreeSet<&str> = rows.iter().map(|r| r["path"].as_str().unwrap()).collect();
    for p in [
        "wgsl/naga",
        "glsl/naga",
        "glsl/glslang",
        "glsl/gl",
        "glsl/gl precise",
        "wgsl/tint",
        "glsl/angle",
        "wgsl/naga on swiftshader",
        "glsl/naga on swiftshader",
        "glsl/glslang on swiftshader",
    ] {
        assert!(paths.contains(p), "{paths:?}");
    }
    assert!(
        rows.iter()
            .all(|r| (r["spec"] == "oct16" || r["spec"] == "oct16p") && r["error"].is_null())
    );
}

/// `verify --portable` evaluates the model under the deviations the APIs allow. Every
/// packed encoder decides its codes portably (the spherical ones with fixed-point
/// trigonometry), so the report says so and exits 0; its float outputs still move.
#[test]
fn verify_portable_reports_codes_that_allowed_deviations_change() {
    let r = run(&["verify", "--portable", "spherical16", "--json"]);
    assert_eq!(r.code, 0, "{r:?}");
    assert!(
        r.stdout.contains("\"packed_encoders_portable\":true"),
        "{r:?}"
    );
    assert!(
        r.stdout.contains(
            "\"role\":\"DecodeFloat\",\"class\":\"fma\",\"items\":16384,\"changed\":3274"
        ),
        "{r:?}"
    );
    let r = run(&["verify", "--portable", "oct16", "--json"]);
    assert_eq!(r.code, 0, "{r:?}");
    assert!(
        r.stdout.contains("\"packed_encoders_portable\":true"),
        "{r:?}"
    );
    for class in ["div", "sqrt", "fma", "denorm", "zero", "excess"] {
        assert!(r.stdout.contains(&format!("\"{class}\"")), "{class}: {r:?}");
    }
    let r = run(&["verify", "--portable", "snorm12x2"]);
    assert_eq!(r.code, 0, "helpers have no packed encoder: {r:?}");
    assert!(r.stdout.contains("snorm12x2"), "{r:?}");
}

/// `verify --portable`'s table explains its cells: every form a cell takes (`.`, `N/Ku`,
/// `N/NaN`, `N!`, `Nx`) and the proven column are in a legend under it, every cell of
/// the table has one of those forms, and each ends under its class's name (a wide cell
/// widens its column). The binary before this printed the table alone, and a cell such as
/// `16318/877203419u` pushed the rest of its row right.
#[test]
fn verify_portable_explains_its_cells() {
    let r = run(&["verify", "--portable", "spherical16"]);
    assert_eq!(r.code, 0, "{r:?}");
    for s in [
        "cells:  .       no output changed",
        "N/Ku    N float outputs changed, by at most K units in the last place",
        "N/NaN",
        "N!      N packed codes changed under a class the guarantee covers: a failure\n                (covered: div, sqrt, fma, denorm, zero)",
        "Nx      N packed codes changed under a class it does not cover\n                (not covered: excess, reassoc, round, contract)",
        "proven: ≤B (seen S)",
    ] {
        assert!(r.stdout.contains(s), "no legend for {s:?}: {r:?}");
    }
    let header = r.stdout.lines().nth(1).expect("the header");
    // spec, function, items, one column per class, proven (2^-24).
    let classes = header
        .split_whitespace()
        .skip(3)
        .take_while(|w| *w != "proven")
        .count();
    assert!(classes >= 5, "{header}");
    let mut cells = 0;
    let names = &word_ends(header)[3..3 + classes];
    for row in r.stdout.lines().filter(|l| l.starts_with("spherical16 ")) {
        // spec, function, (role), items, then one cell per class.
        let words: Vec<&str> = row.split_whitespace().collect();
        assert_eq!(
            &word_ends(row)[4..4 + classes],
            names,
            "{row:?} under {header:?}"
        );
        for cell in &words[4..4 + classes] {
            let (n, rest) = cell.split_at(cell.find(|c: char| !c.is_ascii_digit()).unwrap_or(0));
            let known = match rest {
                "." => n.is_empty(),
                "!" | "x" | "/NaN" => !n.is_empty(),
                u => {
                    let k = u.strip_prefix('/').and_then(|k| k.strip_suffix('u'));
                    !n.is_empty() && k.is_some_and(|k| k.parse::<u64>().is_ok())
                }
            };
            assert!(known, "cell {cell:?} of {row:?} is not in the legend");
            cells += 1;
        }
    }
    assert!(cells >= 2 * classes, "{r:?}");
}

/// Every row of `verify`'s table keeps the columns of the header, the static check
/// `glsl es 300/glslang` too: its path is one character longer than the column was, and
/// on the binary before this it pushed `tested` and `mismatches` one column right.
#[test]
fn verify_table_columns_line_up() {
    let r = run(&["verify", "oct16", "--lang", "glsl"]);
    assert_eq!(r.code, 0, "{r:?}");
    let lines: Vec<&str> = r.stdout.lines().collect();
    let header = lines
        .iter()
        .find(|l| l.starts_with("spec "))
        .expect("a header");
    let end_of = |line: &str, word: &str| {
        line.find(word)
            .map(|i| line[..i + word.len()].chars().count())
    };
    let (tested, mismatches) = (end_of(header, "tested"), end_of(header, "mismatches"));
    let rows: Vec<&str> = lines
        .iter()
        .copied()
        .filter(|l| l.starts_with("oct16 "))
        .collect();
    assert!(
        rows.iter().any(|l| l.contains("glsl es 300/glslang")),
        "{r:?}"
    );
    for row in rows {
        // The two right-aligned numbers end where their headings end.
        let row = row.split("  (same code as").next().unwrap_or_default();
        let ends = word_ends(row);
        let n = ends.len();
        assert!(n >= 2, "{row:?}");
        assert_eq!(
            (Some(ends[n - 2]), Some(ends[n - 1])),
            (tested, mismatches),
            "{row:?} under {header:?}"
        );
    }
}

/// Where each word of `line` ends, in characters: right-aligned cells line up when these
/// equal their headings'.
fn word_ends(line: &str) -> Vec<usize> {
    let chars: Vec<char> = line.chars().collect();
    (1..=chars.len())
        .filter(|&i| chars[i - 1] != ' ' && chars.get(i).is_none_or(|&c| c == ' '))
        .collect()
}

/// The report a `verify --web` page posts once it has run, opened in headless Chromium
/// (WebGPU on SwiftShader without a GPU).
fn page_report(page: String) -> serde_json::Value {
    use unitpack::verify::browser::Browser;
    let browser = Browser::start_with(page).unwrap_or_else(|e| panic!("{e:#}"));
    let report = browser
        .report(std::time::Duration::from_secs(900))
        .unwrap_or_else(|e| panic!("{e:#}"));
    serde_json::from_str(&report).unwrap_or_else(|e| panic!("{e}: {report}"))
}

/// `verify --web DIR SPEC...` writes one self-contained page. Opened in headless Chromium
/// it runs every function a spec owns and reports, in `verify --json`'s shape, every
/// packed function passing (its hashes match) and every float form passing or within its
/// proven bound, the rest measured (SwiftShader flushes denormals); a page whose oct16
/// WGSL include was perturbed (the encoder's rounding boundary moved) reports the encoder
/// failing, with its first mismatching items.
///
/// The page is made of the first spec of every family, so every shape of function the
/// catalogue has (struct returns, frames, tables, two-word codes): every spec's WGSL
/// already runs through the same Tint and SwiftShader in `tests/verify_gpu.rs`'s
/// `wgsl/tint` rows, on 64 times the page's sample, and compiling the whole catalogue a
/// second time here would add nothing but a minute of the suite.
#[test]
fn verify_web_page_passes_in_chromium_and_catches_a_perturbed_include() {
    use unitpack::codecs::Spec;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("page");
    let mut families = std::collections::BTreeSet::new();
    let specs: Vec<Spec> = Spec::all()
        .into_iter()
        .filter(|s| families.insert(s.info().name))
        .collect();
    assert!(specs.len() > 40, "{} families", specs.len());
    let names: Vec<String> = specs.iter().map(|s| s.to_string()).collect();
    let mut args = vec!["verify", "--web", out.to_str().unwrap()];
    args.extend(names.iter().map(String::as_str));
    let r = ok(&args);
    let path = out.join("index.html");
    assert_eq!(r.stdout.trim(), path.display().to_string(), "{r:?}");
    let page = std::fs::read_to_string(&path).unwrap();
    for fetched in ["src=\"http", "href=\"http", "import(", "<link "] {
        assert!(
            !page.contains(fetched),
            "the page fetches something: {fetched}"
        );
    }
    let v = page_report(page);
    let rows = v["rows"].as_array().expect("rows");
    let functions: usize = specs.iter().map(|s| s.emitted().functions.len()).sum();
    assert!(
        rows.len() > 2 * specs.len() && rows.len() <= functions,
        "{} rows",
        rows.len()
    );
    for name in &names {
        assert!(
            rows.iter().any(|r| r["spec"] == name.as_str()),
            "the page runs {name}"
        );
    }
    for row in rows {
        let what = format!("{} {}", row["spec"], row["function"]);
        assert_eq!(row["passed"], true, "{what}: {row}");
        assert_eq!(row["error"], serde_json::Value::Null, "{what}");
        if row["measured"] == true {
            // SwiftShader flushes denormals: float forms are measured there, and so are the
            // lean tier's codes, which are promised only where denormals are kept.
            let spec: Spec = row["spec"].as_str().unwrap().parse().unwrap();
            assert!(
                row["first_mismatches"][0]["output_float"] == true
                    || unitpack::codecs::core::ieee::asked(&spec),
                "{what}: {row}"
            );
        }
    }
    assert_eq!(v["failed"], 0, "{}", v["adapter"]);
    assert_eq!(v["passed"], true);
    assert!(
        v["adapter"].as_str().unwrap().starts_with("WebGPU: "),
        "{v}"
    );

    let oct16: Spec = "oct16".parse().unwrap();
    let perturbed = unitpack::verify::web::page(&[oct16], |_, wgsl| {
        // The encoder steps a rounded field down where `t2 < (t1 - 0.5f) * l1`: with 0.4
        // there it also steps down fields that lie within a tenth of the boundary.
        let at = wgsl
            .find("0.5f")
            .expect("a rounding offset in oct16's WGSL");
        format!("{}0.4f{}", &wgsl[..at], &wgsl[at + 4..])
    });
    let v = page_report(perturbed);
    assert_eq!(v["passed"], false, "{v}");
    let failing: Vec<&serde_json::Value> = v["rows"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["passed"] == false)
        .collect();
    assert!(!failing.is_empty(), "{v}");
    for row in failing {
        let first = &row["first_mismatches"][0];
        assert!(
            first["input"].as_array().is_some_and(|a| !a.is_empty())
                && first["expected"] != first["actual"],
            "a failing row names its first mismatch: {row}"
        );
    }
}
