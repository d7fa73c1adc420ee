//! Every float literal of an emitted include, read back as each compiler reads it.
//!
//! An include computes the model's bits only if every literal in it is the model's f32 on
//! every compiler, and compilers read literals by different rules:
//! - the exact decimal rounded to the nearest f32 (ties to even), or the decimal read as
//!   f64 and then narrowed to f32 (WGSL's abstract floats, compilers that parse with
//!   `strtod`): the two differ where the f64 lands exactly halfway between two f32s
//!   (double rounding);
//! - a literal above FLT_MAX that IEEE rounding still takes to FLT_MAX (Rust's shortest
//!   round trip of `f32::MAX`, `3.4028235e38`, is one) is a shader-creation error in WGSL
//!   (Tint: "value cannot be represented as 'f32'") and infinity on GLSL ES compilers
//!   (ANGLE);
//! - a denormal is zero where denormals are flushed (SwiftShader, ANGLE on many GPUs), so
//!   a nonzero literal that reads back as a denormal or as zero does not survive.
//!
//! naga and glslang accept all of these, so [`check`] reads each literal itself: the range
//! by comparing the literal's exact decimal digits with FLT_MAX's exact expansion (an f64
//! cannot tell `3.4028235e38` from a decimal slightly below FLT_MAX), the rounding with
//! Rust's correctly rounded parsers (hex floats with an exact binary rounding). The printer
//! writes its literals by the same rules ([`crate::emit::lang::literal::f32_literal`]).

use crate::codecs::Spec;
use crate::emit::Lang;
use crate::model::trace::Op;
use anyhow::{Result, anyhow, bail};
use std::cmp::Ordering;
use std::collections::HashSet;

/// FLT_MAX, (2 − 2^-23) · 2^127, written out exactly: its significant digits (trailing
/// zeros dropped) and the decimal exponent of the first one.
const FLT_MAX_DIGITS: &str = "34028234663852885981170418348451692544";
const FLT_MAX_EXPONENT: i64 = 38;

/// One float literal of a text: 1-based line and column (in characters) and its text,
/// suffix included.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Literal<'a> {
    pub line: usize,
    pub column: usize,
    pub text: &'a str,
}

/// Every float literal of `text` in `lang`'s syntax (WESL modules are WGSL), in order:
/// decimal (`1.0`, `.5`, `1e-5`, `1.5e+3f`, `1f`, `1.0h`) and hex (`0x1.8p3f`) floats.
/// Integers (`12`, `3u`, `0x7f800000u`), the digits of identifiers (`vec2`, `t12`, `f32`)
/// and comments (`//`, and `/* */`, which nest in WGSL) are skipped. The emitted languages
/// have no string literals, so none are looked for.
pub fn literals(lang: Lang, text: &str) -> Vec<Literal<'_>> {
    let b = text.as_bytes();
    let at = |i: usize| b.get(i).copied().unwrap_or(0);
    let ident = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    let mut out = Vec::new();
    let (mut line, mut line_start) = (1, 0);
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c == b'\n' {
            line += 1;
            line_start = i + 1;
            i += 1;
        } else if c == b'/' && at(i + 1) == b'/' {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if c == b'/' && at(i + 1) == b'*' {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == b'/' && at(i + 1) == b'*' && (depth == 0 || lang == Lang::Wgsl) {
                    depth += 1;
                    i += 2;
                } else if b[i] == b'*' && at(i + 1) == b'/' {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    if b[i] == b'\n' {
                        line += 1;
                        line_start = i + 1;
                    }
                    i += 1;
                }
            }
        } else if c.is_ascii_alphabetic() || c == b'_' {
            while ident(at(i)) {
                i += 1;
            }
        } else if c.is_ascii_digit() || (c == b'.' && at(i + 1).is_ascii_digit()) {
            let start = i;
            let hex = c == b'0' && matches!(at(i + 1), b'x' | b'X');
            let (digit, exponent): (fn(u8) -> bool, &[u8]) = if hex {
                i += 2;
                (|c| c.is_ascii_hexdigit(), b"pP")
            } else {
                (|c| c.is_ascii_digit(), b"eE")
            };
            while digit(at(i)) {
                i += 1;
            }
            let point = at(i) == b'.';
            if point {
                i += 1;
                while digit(at(i)) {
                    i += 1;
                }
            }
            let signed = matches!(at(i + 1), b'+' | b'-');
            let exp = exponent.contains(&at(i)) && at(i + 1 + usize::from(signed)).is_ascii_digit();
            if exp {
                i += 1 + usize::from(signed);
                while at(i).is_ascii_digit() {
                    i += 1;
                }
            }
            let suffix_start = i;
            while ident(at(i)) {
                i += 1;
            }
            // `1f` is a float in WGSL; a suffix cannot follow a hex mantissa, whose `f` is a
            // digit.
            let float_suffix = matches!(&text[suffix_start..i], "f" | "F" | "h" | "H");
            if point || exp || (!hex && float_suffix) {
                out.push(Literal {
                    line,
                    column: text[line_start..start].chars().count() + 1,
                    text: &text[start..i],
                });
            }
        } else {
            i += 1;
        }
    }
    out
}

