//! `verify`: the report as a table or as JSON.

use crate::verify::{Mismatch, Report, Row};
use serde::Serialize;

#[derive(Serialize)]
struct ReportJson<'a> {
    adapter: &'a str,
    driver: &'a str,
    passed: bool,
    checks: usize,
    /// Items run: rows that repeat an identical function's result add none.
    items: usize,
    failed: usize,
    rows: Vec<RowJson<'a>>,
}

#[derive(Serialize)]
struct RowJson<'a> {
    spec: &'a str,
    function: &'a str,
    path: &'a str,
    tested: usize,
    mismatches: usize,
    passed: bool,
    /// Why the function could not be compiled or run, if it could not.
    error: Option<&'a str>,
    /// The first mismatches, as raw 32-bit words.
    first_mismatches: Vec<MismatchJson<'a>>,
    /// The function (`spec function`) whose identical code and inputs were run on this
    /// path instead; this row repeats its result.
    same_code_as: Option<&'a str>,
    /// Float outputs that mismatched only: the largest `|expected - actual|` of any lane,
    /// 0 when only the sign of a zero differs, with its mismatch in `largest_at`. Infinite
    /// (one side NaN, or infinities that differ) prints as `null` beside a `largest_at`.
    largest_difference: Option<f64>,
    largest_at: Option<MismatchJson<'a>>,
    /// Float outputs on a path that regroups products (Slang's direct SPIR-V at its
    /// default and `-O3`): mismatches reported, not a failure.
    measured: bool,
}

#[derive(Serialize)]
struct MismatchJson<'a> {
    input: &'a [u32],
    expected: &'a [u32],
    actual: &'a [u32],
    /// Whether the input words are f32 bits (else packed codes).
    input_float: bool,
    output_float: bool,
}

fn row(r: &Row) -> RowJson<'_> {
    RowJson {
        spec: &r.spec,
        function: &r.function,
        path: &r.path,
        tested: r.tested,
        mismatches: r.mismatches,
        passed: r.passed(),
        error: r.error.as_deref(),
        first_mismatches: r.first.iter().map(mismatch).collect(),
        same_code_as: r.same_as.as_deref(),
        largest_difference: r.largest.as_ref().map(|l| l.difference),
        largest_at: r.largest.as_ref().map(|l| mismatch(&l.at)),
        measured: r.measured,
    }
}

fn mismatch(m: &Mismatch) -> MismatchJson<'_> {
    MismatchJson {
        input: &m.input,
        expected: &m.expected,
        actual: &m.actual,
        input_float: m.input_float,
        output_float: m.output_float,
    }
}

/// `verify --json`: the table's content, for scripts (same exit status).
pub fn report_json(r: &Report) -> String {
    let j = ReportJson {
        adapter: &r.adapter,
        driver: &r.driver,
        passed: r.all_passed(),
        checks: r.rows.len(),
        items: r.items_run(),
        failed: r.rows.iter().filter(|r| !r.passed()).count(),
        rows: r.rows.iter().map(row).collect(),
    };
    let mut s = serde_json::to_string_pretty(&j).expect("report serializes");
    s.push('\n');
    s
}
