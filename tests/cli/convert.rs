//! `unitpack convert-normal-map`: a conventional tangent-space normal map (RGB8 or RGB16
//! PNG, `n·½ + ½`) to a texel layout and back, texel for texel what the CPU encoder and
//! decoder give, and bad input refused with a clear error and no file lost.

use png::{BitDepth, ColorType};
use std::path::Path;
use std::process::{Command, Output};
use unitpack::api::Batch;

fn unitpack(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_unitpack"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn arg(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A deterministic map from a height field: waves plus a bump, 97×61 texels (odd sizes,
/// so rows are not a multiple of any batch), as `n·½ + ½` at `max` (255 or 65535).
fn normals(w: u32, h: u32) -> Vec<[f64; 3]> {
    let height = |x: f64, y: f64| {
        (x * 0.21).sin() * (y * 0.17).cos() * 6.0
            + 9.0 * (-((x - 40.0).powi(2) + (y - 30.0).powi(2)) / 90.0).exp()
    };
    let mut out = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let (x, y) = (f64::from(x), f64::from(y));
            let dx = height(x + 0.5, y) - height(x - 0.5, y);
            let dy = height(x, y + 0.5) - height(x, y - 0.5);
            let l = (dx * dx + dy * dy + 1.0).sqrt();
            out.push([-dx / l, -dy / l, 1.0 / l]);
        }
    }
    out
}

const W: u32 = 97;
const H: u32 = 61;

/// A PNG's pixels: each sample as an integer (8- or 16-bit), `channels` per pixel.
struct Image {
    width: u32,
    height: u32,
    color: ColorType,
    depth: BitDepth,
    samples: Vec<u32>,
}

impl Image {
    fn new(width: u32, height: u32, color: ColorType, depth: BitDepth, samples: Vec<u32>) -> Self {
        Image {
            width,
            height,
            color,
            depth,
            samples,
        }
    }

    fn open(path: &Path) -> Image {
        let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
        let mut reader = png::Decoder::new(file).read_info().unwrap();
        let mut data = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut data).unwrap();
        data.truncate(info.buffer_size());
        let samples = match info.bit_depth {
            BitDepth::Sixteen => data
                .chunks_exact(2)
                .map(|b| u32::from(u16::from_be_bytes([b[0], b[1]])))
                .collect(),
            _ => data.iter().map(|&b| u32::from(b)).collect(),
        };
        Image::new(
            info.width,
            info.height,
            info.color_type,
            info.bit_depth,
            samples,
        )
    }

    fn save(&self, path: &Path) {
        let mut encoder = png::Encoder::new(
            std::io::BufWriter::new(std::fs::File::create(path).unwrap()),
            self.width,
            self.height,
        );
        encoder.set_color(self.color);
        encoder.set_depth(self.depth);
        let bytes: Vec<u8> = match self.depth {
            BitDepth::Sixteen => self
                .samples
                .iter()
                .flat_map(|&c| (c as u16).to_be_bytes())
                .collect(),
            _ => self.samples.iter().map(|&c| c as u8).collect(),
        };
        let mut writer = encoder.write_header().unwrap();
        writer.write_image_data(&bytes).unwrap();
        writer.finish().unwrap();
    }

    /// The pixels, row by row.
    fn pixels(&self) -> std::slice::ChunksExact<'_, u32> {
        self.samples.chunks_exact(self.color.samples())
    }

    /// The pixels of an RGBA8 image as little-endian words (texels).
    fn texels(&self) -> Vec<u32> {
        assert_eq!((self.color, self.depth), (ColorType::Rgba, BitDepth::Eight));
        self.pixels()
            .map(|p| u32::from_le_bytes([p[0], p[1], p[2], p[3]].map(|c| c as u8)))
            .collect()
    }
}

fn rgb8_map() -> Image {
    let data: Vec<u32> = normals(W, H)
        .iter()
        .flat_map(|n| n.map(|c| ((c * 0.5 + 0.5) * 255.0).round() as u32))
        .collect();
    Image::new(W, H, ColorType::Rgb, BitDepth::Eight, data)
}

