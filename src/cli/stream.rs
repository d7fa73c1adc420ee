//! `encode`, `decode` and `transcode`: the CPU codec as a stream filter, in bounded memory
//! whatever the input size (one line, or one block of records, at a time). `transcode`
//! reads one spec's codes as `decode` does and writes another's as `encode` does.
//!
//! Text input: output line N answers input line N. Blank lines and lines whose first
//! non-blank character is `#` are copied unchanged (with binary output they produce no
//! record); a UTF-8 byte-order mark at the start is skipped; `\r\n` line ends are
//! accepted; output lines end in `\n`. Lines longer than [`MAX_LINE`] bytes are an error.
//!
//! A tangent-frame spec (`qtangent64`, `godot_axis_angle`) reads and writes frames
//! instead of vectors: seven numbers `nx ny nz tx ty tz w`, the normal, the tangent and the
//! bitangent's sign (glTF's convention).
//!
//! Binary input and output are raw little-endian records, for pipelines that move many
//! vectors: a vector is 12 bytes (three `f32`), a frame 28 (seven `f32`), a code one `u32`
//! per word of the spec: 4 bytes, 8 for specs wider than 32 bits (snorm16x3), 12 above 64
//! (float32x3).
//!
//! The first bad line or record ends the run with an error naming it. Output before it
//! has been written (to stdout) or is discarded (`--out`, see [`crate::support::atomic`]).

use super::grammar::{self, LineError, quote};
use crate::api::{RoundTrip, Transcoder};
use crate::codecs::Spec;
use crate::codecs::functions::function::{Function, Inputs, Role};
use crate::codecs::toolkit::quant::code_width;
use anyhow::{Result, bail};
use std::io::{BufRead, ErrorKind, Read, Write};

/// The longest text line read, so that memory stays bounded on input without line ends.
pub const MAX_LINE: usize = 1 << 20;

/// Records processed per block in binary mode.
const BLOCK: usize = 8192;

/// How records are written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// Lines (see below).
    Text,
    /// Raw little-endian records (see below).
    Binary,
}

/// Which way the codec runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    Encode,
    Decode,
}

/// A spec's encoder or decoder on raw words, with what its codes look like.
struct Codec {
    f: Function,
    /// The spec as the user may type it, for messages.
    name: String,
    dir: Direction,
    bits: u32,
    /// 32-bit words per code (1; 2 or 3 above 32 bits).
    code_words: usize,
    /// Floats per decoded record: 3 for a vector, 7 for a tangent frame (`n`, then `t`
    /// with the bitangent's sign in `w`).
    floats: usize,
}

impl Codec {
    fn new(spec: &Spec, dir: Direction) -> Result<Codec> {
        if spec.info().domain.is_none() && !spec.family().frames() {
            bail!(
                "{} is a helper, not a codec: it has no encode/decode",
                spec.id()
            );
        }
        let role = match dir {
            Direction::Encode => Role::Encode,
            Direction::Decode => Role::Decode,
        };
        let emitted = spec.emitted();
        // The code's width is its fields' (a texel layout's code is the whole RGBA8 texel,
        // 32 bits, though it holds 16 bits of parameters).
        let bits = emitted
            .functions
            .iter()
            .find_map(|f| match &f.inputs {
                Inputs::Codes(q) => Some(code_width(q)),
                _ => None,
            })
            .unwrap_or(spec.bits());
        let Some(f) = emitted.cpu_function(role).cloned() else {
            bail!("{} has no {role:?} function", spec.id());
        };
        let (code_words, floats) = match dir {
            Direction::Encode => (f.out_words, f.in_words),
            Direction::Decode => (f.in_words, f.out_words),
        };
        Ok(Codec {
            f,
            name: spec.to_string(),
            dir,
            bits,
            code_words,
            floats,
        })
    }

    fn code_bytes(&self) -> usize {
        4 * self.code_words
    }

    fn in_bytes(&self) -> usize {
        match self.dir {
            Direction::Encode => 4 * self.floats,
            Direction::Decode => self.code_bytes(),
        }
    }
}

