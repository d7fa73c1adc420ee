//! What `encode` and `decode` accept on a text line, and how a bad line is quoted.
//!
//! - A vector is three numbers separated by spaces or tabs, each as Rust reads an `f32`
//!   (`1`, `-0.5`, `.5`, `1e-3`, `inf`, `nan`). A finite number beyond the f32 range
//!   (`1e39`) is an error, not a silent infinity.
//! - A code is `0x` (or `0X`) followed by hex digits, or plain decimal digits: `0x7f`,
//!   `127`. Nothing else: no sign, no `0b`/`0o`, no `_`; leading zeros do not mean octal.
//!   It must fit the spec's width (oct16: 16 bits), since a decoder ignores higher bits
//!   and would silently decode something else.

use std::fmt;

/// Characters of a bad line quoted in an error; longer lines are cut.
pub const QUOTE_CHARS: usize = 80;

/// `s` in quotes, cut to [`QUOTE_CHARS`] characters (the byte length is named when cut).
pub fn quote(s: &str) -> String {
    match s.char_indices().nth(QUOTE_CHARS) {
        None => format!("{s:?}"),
        Some((cut, _)) => format!("{:?}… ({} bytes)", &s[..cut], s.len()),
    }
}

/// Why a line is not what was expected; the caller adds the line number.
#[derive(Debug, PartialEq)]
pub enum LineError {
    Count(usize),
    FrameCount(usize),
    NotANumber(String),
    OutOfRange(String),
    NotACode,
    TooWide { bits: u32 },
}

impl fmt::Display for LineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LineError::Count(n) => write!(f, "expected three numbers `x y z`, found {n}"),
            LineError::FrameCount(n) => {
                write!(f, "expected seven numbers `nx ny nz tx ty tz w`, found {n}")
            }
            LineError::NotANumber(t) => write!(f, "{} is not a number", quote(t)),
            LineError::OutOfRange(t) => write!(
                f,
                "{} is outside the f32 range (largest finite magnitude {:e})",
                quote(t),
                f32::MAX
            ),
            LineError::NotACode => {
                f.write_str("expected a code: 0x followed by hex digits, or decimal digits")
            }
            LineError::TooWide { bits } => write!(
                f,
                "the code has bits set above the spec's width of {bits} bits (largest code 0x{:x})",
                max_code(*bits)
            ),
        }
    }
}

/// The largest code of a `bits`-wide spec.
pub fn max_code(bits: u32) -> u128 {
    if bits >= 128 {
        u128::MAX
    } else {
        (1u128 << bits) - 1
    }
}

/// One `f32`; a finite number that rounds to infinity is out of range.
fn parse_f32(t: &str) -> Result<f32, LineError> {
    let v: f32 = t.parse().map_err(|_| LineError::NotANumber(t.into()))?;
    if v.is_infinite() && !t.to_ascii_lowercase().contains("inf") {
        return Err(LineError::OutOfRange(t.into()));
    }
    Ok(v)
}

/// Three numbers `x y z`.
pub fn parse_vector(line: &str) -> Result<[f32; 3], LineError> {
    parse_numbers(line).map_err(|n| n.unwrap_or_else(LineError::Count))
}

/// Seven numbers `nx ny nz tx ty tz w`: a tangent frame's normal, tangent and the
/// bitangent's sign.
pub fn parse_frame(line: &str) -> Result<[f32; 7], LineError> {
    parse_numbers(line).map_err(|n| n.unwrap_or_else(LineError::FrameCount))
}

/// `N` numbers. The error is a bad number's (`Ok`), or the count of numbers found where
/// it is not `N` (`Err`).
fn parse_numbers<const N: usize>(line: &str) -> Result<[f32; N], Result<LineError, usize>> {
    let mut v = [0f32; N];
    let mut n = 0;
    for t in line.split_ascii_whitespace() {
        if n < N {
            v[n] = parse_f32(t).map_err(Ok)?;
        }
        n += 1;
    }
    if n != N {
        return Err(Err(n));
    }
    Ok(v)
}

/// One code of a `bits`-wide spec, in the grammar above.
pub fn parse_code(line: &str, bits: u32) -> Result<u128, LineError> {
    let t = line.trim_matches([' ', '\t']);
    let (digits, radix) = match t.strip_prefix("0x").or_else(|| t.strip_prefix("0X")) {
        Some(h) => (h, 16),
        None => (t, 10),
    };
    if digits.is_empty() || !digits.chars().all(|c| c.is_digit(radix)) {
        return Err(LineError::NotACode);
    }
    // Only digits remain, so the one failure left is overflow.
    let v = u128::from_str_radix(digits, radix).map_err(|_| LineError::TooWide { bits })?;
    if v > max_code(bits) {
        return Err(LineError::TooWide { bits });
    }
    Ok(v)
}