fn rgb(p: &[u32]) -> [u32; 3] {
    [p[0], p[1], p[2]]
}

/// A fresh directory, removed when the test ends.
fn dir() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

/// What the conventional texel `c` (of `max`) means: `2c/max - 1` per component.
fn vector(c: [u32; 3], max: f64) -> [f32; 3] {
    c.map(|c| (2.0 * f64::from(c) / max - 1.0) as f32)
}

#[test]
fn a_map_goes_to_dxt5nm_and_back_texel_for_texel() {
    let tmp = dir();
    let d = tmp.path();
    let (input, texels, back) = (d.join("in.png"), d.join("nm.png"), d.join("back.png"));
    let map = rgb8_map();
    map.save(&input);
    let spec = "xy16p:layout=dxt5nm";
    let r = unitpack(&[
        "convert-normal-map",
        arg(&input),
        arg(&texels),
        "--to",
        spec,
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    assert!(r.stderr.is_empty(), "no progress bar off a terminal: {r:?}");

    let out = Image::open(&texels);
    assert_eq!(
        (out.color, out.depth),
        (ColorType::Rgba, BitDepth::Eight),
        "the texels are RGBA8"
    );
    assert_eq!((out.width, out.height), (W, H));
    let batch = Batch::new(spec).unwrap();
    let vs: Vec<[f32; 3]> = map.pixels().map(|p| vector(rgb(p), 255.0)).collect();
    let mut want = vec![0u32; vs.len()];
    batch.encode(&vs, &mut want);
    for (i, ((p, t), w)) in out.pixels().zip(out.texels()).zip(&want).enumerate() {
        assert_eq!(t, *w, "texel {i}: {:?}", vs[i]);
        assert_eq!((p[0], p[2]), (255, 0), "dxt5nm: R = 1, B = 0");
    }

    let r = unitpack(&[
        "convert-normal-map",
        arg(&texels),
        arg(&back),
        "--from",
        spec,
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let back = Image::open(&back);
    assert_eq!((back.color, back.depth), (ColorType::Rgb, BitDepth::Eight));
    let mut decoded = vec![[0f32; 3]; want.len()];
    batch.decode(&want, &mut decoded);
    let mut worst = 0f64;
    for (i, ((p, n), m)) in back.pixels().zip(&decoded).zip(map.pixels()).enumerate() {
        let expect = n.map(|x| ((f64::from(x) * 0.5 + 0.5).clamp(0.0, 1.0) * 255.0).round() as u32);
        assert_eq!(rgb(p), expect, "texel {i}: decoded {n:?}");
        let a = vector(rgb(p), 255.0);
        let b = vector(rgb(m), 255.0);
        worst = worst.max(unitpack::measure::quality::angle_deg(a, b));
    }
    // Two 8-bit quantizations of a map whose normals tilt at most about 50°.
    assert!(worst < 3.0, "sample max {worst}° after the round trip");
}

/// A large map converts: 3000² RGBA16 texels are 72 MB of samples, past the `png`
/// decoder's default allocation limit of 64 MiB (which bounds its own buffers, not the
/// image, which the caller allocates).
#[test]
fn maps_past_64_mib_convert() {
    let tmp = dir();
    let d = tmp.path();
    let (input, texels) = (d.join("big.png"), d.join("big_rg.png"));
    let side = 3000;
    // Straight up (n = +Z): R = G = ½, B = 1, A = 1, a constant that compresses well.
    let texel = [32768, 32768, 65535, 65535];
    let samples = texel.repeat((side * side) as usize);
    Image::new(side, side, ColorType::Rgba, BitDepth::Sixteen, samples).save(&input);
    assert!(std::fs::metadata(&input).unwrap().len() < 1 << 20);
    let r = unitpack(&[
        "convert-normal-map",
        arg(&input),
        arg(&texels),
        "--to",
        "xy16_rg",
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let out = Image::open(&texels);
    assert_eq!((out.width, out.height), (side, side));
    let mut want = [0u32];
    Batch::new("xy16_rg")
        .unwrap()
        .encode(&[vector([32768, 32768, 65535], 65535.0)], &mut want);
    assert!(out.texels().iter().all(|&t| t == want[0]));
}

/// An RGB16 map reads at 16 bits per component, and --depth 16 writes one back.
#[test]
fn sixteen_bit_maps_read_and_write() {
    let tmp = dir();
    let d = tmp.path();
    let (input, texels, back) = (d.join("in16.png"), d.join("rg.png"), d.join("back16.png"));
    let data: Vec<u32> = normals(W, H)
        .iter()
        .flat_map(|n| n.map(|c| ((c * 0.5 + 0.5) * 65535.0).round() as u32))
        .collect();
    let map = Image::new(W, H, ColorType::Rgb, BitDepth::Sixteen, data);
    map.save(&input);
    let spec = "hemioct16_rg";
    let r = unitpack(&[
        "convert-normal-map",
        arg(&input),
        arg(&texels),
        "--to",
        spec,
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let out = Image::open(&texels);
    let vs: Vec<[f32; 3]> = map.pixels().map(|p| vector(rgb(p), 65535.0)).collect();
    let mut want = vec![0u32; vs.len()];
    Batch::new(spec).unwrap().encode(&vs, &mut want);
    assert_eq!(out.texels(), want);
    let r = unitpack(&[
        "convert-normal-map",
        arg(&texels),
        arg(&back),
        "--from",
        spec,
        "--depth",
        "16",
    ]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let back = Image::open(&back);
    assert_eq!(
        (back.color, back.depth),
        (ColorType::Rgb, BitDepth::Sixteen),
        "--depth 16 writes RGB16"
    );
    let mut decoded = vec![[0f32; 3]; want.len()];
    Batch::new(spec).unwrap().decode(&want, &mut decoded);
    for (i, (p, n)) in back.pixels().zip(&decoded).enumerate() {
        let expect = n.map(|x| ((f64::from(x) + 1.0) / 2.0 * 65535.0).round() as u32);
        assert_eq!(rgb(p), expect, "texel {i}: decoded {n:?}");
    }
}

/// `--dxt1` writes xra's DXT1 texel (x in R, A = 1), which the same decoder reads; it is
/// refused for a layout with one texel form, and --depth is refused with --to.
#[test]
fn xra_writes_either_texel() {
    let tmp = dir();
    let d = tmp.path();
    let (input, dxt5, dxt1) = (d.join("in.png"), d.join("dxt5.png"), d.join("dxt1.png"));
    rgb8_map().save(&input);
    for (out, extra) in [(&dxt5, None), (&dxt1, Some("--dxt1"))] {
        let mut args = vec![
            "convert-normal-map",
            arg(&input),
            arg(out),
            "--to",
            "paraboloid16_xra",
        ];
        args.extend(extra);
        let r = unitpack(&args);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    }
    let (a, b) = (Image::open(&dxt5), Image::open(&dxt1));
    for (p5, p1) in a.pixels().zip(b.pixels()) {
        let [r, g, bl, al] = [p5[0], p5[1], p5[2], p5[3]];
        assert_eq!((r, bl), (255, 0), "DXT5: R = 1");
        assert_eq!(p1, [al, g, 0, 255], "DXT1: x in R, A = 1");
    }
    let codes = |img: &Image| img.texels();
    let batch = Batch::new("paraboloid16_xra").unwrap();
    let mut n5 = vec![[0f32; 3]; (W * H) as usize];
    let mut n1 = n5.clone();
    batch.decode(&codes(&a), &mut n5);
    batch.decode(&codes(&b), &mut n1);
    assert_eq!(n5, n1, "one decoder for both texels");
    fails(
        &[
            "convert-normal-map",
            arg(&input),
            arg(&d.join("x.png")),
            "--to",
            "xy16_rg",
            "--dxt1",
        ],
        "--dxt1 is for the xra layout",
    );
    fails(
        &[
            "convert-normal-map",
            arg(&input),
            arg(&d.join("x.png")),
            "--to",
            "xy16_rg",
            "--depth",
            "16",
        ],
        "--depth sets the conventional map --from writes",
    );
}

fn fails(args: &[&str], says: &str) {
    let r = unitpack(args);
    let err = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{args:?}: {err}");
    assert!(
        err.contains(says),
        "{args:?}: {err:?} does not say {says:?}"
    );
}

/// Bad input is a clear error (exit 2) and loses nothing: the input is never replaced,
/// nothing is written where the conversion failed, a read-only output is kept.
#[test]
fn bad_input_is_refused_and_loses_nothing() {
    let tmp = dir();
    let d = tmp.path();
    let input = d.join("in.png");
    rgb8_map().save(&input);
    let before = std::fs::read(&input).unwrap();
    let out = d.join("out.png");

    fails(
        &[
            "convert-normal-map",
            arg(&d.join("missing.png")),
            arg(&out),
            "--to",
            "xy16_rg",
        ],
        "missing.png",
    );
    fails(
        &[
            "convert-normal-map",
            arg(&input),
            arg(&out),
            "--to",
            "oct16",
        ],
        "does not store a texel",
    );
    fails(
        &[
            "convert-normal-map",
            arg(&input),
            arg(&input),
            "--to",
            "xy16_rg",
        ],
        "both the input and the output",
    );
    fails(
        &[
            "convert-normal-map",
            arg(&input),
            arg(&d.join("out.tga")),
            "--to",
            "xy16_rg",
        ],
        "must be a .png",
    );
    // A conventional RGB8 map is not a map of texels.
    fails(
        &[
            "convert-normal-map",
            arg(&input),
            arg(&out),
            "--from",
            "xy16_rg",
        ],
        "RGBA8",
    );
    let gray = d.join("gray.png");
    Image::new(4, 4, ColorType::Grayscale, BitDepth::Eight, vec![128; 16]).save(&gray);
    fails(
        &[
            "convert-normal-map",
            arg(&gray),
            arg(&out),
            "--to",
            "xy16_rg",
        ],
        "RGB8 or RGB16",
    );
    let text = d.join("text.png");
    std::fs::write(&text, "not an image").unwrap();
    fails(
        &[
            "convert-normal-map",
            arg(&text),
            arg(&out),
            "--to",
            "xy16_rg",
        ],
        "text.png",
    );
    assert!(!out.exists(), "nothing written by a failed conversion");
    assert_eq!(
        std::fs::read(&input).unwrap(),
        before,
        "the input is untouched"
    );

    // An existing OUT is replaced only with --force: swapped arguments cannot destroy
    // a map.
    std::fs::write(&out, "keep me").unwrap();
    fails(
        &[
            "convert-normal-map",
            arg(&input),
            arg(&out),
            "--to",
            "xy16_rg",
        ],
        "pass --force",
    );
    assert_eq!(std::fs::read(&out).unwrap(), b"keep me");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o444)).unwrap();
    }
    let r = unitpack(&[
        "convert-normal-map",
        arg(&input),
        arg(&out),
        "--to",
        "xy16_rg",
        "--force",
    ]);
    assert!(r.status.success(), "{r:?}");
    let t = Image::open(&out);
    assert_eq!((t.width, t.height), (W, H));
    assert!(t.pixels().all(|p| p[2..] == [0, 255]), "rg: B = 0, A = 1");
}

/// The exit status 2 and stderr of a conversion that must fail, having written no `out`.
fn refused(args: &[&str], out: &Path) -> String {
    let r = unitpack(args);
    let err = String::from_utf8_lossy(&r.stderr).into_owned();
    assert_eq!(r.status.code(), Some(2), "{args:?}: {err}");
    assert!(!out.exists(), "{args:?} wrote {}", out.display());
    err
}

/// A map of texels is not a map of normals, but `--to` ignores alpha (where dxt5nm, rxgb,
/// latc and xra keep x), and the binary before this converted one without a word into
/// nonsense. Each layout's texels, as `--to` writes them, are refused when given to `--to`
/// again: the error names the channel pattern that gave them away and `--from`.
#[test]
fn texels_given_to_to_are_refused() {
    let tmp = dir();
    let d = tmp.path();
    let input = d.join("in.png");
    rgb8_map().save(&input);
    let again = d.join("again.png");
    for (spec, extra, pattern) in [
        ("xy16_rg", None, "B = 0 in every texel"),
        ("xy16p:layout=dxt5nm", None, "B = 0 in every texel"),
        ("paraboloid16_xra", None, "B = 0 in every texel"),
        ("paraboloid16_xra", Some("--dxt1"), "B = 0 in every texel"),
        ("hemioct16:layout=rxgb", None, "R = 1 in every texel"),
        ("xy16:layout=latc", None, "R = G = B in every texel"),
    ] {
        let texels = d.join(format!("{spec}.png"));
        let mut args = vec![
            "convert-normal-map",
            arg(&input),
            arg(&texels),
            "--to",
            spec,
        ];
        args.extend(extra);
        args.push("--force");
        let r = unitpack(&args);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        let err = refused(
            &[
                "convert-normal-map",
                arg(&texels),
                arg(&again),
                "--to",
                spec,
            ],
            &again,
        );
        assert!(
            err.contains(&format!(
                "{} looks like a map of texels, not a conventional normal map: {pattern}",
                texels.display()
            )) && err.contains("with --from SPEC"),
            "{spec}: {err}"
        );
    }
}

/// The usage line shows both directions (it showed `--to` alone before, as if `--from`
/// did not exist), and a call with neither or both says which to give.
#[test]
fn usage_names_to_and_from() {
    let r = unitpack(&["convert-normal-map", "--help"]);
    let help = String::from_utf8_lossy(&r.stdout);
    let usage = help
        .lines()
        .find(|l| l.starts_with("Usage: "))
        .unwrap_or_else(|| panic!("no usage line: {help}"));
    assert!(
        usage.contains("--to <SPEC>") && usage.contains("--from <SPEC>"),
        "{usage}"
    );
    let out = Path::new("never-written.png");
    let err = refused(&["convert-normal-map", "in.png", arg(out)], out);
    assert!(err.contains("--to <SPEC>|--from <SPEC>"), "{err}");
    let err = refused(
        &[
            "convert-normal-map",
            "in.png",
            arg(out),
            "--to",
            "xy16_rg",
            "--from",
            "xy16_rg",
        ],
        out,
    );
    assert!(err.contains("cannot be used with"), "{err}");
}

/// Messages name an image's format as the help and texture formats do, `RGB8`, `RGBA8`,
/// `L8`; the binary before this printed the `png` crate's names (`in.png is Rgb8`).
#[test]
fn formats_are_named_as_the_help_names_them() {
    let tmp = dir();
    let d = tmp.path();
    let (input, gray, out) = (d.join("in.png"), d.join("gray.png"), d.join("out.png"));
    rgb8_map().save(&input);
    Image::new(4, 4, ColorType::Grayscale, BitDepth::Eight, vec![128; 16]).save(&gray);
    let err = refused(
        &[
            "convert-normal-map",
            arg(&input),
            arg(&out),
            "--from",
            "xy16_rg",
        ],
        &out,
    );
    assert!(
        err.contains(&format!(
            "{} is RGB8: a map of texels is RGBA8",
            input.display()
        )),
        "{err}"
    );
    let err = refused(
        &[
            "convert-normal-map",
            arg(&gray),
            arg(&out),
            "--to",
            "xy16_rg",
        ],
        &out,
    );
    assert!(
        err.contains(&format!(
            "{} is L8: a normal map is RGB8 or RGB16",
            gray.display()
        )),
        "{err}"
    );
}