/// What a stream computes: how its records are read, how its results are written, and
/// the computation between.
trait Records {
    /// The codec whose input the stream reads: vectors to encode, or codes of its width.
    fn reads(&self) -> &Codec;
    /// The codec whose output the stream writes.
    fn writes(&self) -> &Codec;
    /// `input`'s records into `out`, one at a time (text) or a `block` on SIMD lanes (the
    /// same bits).
    fn compute(&mut self, input: &[u32], out: &mut [u32], block: bool);
}

impl Records for Codec {
    fn reads(&self) -> &Codec {
        self
    }
    fn writes(&self) -> &Codec {
        self
    }
    fn compute(&mut self, input: &[u32], out: &mut [u32], block: bool) {
        if block {
            self.f.eval_many(input, out);
        } else {
            (self.f.eval)(input, out);
        }
    }
}

/// `transcode`: one spec's codes decoded and encoded as another's, each round trip
/// measured ([`Transcoder`]). `from` and `to` give the stream its rules for reading
/// `from`'s codes and writing `to`'s, the transcoder computes.
struct Transcoding {
    from: Codec,
    to: Codec,
    t: Transcoder,
    error: RoundTrip,
}

impl Records for Transcoding {
    fn reads(&self) -> &Codec {
        &self.from
    }
    fn writes(&self) -> &Codec {
        &self.to
    }
    fn compute(&mut self, input: &[u32], out: &mut [u32], _block: bool) {
        self.error = self.error.then(self.t.transcode(input, out));
    }
}

/// A code's words as one number, first word lowest.
fn code_value(w: &[u32]) -> u128 {
    w.iter()
        .rev()
        .fold(0, |acc, &x| (acc << 32) | u128::from(x))
}

/// Writes one result in `to`'s form.
fn put(c: &Codec, res: &[u32], to: Format, out: &mut dyn Write) -> std::io::Result<()> {
    match (c.dir, to) {
        (Direction::Encode, Format::Text) => match c.code_words {
            1 => writeln!(out, "0x{:08x}", res[0]),
            n => writeln!(
                out,
                "0x{:0w$x}",
                code_value(&res[..n]),
                w = c.bits.div_ceil(4) as usize
            ),
        },
        // Little-endian words, first word first: one little-endian integer of the width.
        (Direction::Encode, Format::Binary) => res[..c.code_words]
            .iter()
            .try_for_each(|w| out.write_all(&w.to_le_bytes())),
        (Direction::Decode, Format::Text) => {
            let text: Vec<String> = res[..c.floats]
                .iter()
                .map(|&w| format!("{:?}", f32::from_bits(w)))
                .collect();
            writeln!(out, "{}", text.join(" "))
        }
        (Direction::Decode, Format::Binary) => {
            for w in &res[..c.floats] {
                out.write_all(&w.to_le_bytes())?;
            }
            Ok(())
        }
    }
}

/// Runs `spec`'s encoder or decoder from `input` to `output`; returns the records done.
/// A failed write is a `WriteError`.
pub fn filter(
    spec: &Spec,
    dir: Direction,
    from: Format,
    to: Format,
    input: &mut dyn BufRead,
    output: &mut dyn Write,
) -> Result<u64> {
    let mut c = Codec::new(spec, dir)?;
    run(&mut c, from, to, input, output)
}

/// Reads codes of `from_spec` from `input` and writes those of `to_spec` for the same
/// vectors to `output`; returns the round trips' error ([`RoundTrip`]). A failed write is
/// a `WriteError`.
pub fn transcode(
    (from_spec, to_spec): (&Spec, &Spec),
    from: Format,
    to: Format,
    input: &mut dyn BufRead,
    output: &mut dyn Write,
) -> Result<RoundTrip> {
    if let Some(s) = [from_spec, to_spec]
        .into_iter()
        .find(|s| s.family().frames())
    {
        bail!(
            "{} codes tangent frames: `unitpack transcode` moves vector codes",
            s.id()
        );
    }
    let mut t = Transcoding {
        from: Codec::new(from_spec, Direction::Decode)?,
        to: Codec::new(to_spec, Direction::Encode)?,
        t: Transcoder::new(&from_spec.to_string(), &to_spec.to_string())?,
        error: RoundTrip::default(),
    };
    run(&mut t, from, to, input, output)?;
    Ok(t.error)
}

