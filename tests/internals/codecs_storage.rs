//! Where float forms are stored (`src/codecs/core/storage.rs`): the format chosen for a
//! set of fields, as a graphics programmer would pick it from the APIs' format tables;
//! each API's conversion; and, for every spec, that the format's claims hold on the
//! spec's own encoder output (an exact format changes no value a precise float form
//! writes, a wider one rounds them, and a round trip through it errs no more than the
//! packed code's).

use rand_core::Rng;
use rand_pcg::Pcg64Mcg;
use unitpack::codecs::core::storage::{self, Channel, Holds};
use unitpack::codecs::functions::function::Role;
use unitpack::codecs::toolkit::quant::Quant::{self, Half, Single, Snorm, Unorm};
use unitpack::measure::quality::angle_deg;

#[test]
fn a_float_form_goes_to_the_smallest_real_format_that_holds_its_fields() {
    // (fields, WebGPU or vertex name, bits a texel, whether it stores the values exactly)
    let cases: &[(&[Quant], &str, u32, bool)] = &[
        (&[Snorm(8), Snorm(8)], "rg8snorm", 16, true),
        (&[Unorm(8), Unorm(8)], "rg8unorm", 16, true),
        (&[Unorm(4), Unorm(4)], "rg8unorm", 16, true),
        (&[Snorm(8), Snorm(8), Snorm(8)], "rgba8snorm", 32, true),
        (&[Snorm(16), Snorm(16)], "rg16snorm", 32, true),
        (&[Half, Half], "rg16float", 32, true),
        (&[Half, Half, Half], "rgba16float", 64, true),
        (&[Single, Single, Single], "float32x3", 96, true),
        // No 16-bit format has an 8-, a 7- and a 1-bit channel: RGBA8 has them wider.
        (&[Unorm(8), Unorm(7), Unorm(1)], "rgba8unorm", 32, false),
        // RGB10A2 holds 10, 9 and 1 bits in 32 where RGBA8 cannot.
        (&[Unorm(10), Unorm(9), Unorm(1)], "rgb10a2unorm", 32, false),
        (&[Unorm(12), Unorm(12)], "rg16unorm", 32, false),
        (&[Snorm(12), Snorm(12)], "rg16snorm", 32, false),
        // A unorm bit holds in a snorm channel (0 and 1 are snorm values).
        (&[Snorm(8), Snorm(7), Unorm(1)], "rgba8snorm", 32, false),
        (&[Unorm(16), Unorm(15), Unorm(1)], "rgba16unorm", 64, false),
    ];
    for (fields, name, bits, exact) in cases {
        let (r, got_exact) =
            storage::float_form_format(fields).unwrap_or_else(|| panic!("{fields:?} has a format"));
        let got = r.texture.or(r.vertex).unwrap();
        assert_eq!(
            (got, r.bits, got_exact),
            (*name, *bits, *exact),
            "{fields:?}"
        );
    }
    // A snorm field has no unorm channel to go to alone, but snorm formats take it.
    assert!(storage::float_form_format(&[Snorm(33)]).is_none());
}

#[test]
fn a_render_target_stores_what_each_api_converts_to() {
    // A fetch returns c·(1/M) in f32, as the model reads every field.
    let unorm8 = |c: f32| c * (1.0f32 / 255.0);
    let snorm8 = |c: f32| c * (1.0f32 / 127.0);
    // unorm8: round(x·255) to nearest, ties to even; 0.5·255 = 127.5 → 128.
    assert_eq!(Channel::Unorm(8).store(0.5), unorm8(128.0));
    assert_eq!(Channel::Unorm(8).store(-0.25), 0.0);
    assert_eq!(Channel::Unorm(8).store(f32::NAN), 0.0);
    assert_eq!(Channel::Unorm(8).store(1.5), 1.0);
    // 7-bit values c/127 go to the nearest of 255 steps: 5/127·255 = 10.04 → 10.
    assert_eq!(Channel::Unorm(8).store(snorm8(5.0)), unorm8(10.0));
    // snorm8: round(x·127); -1 stays -1; 0.3·127 = 38.1 → 38.
    assert_eq!(Channel::Snorm(8).store(0.3), snorm8(38.0));
    assert_eq!(Channel::Snorm(8).store(-1.0), -1.0);
    assert_eq!(Channel::Snorm(8).store(-7.0), -1.0);
    // 1/3 as binary16: 0x3555, 1365/4096.
    assert_eq!(Channel::Float16.store(1.0 / 3.0), 1365.0 / 4096.0);
    assert_eq!(Channel::Float32.store(0.1), 0.1);
}