/// The f32 every compiler of `lang` reads `literal` (unsigned, suffix included) as, or why
/// they do not all read the same f32: a suffix of another type, a magnitude above FLT_MAX
/// (each language's consequence named), or a decimal whose f32 and f64-then-f32 readings
/// differ. Denormals are read as written; [`check`] holds them to the flushing rule.
pub fn read(lang: Lang, literal: &str) -> Result<f32> {
    let hex = literal.starts_with("0x") || literal.starts_with("0X");
    let body_end = if hex {
        let after = literal.find(['p', 'P']);
        after.map_or(literal.len(), |p| {
            p + literal[p..]
                .find(|c: char| c.is_ascii_alphabetic() && c != 'p' && c != 'P')
                .unwrap_or(literal.len() - p)
        })
    } else {
        literal
            .find(|c: char| c.is_ascii_alphabetic() && c != 'e' && c != 'E')
            .unwrap_or(literal.len())
    };
    let (body, suffix) = literal.split_at(body_end);
    let other_type = match (lang, suffix) {
        (Lang::Wgsl, "" | "f") | (Lang::Glsl | Lang::Hlsl, "" | "f" | "F") => None,
        (Lang::C, "f" | "F") => None,
        (Lang::C, "") => Some("double, which makes C evaluate its operation in double"),
        (Lang::Wgsl, "h") | (Lang::Hlsl, "h" | "H") => Some("a half"),
        (Lang::Glsl, "lf" | "LF") | (Lang::Hlsl, "l" | "L") => Some("a double"),
        (Lang::C, "l" | "L") => Some("a long double"),
        _ => return Err(anyhow!("`{literal}` has a suffix {lang:?} does not know")),
    };
    if let Some(ty) = other_type {
        bail!("`{literal}` is {ty}, not the model's f32");
    }
    // Each reading is infinity where IEEE rounding overflows.
    let (above_max, direct, via_f64) = if hex {
        let (m, sticky, e2) = hex_value(&body[2..])?;
        let read = |precision, min_exponent| round_binary(m, sticky, e2, precision, min_exponent);
        let direct =
            read(24, -149).map_or(f32::INFINITY, |(s, q)| libm::ldexpf(s as f32, q as i32));
        let via_f64 = read(53, -1074).map_or(f32::INFINITY, |(s, q)| {
            libm::ldexp(s as f64, q as i32) as f32
        });
        (hex_above_max(m, sticky, e2), direct, via_f64)
    } else {
        let not_float = |_| anyhow!("`{literal}` is not a float literal");
        let direct = body.parse::<f32>().map_err(not_float)?;
        let via_f64 = body.parse::<f64>().map_err(not_float)? as f32;
        (decimal_above_max(body), direct, via_f64)
    };
    if above_max {
        let consequence = match lang {
            Lang::Wgsl => {
                "in WGSL a shader-creation error (Tint: value cannot be represented as 'f32')"
            }
            Lang::Glsl => "GLSL ES compilers (ANGLE) read it as infinity (0x7f800000)",
            Lang::Hlsl => "an HLSL compiler may read it as infinity (0x7f800000)",
            Lang::C => "outside float's range, which a C constant must lie in (C11 6.4.4p2)",
        };
        bail!(
            "`{literal}` is above FLT_MAX = 3.40282346638528859811704183484516925440e38 \
             (IEEE rounding reads {:#010x}): {consequence}",
            direct.to_bits()
        );
    }
    if direct.to_bits() != via_f64.to_bits() {
        bail!(
            "`{literal}` reads {:#010x} rounded to f32 but {:#010x} through f64 (double \
             rounding): compilers that parse it as double disagree with the others",
            direct.to_bits(),
            via_f64.to_bits()
        );
    }
    Ok(direct)
}