fn run(
    r: &mut dyn Records,
    from: Format,
    to: Format,
    input: &mut dyn BufRead,
    output: &mut dyn Write,
) -> Result<u64> {
    match from {
        Format::Text => text_in(r, to, input, output),
        Format::Binary => binary_in(r, to, input, output),
    }
}

/// A failed write of the output, kept apart from input errors so that the caller can name
/// its output in the message (`cannot write to stdout: …`).
#[derive(Debug, thiserror::Error)]
#[error("cannot write the output: {0}")]
pub struct WriteError(pub std::io::Error);

fn write_err(e: std::io::Error) -> anyhow::Error {
    anyhow::Error::new(WriteError(e))
}

fn read_err(e: std::io::Error) -> anyhow::Error {
    anyhow::Error::new(e).context("cannot read the input")
}

fn text_in(
    r: &mut dyn Records,
    to: Format,
    input: &mut dyn BufRead,
    out: &mut dyn Write,
) -> Result<u64> {
    let (iw, ow) = (r.reads().f.in_words, r.writes().f.out_words);
    let mut buf = Vec::with_capacity(256);
    let mut res = [0u32; 7];
    let (mut n, mut done) = (0u64, 0u64);
    loop {
        buf.clear();
        let got = (&mut *input)
            .take(MAX_LINE as u64 + 1)
            .read_until(b'\n', &mut buf)
            .map_err(read_err)?;
        if got == 0 {
            break;
        }
        n += 1;
        if buf.last() == Some(&b'\n') {
            buf.pop();
            if buf.last() == Some(&b'\r') {
                buf.pop();
            }
        }
        if buf.len() > MAX_LINE {
            bail!("line {n}: longer than {MAX_LINE} bytes");
        }
        let mut bytes = &buf[..];
        if n == 1 {
            bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
        }
        let line = std::str::from_utf8(bytes).map_err(|e| {
            anyhow::anyhow!(
                "line {n}: not valid UTF-8 (bad byte at column {})",
                e.valid_up_to() + 1
            )
        })?;
        let body = line.trim_start_matches([' ', '\t']);
        if body.is_empty() || body.starts_with('#') {
            if to == Format::Text {
                out.write_all(line.as_bytes())
                    .and_then(|()| out.write_all(b"\n"))
                    .map_err(write_err)?;
            }
            continue;
        }
        let c = r.reads();
        let bad = |e: LineError| match e {
            LineError::TooWide { bits } => anyhow::anyhow!(
                "line {n}: {} has bits set above {}'s width of {bits} bits (largest code 0x{:x})",
                quote(line.trim()),
                c.name,
                grammar::max_code(bits)
            ),
            e => anyhow::anyhow!("line {n}: {e}: {}", quote(line)),
        };
        let mut words = [0u32; 7];
        match c.dir {
            Direction::Encode if c.floats == 7 => {
                words = grammar::parse_frame(line).map_err(bad)?.map(f32::to_bits);
            }
            Direction::Encode => {
                let v = grammar::parse_vector(line).map_err(bad)?;
                words[..3].copy_from_slice(&v.map(f32::to_bits));
            }
            Direction::Decode => {
                let v = grammar::parse_code(line, c.bits).map_err(bad)?;
                words[..3].copy_from_slice(&[0, 32, 64].map(|sh| (v >> sh) as u32));
            }
        }
        r.compute(&words[..iw], &mut res[..ow], false);
        put(r.writes(), &res, to, out).map_err(write_err)?;
        done += 1;
    }
    Ok(done)
}

/// Fills `buf` from `input` as far as it goes; returns the bytes read (short only at EOF).
fn fill(input: &mut dyn Read, buf: &mut [u8]) -> Result<usize> {
    let mut got = 0;
    while got < buf.len() {
        match input.read(&mut buf[got..]) {
            Ok(0) => break,
            Ok(k) => got += k,
            Err(e) if e.kind() == ErrorKind::Interrupted => {}
            Err(e) => return Err(read_err(e)),
        }
    }
    Ok(got)
}

