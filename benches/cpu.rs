//! CPU codec throughput in vectors per second, with a baseline measured in the same run
//! (normalizing the same vectors in f32) so that results compare across machines as ratios.
//! The typed slices (`Encoder::encode_slice`) and `Batch` both run the model eight vectors
//! per step on AVX2 lanes where the processor has them (chosen at run time; the typed
//! slices compiled for AVX-512VL where it has that too), else four on SSE2 lanes
//! (`unitpack::model::lanes`, `avx2_lanes`). Beside oct16 and oct32, the peer they
//! replace: meshoptimizer's octahedral vertex filter (`meshopt_encodeFilterOct` /
//! `meshopt_decodeFilterOct`, 8- and 16-bit components, through the `meshopt` crate),
//! measured in the same run on the same vectors, as ratios (above 1: unitpack is faster). meshoptimizer decodes snorm integers to snorm integers in place with
//! SIMD; unitpack's decode writes f32×3, more work, and the ratio is printed as it stands.
//! Also the `encode`/`decode` stream filter (`unitpack::cli::filter`) over in-memory
//! buffers, in its raw binary format and in text, to show what a pipeline gets end to end.
//! And the model's reference evaluation, one call per item against one over a slice.
//! And tangent frames: qtangent64 through `FrameBatch` beside a scalar port of Filament's
//! `packTangentFrame` and `toTangentFrame` (the oracle `tests/families/oracles/filament.rs`,
//! one frame at a time as Filament's `SurfaceOrientation` and a CPU decoder run them), on
//! the same frames in the same run, as ratios (above 1: unitpack is faster).
//! Run: `cargo bench`.

use std::hint::black_box;
use std::time::Instant;
use unitpack::api::{Batch, CpuCodec, Encoder, Frame, FrameBatch, HemiOct, Oct};
use unitpack::cli::{Direction, Format, filter};
use unitpack::codecs::{Codec, Spec};

const N: usize = 1 << 20;

fn rate(mut f: impl FnMut()) -> f64 {
    f(); // warm up
    let t = Instant::now();
    let mut runs = 0;
    while t.elapsed().as_secs_f64() < 0.5 {
        f();
        runs += 1;
    }
    (runs * N) as f64 / t.elapsed().as_secs_f64()
}

/// Prints and returns the encode and decode rates of `e`.
fn bench<C: Codec>(name: &str, e: Encoder<C>, vs: &[[f32; 3]], base: f64) -> (f64, f64)
where
    C::C<f32>: Default + Copy,
{
    let mut codes = vec![C::C::<f32>::default(); N];
    let enc = rate(|| e.encode_slice(black_box(vs), &mut codes));
    let mut out = vec![[0f32; 3]; N];
    let dec = rate(|| e.decode_slice(black_box(&codes), &mut out));
    println!(
        "{name:<12} encode {:>7.1} M/s ({:>5.2}× baseline)   decode {:>7.1} M/s ({:>5.2}× baseline)",
        enc / 1e6,
        enc / base,
        dec / 1e6,
        dec / base
    );
    (enc, dec)
}

/// The encode and decode rates of [`Batch`] (the same lanes as the typed slices,
/// through one non-generic entry point compiled inside unitpack), printed beside the typed
/// encoder's.
fn batch(spec: &str, vs: &[[f32; 3]], base: f64) -> (f64, f64) {
    let b = Batch::new(spec).unwrap();
    let mut codes = vec![0u32; N * b.words()];
    let enc = rate(|| b.encode(black_box(vs), &mut codes));
    let mut out = vec![[0f32; 3]; N];
    let dec = rate(|| b.decode(black_box(&codes), &mut out));
    println!(
        "{:<12} encode {:>7.1} M/s ({:>5.2}× baseline)   decode {:>7.1} M/s ({:>5.2}× baseline)",
        format!("{spec} Batch"),
        enc / 1e6,
        enc / base,
        dec / 1e6,
        dec / base
    );
    (enc, dec)
}