/// Reads every float literal of `text` ([`literals`]) by [`read`] and also rejects a
/// nonzero literal that reads back as a denormal or zero (flushed to zero by SwiftShader
/// and ANGLE, so the model's value would not survive) and, given `model` (the bit patterns
/// of the model's literals, [`model_literals`]), one that reads back as none of them.
/// Returns how many literals were read; the error lists every failing literal with its
/// line and column.
pub fn check(lang: Lang, text: &str, model: Option<&HashSet<u32>>) -> Result<usize> {
    let found = literals(lang, text);
    let mut errors = Vec::new();
    for l in &found {
        let verdict = read(lang, l.text).and_then(|v| {
            let bits = v.to_bits();
            if !v.is_normal() && bits != 0 {
                bail!(
                    "`{}` reads {bits:#010x}, a denormal: zero where denormals are flushed \
                     (SwiftShader, ANGLE)",
                    l.text
                );
            }
            if bits == 0 && !written_zero(l.text) {
                bail!("`{}` is not zero but reads 0x00000000", l.text);
            }
            if model.is_some_and(|m| !m.contains(&bits)) {
                bail!("`{}` reads {bits:#010x}, no literal of the model", l.text);
            }
            Ok(())
        });
        if let Err(e) = verdict {
            errors.push(format!("line {}, column {}: {e:#}", l.line, l.column));
        }
    }
    if !errors.is_empty() {
        bail!(
            "{} of {} {lang:?} float literals do not read back as the model's f32 on every \
             compiler:\n{}",
            errors.len(),
            found.len(),
            errors.join("\n")
        );
    }
    Ok(found.len())
}

/// The bit patterns of every f32 literal `spec`'s traced functions use, each also negated:
/// the printer writes a negative literal as the negation of a positive one.
pub fn model_literals(spec: &Spec) -> HashSet<u32> {
    let e = spec.emitted();
    let module = &e.module;
    let values = module.funcs.iter().flat_map(|f| &f.nodes);
    values
        .filter_map(|n| match n.op {
            Op::ConstF(v) => Some(v.to_bits()),
            _ => None,
        })
        .flat_map(|bits| [bits, bits ^ 0x8000_0000])
        .collect()
}

/// Whether a float literal's digits are all zero (a hex mantissa ends at its exponent, a
/// decimal one at its exponent or suffix).
fn written_zero(literal: &str) -> bool {
    let (digits, radix) = match literal.strip_prefix("0x").or(literal.strip_prefix("0X")) {
        Some(hex) => (hex.split(['p', 'P']).next(), 16),
        None => (literal.split(|c: char| c.is_ascii_alphabetic()).next(), 10),
    };
    let digits = digits.unwrap_or_default().chars();
    digits.filter_map(|c| c.to_digit(radix)).all(|d| d == 0)
}