/// What text given as binary input (`--format binary` meant for the output alone) is told:
/// it reads as records of nonsense or ends mid-record.
const TEXT_AS_BINARY: &str = "the input looks like text: binary input is raw little-endian \
                              words, and text in with binary out is --input-format text \
                              --output-format binary";

/// Whether the start of a binary input is text: printable ASCII and whitespace only, with
/// a space or line break in it, as numbers typed or printed are (raw floats and codes hold
/// other bytes almost always).
fn looks_like_text(start: &[u8]) -> bool {
    !start.is_empty()
        && start
            .iter()
            .all(|&b| b.is_ascii_graphic() || matches!(b, b' ' | b'\t' | b'\n' | b'\r'))
        && start.iter().any(|&b| matches!(b, b' ' | b'\t' | b'\n'))
}

fn binary_in(
    r: &mut dyn Records,
    to: Format,
    input: &mut dyn BufRead,
    out: &mut dyn Write,
) -> Result<u64> {
    let c = r.reads();
    let size = c.in_bytes();
    let (iw, ow) = (c.f.in_words, r.writes().f.out_words);
    let (bits, name, dir, code_words, floats) =
        (c.bits, c.name.clone(), c.dir, c.code_words, c.floats);
    let mut block = vec![0u8; size * BLOCK];
    let mut results = vec![0u32; ow * BLOCK];
    let mut words = Vec::with_capacity(iw * BLOCK);
    let mut done = 0u64;
    let noun = match dir {
        Direction::Encode if floats == 7 => "a frame is 28 bytes, 7×f32",
        Direction::Encode => "a vector is 12 bytes, 3×f32",
        Direction::Decode if code_words == 1 => "a code is 4 bytes, u32",
        Direction::Decode if code_words == 2 => "a code is 8 bytes, u64",
        Direction::Decode => "a code is 12 bytes, 3×u32",
    };
    // Text where raw words were asked for (`--format binary` meant for the output alone)
    // reads as records of nonsense or ends mid-record: said once, at the start.
    let mut text_hint = "";
    loop {
        let got = fill(input, &mut block)?;
        if done == 0 && text_hint.is_empty() && looks_like_text(&block[..got.min(64)]) {
            text_hint = TEXT_AS_BINARY;
            // Records that will run: said now. Else the error below says it.
            if got >= size {
                eprintln!("warning: {TEXT_AS_BINARY}");
            }
        }
        let records = got / size;
        let word = |i: usize, j: usize| {
            let b = &block[i * size + 4 * j..][..4];
            u32::from_le_bytes([b[0], b[1], b[2], b[3]])
        };
        // Every record before the first bad one is written, then the error names it.
        let too_wide = |i: usize| {
            let w: [u32; 3] = std::array::from_fn(|j| if j < iw { word(i, j) } else { 0 });
            Some(code_value(&w[..iw])).filter(|v| *v > grammar::max_code(bits))
        };
        let bad = match dir {
            Direction::Decode => (0..records).find_map(|i| too_wide(i).map(|v| (i, v))),
            Direction::Encode => None,
        };
        let good = bad.map_or(records, |(i, _)| i);
        // Eight (AVX2) or four (SSE2) records per step on SIMD lanes: the same bits as one at
        // a time.
        words.clear();
        words.extend((0..good * iw).map(|k| word(k / iw, k % iw)));
        r.compute(&words, &mut results[..good * ow], true);
        for res in results[..good * ow].chunks_exact(ow) {
            put(r.writes(), res, to, out).map_err(write_err)?;
        }
        done += good as u64;
        if let Some((_, v)) = bad {
            bail!(
                "record {}: code 0x{v:x} has bits set above {}'s width of {} bits (largest code 0x{:x})",
                done + 1,
                name,
                bits,
                grammar::max_code(bits)
            );
        }
        if got % size != 0 {
            bail!(
                "the input ends {} bytes into record {} ({noun}){}{text_hint}",
                got % size,
                done + 1,
                if text_hint.is_empty() { "" } else { "; " }
            );
        }
        if got < block.len() {
            return Ok(done);
        }
    }
}