/// Seeded unit vectors, uniform on the sphere (or the upper hemisphere).
fn vectors(n: usize, hemisphere: bool) -> Vec<[f32; 3]> {
    let mut rng = Pcg64Mcg::new(0x0053_746f_7261_6765);
    let mut u = || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
    (0..n)
        .map(|_| {
            let z = 2.0 * u() - 1.0;
            let z = if hemisphere { z.abs() } else { z };
            let phi = std::f64::consts::TAU * u();
            let r = (1.0 - z * z).sqrt();
            [r * phi.cos(), r * phi.sin(), z].map(|x| x as f32)
        })
        .collect()
}

fn words(v: &[[f32; 3]]) -> Vec<u32> {
    v.iter().flat_map(|x| x.map(f32::to_bits)).collect()
}

fn vec3(w: &[u32]) -> [f32; 3] {
    [0, 1, 2].map(|i| f32::from_bits(w[i]))
}

#[test]
fn every_float_form_format_keeps_its_claims_on_the_specs_own_output() {
    const N: usize = 4096;
    let mut checked = 0;
    for spec in unitpack::report::doc_tables::codec_specs() {
        let e = spec.emitted();
        let formats = storage::formats(&spec, &e);
        let Some(f) = storage::float_form_storage(&formats) else {
            continue;
        };
        let fields = storage::float_fields(&e).expect("a stored float form has fields");
        let id = spec.id();
        assert_eq!(f.holds, Holds::FloatForm, "{id}");
        // A texel's cost is its channels' widths, whatever the table says.
        let widths: u32 = f
            .channels
            .iter()
            .map(|c| match c {
                Channel::Unorm(k) | Channel::Snorm(k) | Channel::Uint(k) => *k,
                Channel::Float16 => 16,
                Channel::Float32 => 32,
                Channel::Block => unreachable!("not a block format"),
            })
            .sum();
        assert_eq!(f.bits, widths, "{id}: {}", f.name());
        assert!(f.channels.len() >= fields.len(), "{id}: {}", f.name());
        let (Some(enc), Some(dec), Some(pack), Some(unpack)) = (
            e.cpu_function(Role::EncodeFloat),
            e.cpu_function(Role::DecodeFloat),
            e.cpu_function(Role::Encode),
            e.cpu_function(Role::Decode),
        ) else {
            continue;
        };
        if enc.in_words != 3 || enc.out_words != fields.len() || dec.in_words != fields.len() {
            continue;
        }
        let hemisphere =
            spec.info().domain == Some(unitpack::codecs::core::info::Domain::Hemisphere);
        let vs = vectors(N, hemisphere);
        let mut params = vec![0u32; N * fields.len()];
        enc.eval_many(&words(&vs), &mut params);
        let mut stored = params.clone();
        for item in stored.chunks_exact_mut(fields.len()) {
            let mut p: Vec<f32> = item.iter().map(|w| f32::from_bits(*w)).collect();
            f.store(&mut p);
            for (w, x) in item.iter_mut().zip(p) {
                *w = x.to_bits();
            }
        }
        if spec.precise() {
            // A precise float form writes its codes' values c/M: an exact format keeps
            // every one, a wider one rounds some of them.
            let changed = params.iter().zip(&stored).filter(|(a, b)| a != b).count();
            if f.exact {
                assert_eq!(changed, 0, "{id}: {} changes the codes' values", f.name());
            } else {
                assert!(
                    changed > 0,
                    "{id}: {} is called inexact yet keeps every value",
                    f.name()
                );
            }
        }
        // Read back from the format, the float form errs about as the packed code does
        // (an index codec's float form is split bytes, read through its packed decoder).
        if spec.family().float_form(&spec).unfilterable().is_some() {
            continue;
        }
        let mut back = vec![0u32; N * 3];
        dec.eval_many(&stored, &mut back);
        let mut codes = vec![0u32; N * pack.out_words];
        pack.eval_many(&words(&vs), &mut codes);
        let mut packed = vec![0u32; N * 3];
        unpack.eval_many(&codes, &mut packed);
        let worst = |out: &[u32]| {
            (0..N)
                .map(|i| angle_deg(vs[i], vec3(&out[i * 3..])))
                .fold(0.0, f64::max)
        };
        let (stored_max, packed_max) = (worst(&back), worst(&packed));
        assert!(
            stored_max <= 1.5 * packed_max + 1e-3,
            "{id}: through {} the sample max is {stored_max}°, the packed code's {packed_max}°",
            f.name()
        );
        checked += 1;
    }
    assert!(checked > 150, "only {checked} specs checked");
}
