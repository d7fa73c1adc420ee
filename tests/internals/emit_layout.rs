//! The layout pass: long lines broken where a reader expects, comments filled.

use unitpack::emit::lang::layout::{WIDTH, wrap};

fn columns(s: &str) -> usize {
    s.chars().count()
}

#[test]
fn a_long_statement_breaks_at_its_loosest_operator() {
    let s = format!("    let t = {} * {};", "a".repeat(60), "b(c, d)".repeat(6));
    let w = wrap(&s);
    assert_eq!(
        w,
        format!(
            "    let t = {}\n        * {};",
            "a".repeat(60),
            "b(c, d)".repeat(6)
        )
    );
}

#[test]
fn a_long_call_puts_one_argument_per_line() {
    let arg = "x".repeat(40);
    let s = format!("    let t = f({arg}, g({arg}), {arg});");
    assert_eq!(
        wrap(&s),
        format!("    let t = f(\n        {arg},\n        g({arg}),\n        {arg}\n    );")
    );
}

#[test]
fn comments_fill_the_width_with_a_hanging_indent() {
    let s = format!("// {}", "word ".repeat(40).trim_end());
    let w = wrap(&s);
    let lines: Vec<&str> = w.lines().collect();
    assert!(lines.iter().all(|l| columns(l) <= WIDTH), "{w}");
    assert!(lines[1].starts_with("//   word"), "{w}");
    assert_eq!(w.split_whitespace().filter(|t| *t == "word").count(), 40);
}

#[test]
fn short_lines_and_unbreakable_ones_stay() {
    assert_eq!(wrap("    let t = a + b;\n"), "    let t = a + b;\n");
    let long = format!("    let t = {};", "a".repeat(120));
    assert_eq!(wrap(&long), long);
}