/// meshoptimizer's octahedral filter with `bits`-bit components (8 or 16), as
/// `(encode, decode)` rates: the encoder into a buffer allocated once (the crate's safe
/// wrapper allocates per call), the decoder in place, as the library is meant to be used.
fn meshopt_oct(bits: i32, vs: &[[f32; 3]]) -> (f64, f64) {
    let input: Vec<[f32; 4]> = vs.iter().map(|v| [v[0], v[1], v[2], 0.0]).collect();
    let stride = if bits <= 8 { 4 } else { 8 };
    let mut codes = vec![0u8; N * stride];
    let encode = |codes: &mut [u8]| {
        // SAFETY: `codes` holds N vectors of `stride` bytes and `input` N vectors of four
        // floats, the sizes meshopt_encodeFilterOct reads and writes for this stride.
        unsafe {
            meshopt::ffi::meshopt_encodeFilterOct(
                codes.as_mut_ptr().cast(),
                N,
                stride,
                bits,
                black_box(input.as_ptr()).cast(),
            )
        }
    };
    let enc = rate(|| encode(&mut codes));
    // The decoder filters in place; its work does not depend on the values, so later
    // runs filter the previous run's output (no copy in the timed loop).
    let dec = rate(|| {
        // SAFETY: `codes` holds N vectors of `stride` bytes, filtered in place.
        unsafe { meshopt::ffi::meshopt_decodeFilterOct(codes.as_mut_ptr().cast(), N, stride) }
        black_box(&mut codes);
    });
    (enc, dec)
}

/// unitpack's rates for one spec over meshoptimizer's at the same component size.
fn ratios(name: &str, (enc, dec): (f64, f64), (m_enc, m_dec): (f64, f64)) {
    println!(
        "{name:<13} vs meshopt: encode {:>5.2}×   decode {:>5.2}×   (meshopt {:>7.1} / {:>7.1} M/s)",
        enc / m_enc,
        dec / m_dec,
        m_enc / 1e6,
        m_dec / 1e6
    );
}

#[path = "../tests/families/oracles/filament.rs"]
mod filament;

/// Frames coded per pass in [`frames`]: 16384 frames (448 KiB, the codes 128 KiB) stay in
/// the second-level cache, so that the codecs' arithmetic is measured rather than the
/// memory's bandwidth, which a pass over 2^20 frames (29 MiB each way) reaches.
const FRAMES: usize = 1 << 14;

/// qtangent64's `FrameBatch` encode and decode rates over the scalar Filament port's, on
/// the verify inputs' first [`FRAMES`] frames (seeded and edge frames), [`N`] frames per
/// timed run as `N / FRAMES` passes over them.
fn frames() {
    let seeded = unitpack::codecs::functions::inputs::frames();
    let frames: Vec<Frame> = seeded
        .chunks_exact(7)
        .take(FRAMES)
        .map(|x| {
            let f = |i: usize| f32::from_bits(x[i]);
            Frame {
                n: [f(0), f(1), f(2)],
                t: [f(3), f(4), f(5), f(6)],
            }
        })
        .collect();
    let b = FrameBatch::new("qtangent64").unwrap();
    let passes = || 0..N / FRAMES;
    let mut codes = vec![0u32; FRAMES * b.words()];
    let enc = rate(|| passes().for_each(|_| b.encode(black_box(&frames), &mut codes)));
    let mut shorts = vec![[0i16; 4]; FRAMES];
    let peer_enc = rate(|| {
        for _ in passes() {
            for (s, f) in shorts.iter_mut().zip(black_box(&frames)) {
                *s = filament::encode(f.n, [f.t[0], f.t[1], f.t[2]], f.t[3]);
            }
            black_box(&mut shorts);
        }
    });
    let mut back = vec![Frame::default(); FRAMES];
    let dec = rate(|| passes().for_each(|_| b.decode(black_box(&codes), &mut back)));
    let peer_dec = rate(|| {
        for _ in passes() {
            for (s, f) in black_box(&shorts).iter().zip(&mut back) {
                let (n, t, sign) = filament::to_tangent_frame(s.map(filament::fetch));
                *f = Frame {
                    n,
                    t: [t[0], t[1], t[2], sign],
                };
            }
            black_box(&mut back);
        }
    });
    println!(
        "qtangent64 FrameBatch vs scalar Filament: encode {:>5.2}×   decode {:>5.2}×   (ours {:>6.1} / {:>6.1} M/s, Filament {:>6.1} / {:>6.1} M/s)",
        enc / peer_enc,
        dec / peer_dec,
        enc / 1e6,
        dec / 1e6,
        peer_enc / 1e6,
        peer_dec / 1e6
    );
}

