//! The report `verify` prints: one row per spec, function and path, with the first
//! mismatches as input, expected and actual words, and the largest float deviation.

/// One mismatching item: its input words, expected and actual output words, and whether
/// the input and output words are floats (printed as value and hex) or codes (hex).
#[derive(Clone, Debug)]
pub struct Mismatch {
    pub input: Vec<u32>,
    pub expected: Vec<u32>,
    pub actual: Vec<u32>,
    pub input_float: bool,
    pub output_float: bool,
}

/// One row of the report.
#[derive(Clone, Debug)]
pub struct Row {
    pub spec: String,
    pub function: String,
    pub path: String,
    pub tested: usize,
    pub mismatches: usize,
    pub first: Vec<Mismatch>,
    /// Compilation or validation failure, if any.
    pub error: Option<String>,
    /// The function (`spec function`) whose code and inputs this one shares exactly,
    /// verified once on the path; this row repeats that row's result.
    pub same_as: Option<String>,
    /// For float outputs that mismatched: the mismatch farthest from the model's value.
    /// On lavapipe there is none; on a hardware adapter it says how far the GPU's
    /// division, roots, contractions and flushes moved the outputs.
    pub largest: Option<Largest>,
    /// Float outputs on a path that regroups products ([`Path::regroups`]): the
    /// mismatches are reported, and are not a failure.
    pub measured: bool,
}

/// The largest difference of one function's float outputs from the model's on a path.
#[derive(Clone, Debug)]
pub struct Largest {
    /// `|expected - actual|` of the lane that differs most, in f64: 0 when only the sign
    /// of a zero differs, infinite when one side is NaN or their infinities differ.
    pub difference: f64,
    pub at: Mismatch,
}

/// `|a - b|` of two f32 words, as [`Largest::difference`] defines it.
pub(super) fn difference(a: u32, b: u32) -> f64 {
    let (a, b) = (f64::from(f32::from_bits(a)), f64::from(f32::from_bits(b)));
    match (a.is_nan(), b.is_nan()) {
        (true, true) => 0.0,
        (false, false) if a == b => 0.0,
        (false, false) => {
            let d = (a - b).abs();
            if d.is_nan() { f64::INFINITY } else { d }
        }
        _ => f64::INFINITY,
    }
}

impl Row {
    pub fn passed(&self) -> bool {
        self.error.is_none() && (self.mismatches == 0 || self.measured)
    }
}

pub struct Report {
    pub adapter: String,
    pub driver: String,
    pub rows: Vec<Row>,
}

pub(super) fn words_hex(w: &[u32], as_float: bool) -> String {
    w.iter()
        .map(|b| {
            if as_float {
                format!("{:?} (0x{b:08x})", f32::from_bits(*b))
            } else {
                format!("0x{b:08x}")
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

impl Report {
    pub fn all_passed(&self) -> bool {
        self.rows.iter().all(Row::passed)
    }

    pub fn table(&self) -> String {
        let mut s = format!("adapter: {} — driver: {}\n", self.adapter, self.driver);
        // Each column is as wide as its longest entry (`glsl es 300/glslang` is wider
        // than the usual 18), so that no row shifts the columns after it.
        let width = |min: usize, field: fn(&Row) -> &str| {
            let longest = self.rows.iter().map(|r| field(r).chars().count()).max();
            longest.unwrap_or(0).max(min)
        };
        let (ws, wf, wp) = (
            width(22, |r| &r.spec),
            width(28, |r| &r.function),
            width(18, |r| &r.path),
        );
        s.push_str(&format!(
            "{:<ws$} {:<wf$} {:<wp$} {:>10} {:>10}\n",
            "spec", "function", "path", "tested", "mismatches"
        ));
        for r in &self.rows {
            let mm = if r.error.is_some() {
                "ERROR".to_string()
            } else if r.measured && r.mismatches > 0 {
                format!("{}~", r.mismatches)
            } else {
                r.mismatches.to_string()
            };
            let shared = r
                .same_as
                .as_ref()
                .map_or(String::new(), |o| format!("  (same code as {o})"));
            s.push_str(&format!(
                "{:<ws$} {:<wf$} {:<wp$} {:>10} {:>10}{shared}\n",
                r.spec, r.function, r.path, r.tested, mm
            ));
        }
        let failed: Vec<&Row> = self.rows.iter().filter(|r| !r.passed()).collect();
        for r in &failed {
            s.push_str(&format!(
                "\nFAILED {} {} on {}:\n",
                r.spec, r.function, r.path
            ));
            if let Some(e) = &r.error {
                s.push_str(&format!("  {e}\n"));
            }
            if let Some(l) = &r.largest {
                s.push_str(&format!(
                    "  largest difference {:e}, at input [{}]\n    expected [{}]\n    actual   [{}]\n  first mismatches:\n",
                    l.difference,
                    words_hex(&l.at.input, l.at.input_float),
                    words_hex(&l.at.expected, l.at.output_float),
                    words_hex(&l.at.actual, l.at.output_float)
                ));
            }
            for m in &r.first {
                s.push_str(&format!(
                    "  input [{}]\n    expected [{}]\n    actual   [{}]\n",
                    words_hex(&m.input, m.input_float),
                    words_hex(&m.expected, m.output_float),
                    words_hex(&m.actual, m.output_float)
                ));
            }
        }
        for r in self.rows.iter().filter(|r| r.measured && r.mismatches > 0) {
            let largest = r.largest.as_ref().map_or(String::new(), |l| {
                format!(", largest difference {:e}", l.difference)
            });
            s.push_str(&format!(
                "\nmeasured {} {} on {}: {} of {} differ{largest}",
                r.spec, r.function, r.path, r.mismatches, r.tested
            ));
        }
        if self.rows.iter().any(|r| r.measured && r.mismatches > 0) {
            s.push_str(
                "\nN~: measured, not held to the model's bits: float outputs on a path that \
                 regroups products (Slang's direct SPIR-V at its default and -O3); float forms, \
                 and the lean tier's codes, where denormals are flushed (SwiftShader, the \
                 browsers); an engine's contracted arithmetic where OpenGL's compiler contracts \
                 it (without precise)\n",
            );
        }
        let shared = self.rows.iter().filter(|r| r.same_as.is_some()).count();
        s.push_str(&format!(
            "\n{} checks ({shared} shared with identical code), {} items run, {} failed\n",
            self.rows.len(),
            self.items_run(),
            failed.len()
        ));
        s
    }

    /// The items actually run: rows that share another's result add none.
    pub fn items_run(&self) -> usize {
        self.rows
            .iter()
            .filter(|r| r.same_as.is_none())
            .map(|r| r.tested)
            .sum()
    }
}