/// Whether the decimal `body` (no sign, no suffix) is above FLT_MAX, from its exact digits.
fn decimal_above_max(body: &str) -> bool {
    let (mantissa, exponent) = match body.find(['e', 'E']) {
        Some(e) => (&body[..e], &body[e + 1..]),
        None => (body, "0"),
    };
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let digits = format!("{int}{frac}");
    let lead = digits.trim_start_matches('0');
    let significant = lead.trim_end_matches('0');
    if significant.is_empty() {
        return false;
    }
    // Saturated: an exponent beyond i64 is far out of range either way.
    let exponent: i64 = exponent.parse().unwrap_or(if exponent.starts_with('-') {
        i64::MIN / 2
    } else {
        i64::MAX / 2
    });
    // The decimal exponent of the first significant digit.
    let first = exponent + int.len() as i64 - (digits.len() - lead.len()) as i64 - 1;
    match first.cmp(&FLT_MAX_EXPONENT) {
        // Trailing zeros dropped on both sides, so where one is a prefix of the other,
        // the longer is the larger.
        Ordering::Equal => significant > FLT_MAX_DIGITS,
        other => other == Ordering::Greater,
    }
}

/// A hex float's body (after `0x`, suffix off) as `(m + sticky) · 2^e2`: `m` holds its
/// first 124 significant bits, `sticky` whether any nonzero digit lies beyond them.
fn hex_value(body: &str) -> Result<(u128, bool, i64)> {
    let (mantissa, exponent) = body.split_once(['p', 'P']).unwrap_or((body, "0"));
    let exponent: i64 = exponent
        .parse()
        .map_err(|_| anyhow!("hex float exponent `{exponent}`"))?;
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let (mut m, mut sticky, mut e2) = (0u128, false, exponent - 4 * frac.len() as i64);
    for d in int.chars().chain(frac.chars()) {
        let d = d.to_digit(16).expect("a hex digit");
        if m >> 120 == 0 {
            m = m << 4 | u128::from(d);
        } else {
            sticky |= d != 0;
            e2 += 4;
        }
    }
    Ok((m, sticky, e2))
}

/// `(m + sticky) · 2^e2` rounded to nearest even with `precision` significant bits and no
/// exponent below `min_exponent` (denormals): `Some((s, q))` for `s · 2^q`, `None` beyond
/// any finite value of the precision's type.
fn round_binary(
    m: u128,
    sticky: bool,
    e2: i64,
    precision: i64,
    min_exponent: i64,
) -> Option<(u64, i64)> {
    if m == 0 {
        return Some((0, 0));
    }
    let leading = e2 + 127 - i64::from(m.leading_zeros());
    let q = (leading - (precision - 1)).max(min_exponent);
    let shift = q - e2;
    let s = if shift <= 0 {
        (m << -shift) as u64
    } else if shift > 128 {
        0
    } else {
        let kept = if shift == 128 { 0 } else { m >> shift };
        let rest = m & (u128::MAX >> (128 - shift));
        let half = 1u128 << (shift - 1);
        let up = rest > half || (rest == half && (sticky || kept & 1 == 1));
        (kept + u128::from(up)) as u64
    };
    // The largest exponent of f32 (precision 24) or f64 (53) values.
    let max_leading = if precision == 24 { 127 } else { 1023 };
    (q + 63 - i64::from(s.leading_zeros()) <= max_leading).then_some((s, q))
}

/// Whether `(m + sticky) · 2^e2` is above FLT_MAX = (2^24 − 1) · 2^104.
fn hex_above_max(m: u128, sticky: bool, e2: i64) -> bool {
    if m == 0 {
        return false;
    }
    let leading = e2 + 127 - i64::from(m.leading_zeros());
    let width = 128 - i64::from(m.leading_zeros());
    // At FLT_MAX's binade, above it exactly where a bit below its 24 is set.
    let beyond = width > 24 && m & (u128::MAX >> (128 - (width - 24))) != 0;
    leading > 127 || (leading == 127 && (beyond || sticky))
}
