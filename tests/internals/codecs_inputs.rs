use unitpack::codecs::functions::inputs::*;
use unitpack::codecs::toolkit::quant::{Quant, field_offsets};

/// An RGBA8 texel's sweep holds every (G, A) pair with R = B = 255 (dxt5nm's and
/// xra's DXT5 texels) and every (R, G) pair with B = A = 255 (rg's, xra's DXT1).
#[test]
fn texel_sweep_holds_every_written_texel() {
    let q = [Quant::Unorm(8); 4];
    let words: std::collections::HashSet<u32> = codes(&q, 1).into_iter().collect();
    for k in 0..1u32 << 16 {
        let (a, b) = (k & 0xff, k >> 8);
        assert!(
            words.contains(&(0x00ff_00ff | a << 8 | b << 24)),
            "G {a} A {b}"
        );
        assert!(words.contains(&(0xffff_0000 | a | b << 8)), "R {a} G {b}");
    }
}

/// Above 24 bits every 16-bit field still takes each of its 65536 values, in the
/// packed codes and in the fetched floats (each f16 pattern's value, NaN payloads
/// included).
#[test]
fn every_16_bit_field_takes_every_value() {
    let q = [Quant::Half; 3];
    let words = codes(&q, 2);
    let floats = float_codes(&q);
    let offs = field_offsets(&q);
    for (i, off) in offs.iter().take(q.len()).enumerate() {
        let mut seen = vec![false; 1 << 16];
        let mut seen_bits = std::collections::HashSet::new();
        for (item, f) in words.chunks(2).zip(floats.chunks(3)) {
            let w = item[(off / 32) as usize];
            seen[((w >> (off % 32)) & 0xffff) as usize] = true;
            seen_bits.insert(f[i]);
        }
        assert!(seen.iter().all(|s| *s), "field {i}");
        // 65536 patterns, and +0 / -0 apart: every pattern gives its own f32.
        assert_eq!(seen_bits.len(), 1 << 16, "field {i}");
    }
}
