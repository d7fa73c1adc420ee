//! How the emitted languages spell a constant: the one text of each f32 and u32 that
//! every compiler reads back as the model's value. The printer writes its constants with
//! these, and the language backends theirs (WGSL's bitcast for ±FLT_MAX).

/// The shortest decimal that reads back as exactly `v` by every rule a compiler reads a
/// float literal with, and never lies above the largest finite f32:
/// - directly, the exact decimal rounded to the nearest f32;
/// - through f64 (compilers that parse a literal as double and then narrow it, WGSL's
///   abstract floats among them, must land on the same f32);
/// - in range: Rust's shortest round trip of `f32::MAX` is `3.4028235e38`, above
///   FLT_MAX = 3.40282346638…e38. It rounds to FLT_MAX in IEEE arithmetic, but WGSL makes
///   an abstract float beyond f32's range a shader-creation error (Tint rejects it), and
///   GLSL ES compilers (ANGLE) read it as infinity. So a decimal is kept only where its
///   magnitude is at most FLT_MAX: for ±FLT_MAX that is `3.4028234e38`.
///
/// At each precision the candidates are the decimal rounded to nearest and the decimal
/// truncated toward zero (which never exceeds `|v|`, so it is the in-range one where the
/// rounded one lies above FLT_MAX). Below FLT_MAX every decimal that reads back as `v` lies
/// below the midpoint to the next f32, so only ±FLT_MAX can round out of range.
/// `src/verify/literals.rs` checks every literal of every emitted include by these rules.
pub fn f32_literal(v: f32) -> String {
    assert!(
        v.is_finite(),
        "non-finite literal {v}: compare against f32::MAX instead"
    );
    let reads_back = |s: &str| {
        s.parse::<f32>().map(f32::to_bits) == Ok(v.to_bits())
            && s.parse::<f64>().map(|d| (d as f32).to_bits()) == Ok(v.to_bits())
    };
    let debug = format!("{v:?}");
    let mut s = if reads_back(&debug) && v.abs() < f32::MAX {
        debug
    } else {
        // Every f32's decimal expansion ends within 112 significant digits: this is exact.
        // (Only here: the exact expansion costs more than the rest of a function's text.)
        let expansion = format!("{:.120e}", v);
        let (mantissa, exponent) = expansion.split_once('e').expect("exponential form");
        let truncated = |p: usize| {
            // `p` significant digits: the leading one, the point, then `p - 1` more.
            let digits = &mantissa[..mantissa.find('.').expect("a point") + p];
            format!("{}e{exponent}", digits.trim_end_matches('.'))
        };
        (1..=17)
            .flat_map(|p| {
                let rounded = format!("{:.*e}", p - 1, v);
                let truncated = truncated(p);
                // The rounded decimal lies above `|v|` only where it differs from the
                // truncated one; above FLT_MAX only where `|v|` is FLT_MAX.
                let in_range = v.abs() < f32::MAX || rounded == truncated;
                [in_range.then_some(rounded), Some(truncated)]
            })
            .flatten()
            .find(|s| reads_back(s))
            .expect("f32 round trip")
    };
    if !s.contains(['.', 'e']) {
        s.push_str(".0");
    }
    s
}

/// A u32 constant as a programmer reads it: a bit pattern in hex, other values in decimal.
/// A value from 256 up is a bit pattern where at least half its hex digits are 0 or f:
/// masks and exponent fields (`0x7f800000u`, `0xffffu`, `0xff00u`, `0x3ff7ffu`), not
/// counts and offsets (`1000u`, `281u`, `32586u`).
pub fn u32_literal(v: u32) -> String {
    let hex = format!("{v:x}");
    let plain = hex.bytes().filter(|&d| d == b'0' || d == b'f').count();
    if v >= 0x100 && 2 * plain >= hex.len() {
        format!("0x{hex}u")
    } else {
        format!("{v}u")
    }
}
