//! CPU codec throughput in vectors per second, with a baseline measured in the same run
//! (normalizing the same vectors in f32) so that results compare across machines as ratios.
//! Also the `encode`/`decode` stream filter (`unitpack::cli::transcode`) over in-memory
//! buffers, in its raw binary format and in text, to show what a pipeline gets end to end.
//! Run: `cargo bench`.

use std::hint::black_box;
use std::time::Instant;
use unitpack::api::{CpuCodec, Encoder, HemiOct, Oct};
use unitpack::cli::{Direction, Format, transcode};
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

fn bench<C: Codec>(name: &str, e: Encoder<C>, vs: &[[f32; 3]], base: f64)
where
    C::C<f32>: Default + Copy,
{
    let mut codes = vec![C::C::<f32>::default(); N];
    let enc = rate(|| e.encode_slice(black_box(vs), &mut codes));
    let mut out = vec![[0f32; 3]; N];
    let dec = rate(|| e.decode_slice(black_box(&codes), &mut out));
    println!(
        "{name:<10} encode {:>7.1} M/s ({:>5.2}× baseline)   decode {:>7.1} M/s ({:>5.2}× baseline)",
        enc / 1e6,
        enc / base,
        dec / 1e6,
        dec / base
    );
}

fn main() {
    let vs = unitpack::quality::random_unit_vectors(1, N, false);
    let mut norm = vec![[0f32; 3]; N];
    let base = rate(|| {
        for (o, v) in norm.iter_mut().zip(black_box(&vs)) {
            let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            *o = v.map(|x| x / l);
        }
        black_box(&mut norm);
    });
    println!("baseline (normalize) {:.1} M vectors/s", base / 1e6);
    for bits in [16, 24, 32] {
        bench(
            &format!("oct{bits}"),
            Oct::new(bits).unwrap().fast(),
            &vs,
            base,
        );
        bench(
            &format!("oct{bits}p"),
            Oct::new(bits).unwrap().precise(),
            &vs,
            base,
        );
    }
    bench("hemioct24", HemiOct::new(24).unwrap().fast(), &vs, base);
    for spec in ["oct16", "oct24p", "snorm16x3"] {
        stream(spec, &vs, Format::Binary);
    }
    stream("oct16", &vs, Format::Text);
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
        let n = transcode(&spec, dir, format, format, &mut black_box(input), out).unwrap();
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