fn main() {
    frames();
    let vs = unitpack::support::sampling::random_unit_vectors(1, N, false);
    let mut norm = vec![[0f32; 3]; N];
    let base = rate(|| {
        for (o, v) in norm.iter_mut().zip(black_box(&vs)) {
            let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            *o = v.map(|x| x / l);
        }
        black_box(&mut norm);
    });
    println!("baseline (normalize) {:.1} M vectors/s", base / 1e6);
    let mut peers = Vec::new();
    for bits in [16, 24, 32] {
        let fast = bench(
            &format!("oct{bits}"),
            Oct::new(bits).unwrap().fast(),
            &vs,
            base,
        );
        let precise = bench(
            &format!("oct{bits}p"),
            Oct::new(bits).unwrap().precise(),
            &vs,
            base,
        );
        let lanes = batch(&format!("oct{bits}"), &vs, base);
        let lanes_precise = batch(&format!("oct{bits}p"), &vs, base);
        if bits != 24 {
            let peer = meshopt_oct(bits as i32 / 2, &vs);
            peers.push((bits, [fast, precise, lanes, lanes_precise], peer));
        }
    }
    for (bits, [fast, precise, lanes, lanes_precise], peer) in peers {
        ratios(&format!("oct{bits}"), fast, peer);
        ratios(&format!("oct{bits}p"), precise, peer);
        ratios(&format!("oct{bits} Batch"), lanes, peer);
        ratios(&format!("oct{bits}p Batch"), lanes_precise, peer);
    }
    bench("hemioct24", HemiOct::new(24).unwrap().fast(), &vs, base);
    for spec in ["oct16", "oct24p", "snorm16x3"] {
        stream(spec, &vs, Format::Binary);
    }
    stream("oct16", &vs, Format::Text);
    for (spec, function) in [
        ("oct24p", "decode"),
        ("snorm8x3", "decode"),
        ("oct24p", "encode"),
    ] {
        reference(spec, function);
    }
}

/// The model's `f32` evaluation (`Function::eval`, from which `verify` takes its expected
/// values) of `function`, over the first [`N`] of its verify inputs: called once per item
/// and once for the whole slice, and the ratio (above 1: the whole slice is faster).
fn reference(spec: &str, function: &str) {
    let spec: Spec = spec.parse().unwrap();
    let emitted = spec.emitted();
    let f = emitted
        .functions
        .iter()
        .find(|f| f.name == function)
        .unwrap();
    let input = unitpack::codecs::functions::inputs::generate(&f.inputs, f.in_words);
    let input = &input[..N * f.in_words];
    let mut out = vec![0u32; N * f.out_words];
    let per_item = rate(|| {
        for (i, o) in black_box(input)
            .chunks_exact(f.in_words)
            .zip(out.chunks_exact_mut(f.out_words))
        {
            (f.eval)(i, o);
        }
    });
    let whole = rate(|| (f.eval)(black_box(input), &mut out));
    println!(
        "model {spec} {function:<8} per item {:>6.1} M/s   whole slice {:>6.1} M/s ({:>5.2}×)",
        per_item / 1e6,
        whole / 1e6,
        whole / per_item
    );
}

/// Vectors per second through `transcode`, input and output in `format`, each way.
fn stream(name: &str, vs: &[[f32; 3]], format: Format) {
    let spec: Spec = name.parse().unwrap();
    let vectors: Vec<u8> = match format {
        Format::Binary => vs.iter().flatten().flat_map(|x| x.to_le_bytes()).collect(),
        Format::Text => vs
            .iter()
            .map(|v| format!("{} {} {}\n", v[0], v[1], v[2]))
            .collect::<String>()
            .into_bytes(),
    };
    let mut codes = Vec::new();
    let run = |dir: Direction, input: &[u8], out: &mut Vec<u8>| {
        out.clear();
        let n = filter(&spec, dir, format, format, &mut black_box(input), out).unwrap();
        assert_eq!(n as usize, N);
    };
    let enc = rate(|| run(Direction::Encode, &vectors, &mut codes));
    let mut back = Vec::new();
    let dec = rate(|| run(Direction::Decode, &codes, &mut back));
    let f = format!("{format:?}").to_lowercase();
    println!(
        "stream {name:<10} {f:<6} encode {:>7.1} M vectors/s   decode {:>7.1} M vectors/s",
        enc / 1e6,
        dec / 1e6
    );
}
