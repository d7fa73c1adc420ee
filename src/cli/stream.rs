//! `encode` and `decode`: the CPU codec over stdin/stdout. Every line is parsed before
//! anything is printed, so a malformed line yields an error and no partial output.

use crate::codecs::Spec;
use crate::codecs::functions::{Function, Role};
use anyhow::{Result, bail};
use std::io::{Read, Write};

/// A number; `inf` and `nan` are accepted as written, but a finite number too large for
/// f32 (`1e50`) is an error rather than a silent infinity.
fn parse_f32(t: &str) -> Result<f32, ()> {
    let v: f32 = t.parse().map_err(|_| ())?;
    let spelled = t.to_ascii_lowercase().contains("inf");
    if v.is_infinite() && !spelled {
        Err(())
    } else {
        Ok(v)
    }
}

fn parse_vector(line: &str) -> Option<[f32; 3]> {
    let mut it = line.split_whitespace().map(parse_f32);
    let v = [it.next()?.ok()?, it.next()?.ok()?, it.next()?.ok()?];
    it.next().is_none().then_some(v)
}

fn parse_code(line: &str, words: usize) -> Option<Vec<u32>> {
    let t = line.trim();
    let t = t
        .strip_prefix("0x")
        .or_else(|| t.strip_prefix("0X"))
        .unwrap_or(t);
    let v = u64::from_str_radix(t, 16).ok()?;
    if words == 1 {
        Some(vec![u32::try_from(v).ok()?])
    } else {
        // Two-word codes hold 48 bits (snorm16×3).
        (v >> 48 == 0).then(|| vec![v as u32, (v >> 32) as u32])
    }
}

fn format_code(w: &[u32]) -> String {
    match w {
        [a] => format!("0x{a:08x}"),
        [a, b] => format!("0x{:012x}", (u64::from(*b) << 32) | u64::from(*a)),
        _ => unreachable!(),
    }
}

/// Runs the codec over `input`, returning all output lines or the first bad line's error.
pub fn transform(spec: &Spec, encode: bool, input: &str) -> Result<String> {
    if spec.info().domain.is_none() {
        bail!(
            "{} is a packing helper, not a codec: it has no encode/decode",
            spec.id()
        );
    }
    let e = spec.emitted();
    let role = if encode { Role::Encode } else { Role::Decode };
    let f: &Function = e
        .functions
        .iter()
        .find(|f| f.role == role)
        .expect("codec function");
    let mut out = String::new();
    let mut res = vec![0u32; f.out_words];
    for (n, line) in input.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        if encode {
            let Some(v) = parse_vector(line) else {
                bail!(
                    "line {}: expected three numbers `x y z`, got {line:?}",
                    n + 1
                );
            };
            (f.eval)(&v.map(f32::to_bits), &mut res);
            out.push_str(&format_code(&res));
        } else {
            let Some(code) = parse_code(line, f.in_words) else {
                let max = if f.in_words == 1 { "8" } else { "12" };
                bail!(
                    "line {}: expected a hex code of at most {max} digits, got {line:?}",
                    n + 1
                );
            };
            (f.eval)(&code, &mut res);
            let v = res
                .iter()
                .map(|b| format!("{:?}", f32::from_bits(*b)))
                .collect::<Vec<_>>();
            out.push_str(&v.join(" "));
        }
        out.push('\n');
    }
    Ok(out)
}

pub fn run(spec: &Spec, encode: bool) -> Result<i32> {
    let mut input = String::new();
    std::io::stdin().read_to_string(&mut input)?;
    let out = transform(spec, encode, &input)?;
    std::io::stdout().write_all(out.as_bytes())?;
    Ok(0)
}
