//! `gen` (src/cli/include.rs): one include on stdout, in a file or one file per language in a directory, and
//! the rules every written file follows (atomic replacement, links, permissions).

use crate::common::*;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;
use unitpack::codecs::Spec;
use unitpack::emit::Lang;

#[test]
fn gen_wgsl_defines_encode_and_decode() {
    let r = ok(&["gen", "oct16", "--lang", "wgsl"]);
    assert!(r.stdout.contains("fn unitpack_oct16_encode("), "{r:?}");
    assert!(r.stdout.contains("fn unitpack_oct16_decode("), "{r:?}");
    assert!(
        r.stdout
            .contains("// Regenerate: unitpack gen oct16 --lang wgsl\n"),
        "{r:?}"
    );
    assert!(r.stderr.is_empty(), "{r:?}");
}

#[test]
fn gen_glsl_and_hlsl_signatures() {
    let r = ok(&["gen", "oct16", "--lang", "glsl"]);
    assert!(
        r.stdout.contains("uint unitpack_oct16_encode(vec3 v)"),
        "{r:?}"
    );
    assert!(
        r.stdout.contains("vec3 unitpack_oct16_decode(uint code)"),
        "{r:?}"
    );
    assert!(r.stdout.contains("#ifndef UNITPACK_OCT16_GLSL"), "{r:?}");
    let r = ok(&["gen", "oct16", "--lang", "hlsl"]);
    assert!(
        r.stdout.contains("uint unitpack_oct16_encode(float3 v)"),
        "{r:?}"
    );
    assert!(
        r.stdout.contains("float3 unitpack_oct16_decode(uint code)"),
        "{r:?}"
    );
    assert!(r.stdout.contains("#ifndef UNITPACK_OCT16_HLSL"), "{r:?}");
}

#[test]
fn gen_several_specs_in_one_include() {
    let r = ok(&["gen", "oct16", "hemioct24p", "snorm8x3", "--lang", "wgsl"]);
    for f in [
        "unitpack_oct16_encode",
        "unitpack_hemioct24p_encode",
        "unitpack_snorm8x3_decode",
    ] {
        assert!(r.stdout.contains(&format!("fn {f}(")), "missing {f}: {r:?}");
    }
    assert!(
        r.stdout
            .contains("// Regenerate: unitpack gen oct16 hemioct24p snorm8x3 --lang wgsl\n"),
        "{r:?}"
    );
}

#[test]
fn gen_options_reach_the_output() {
    let r = ok(&["gen", "oct24:layout=rgb8", "--lang", "wgsl"]);
    assert!(r.stdout.contains("fn unitpack_oct24_rgb8_encode("), "{r:?}");
    assert!(r.stdout.contains("fn unitpack_oct24_rgb8_decode("), "{r:?}");
    // layout=snorm is the default: same text as no option.
    assert_eq!(
        ok(&["gen", "oct24:layout=snorm", "--lang", "wgsl"]).stdout,
        ok(&["gen", "oct24", "--lang", "wgsl"]).stdout
    );
    // A non-default scale is part of the spec's displayed name and changes the code.
    let scaled = ok(&["gen", "stereo_scaled16:scale=2", "--lang", "wgsl"]);
    let default = ok(&["gen", "stereo_scaled16", "--lang", "wgsl"]);
    assert!(
        scaled
            .stdout
            .contains("unitpack gen stereo_scaled16:scale=2 --lang wgsl"),
        "{scaled:?}"
    );
    assert_ne!(scaled.stdout, default.stdout);
}

#[test]
fn gen_spec_names_are_case_insensitive() {
    assert_eq!(
        ok(&["gen", "OCT16P", "--lang", "wgsl"]).stdout,
        ok(&["gen", "oct16p", "--lang", "wgsl"]).stdout
    );
}

#[test]
fn gen_prefix_renames_every_function() {
    let r = ok(&["gen", "oct16", "--lang", "wgsl", "--prefix", "my_"]);
    assert!(r.stdout.contains("fn my_oct16_encode("), "{r:?}");
    assert!(r.stdout.contains("fn my_oct16_decode("), "{r:?}");
    assert!(
        !r.stdout.contains("unitpack_oct16"),
        "default prefix left behind: {r:?}"
    );
    assert!(
        r.stdout.contains("--prefix my_"),
        "the regenerate line should repeat the prefix: {r:?}"
    );
    let r = ok(&["gen", "oct16", "--lang", "glsl", "--prefix", "my_"]);
    assert!(r.stdout.contains("#ifndef MY_OCT16_GLSL"), "{r:?}");
    // An empty prefix is allowed: bare names.
    let r = ok(&["gen", "oct16", "--lang", "wgsl", "--prefix", ""]);
    assert!(r.stdout.contains("fn oct16_encode("), "{r:?}");
}

#[test]
fn gen_rejects_invalid_prefixes() {
    for prefix in ["9bad", "a__b", "my-", "_x", "é_", "a b"] {
        let err = fails(&["gen", "oct16", "--lang", "wgsl", "--prefix", prefix], "");
        assert!(
            err.contains(&format!("invalid prefix '{prefix}'")),
            "prefix {prefix:?}: {err}"
        );
    }
}

#[test]
fn gen_out_writes_what_stdout_shows() {
    let dir = tempdir();
    let path = dir.path().join("oct16.wgsl");
    let r = ok(&[
        "gen",
        "oct16",
        "--lang",
        "wgsl",
        "--out",
        path.to_str().unwrap(),
    ]);
    assert!(
        r.stdout.is_empty(),
        "with --out nothing goes to stdout: {r:?}"
    );
    let written = std::fs::read_to_string(&path).expect("--out file");
    assert_eq!(written, ok(&["gen", "oct16", "--lang", "wgsl"]).stdout);
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([PathBuf::from("oct16.wgsl")]),
        "no temporary files left"
    );
}

#[test]
fn gen_out_replaces_an_existing_file_atomically() {
    let dir = tempdir();
    let path = dir.path().join("normals.glsl");
    std::fs::write(
        &path,
        "old contents that are longer than nothing\n".repeat(500),
    )
    .unwrap();
    #[cfg(unix)]
    let old_inode = std::os::unix::fs::MetadataExt::ino(&std::fs::metadata(&path).unwrap());
    ok(&[
        "gen",
        "hemioct16",
        "--lang",
        "glsl",
        "--out",
        path.to_str().unwrap(),
    ]);
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        ok(&["gen", "hemioct16", "--lang", "glsl"]).stdout
    );
    // Replaced by a rename, not rewritten in place: readers never see a half-written file.
    #[cfg(unix)]
    assert_ne!(
        std::os::unix::fs::MetadataExt::ino(&std::fs::metadata(&path).unwrap()),
        old_inode
    );
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([PathBuf::from("normals.glsl")]),
        "no temporary files left"
    );
}

#[test]
fn gen_out_creates_missing_directories() {
    let dir = tempdir();
    let path = dir.path().join("new").join("dir").join("x.wgsl");
    ok(&[
        "gen",
        "oct16",
        "--lang",
        "wgsl",
        "--out",
        path.to_str().unwrap(),
    ]);
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        ok(&["gen", "oct16", "--lang", "wgsl"]).stdout
    );
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([PathBuf::from("new/dir/x.wgsl")])
    );
}

/// A failed write names the user's path, never the temporary file beside it, and leaves
/// nothing behind.
#[test]
fn gen_out_errors_name_the_file_not_a_temporary_one() {
    let dir = tempdir();
    std::fs::write(dir.path().join("plain"), "a file, not a directory\n").unwrap();
    let path = dir.path().join("plain").join("x.wgsl");
    let err = fails(
        &[
            "gen",
            "oct16",
            "--lang",
            "wgsl",
            "--out",
            path.to_str().unwrap(),
        ],
        "",
    );
    assert!(
        err.contains(&format!("cannot write {}", path.display())),
        "{err}"
    );
    // The temporary directory's own name may contain "tmp"; nothing after it may.
    let rest = err.replace(dir.path().to_str().unwrap(), "DIR");
    assert!(!rest.contains("tmp"), "a temporary file is named: {err}");
    assert_eq!(tree(dir.path()), BTreeSet::from([PathBuf::from("plain")]));
    // /proc refuses new files even to root: the temporary file cannot be created.
    #[cfg(target_os = "linux")]
    {
        let err = fails(
            &[
                "gen",
                "oct16",
                "--lang",
                "wgsl",
                "--out",
                "/proc/self/x.wgsl",
            ],
            "",
        );
        assert!(err.contains("cannot write /proc/self/x.wgsl"), "{err}");
        assert!(!err.contains("tmp"), "a temporary file is named: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
}

#[test]
fn gen_out_onto_a_directory_writes_into_it() {
    let dir = tempdir();
    ok(&[
        "gen",
        "oct16",
        "--lang",
        "wgsl",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([PathBuf::from("oct16.wgsl")])
    );
    assert_eq!(
        std::fs::read_to_string(dir.path().join("oct16.wgsl")).unwrap(),
        ok(&["gen", "oct16", "--lang", "wgsl"]).stdout
    );
    // A directory where the file would go is never replaced.
    let other = tempdir();
    std::fs::create_dir(other.path().join("oct16.wgsl")).unwrap();
    let err = fails(
        &[
            "gen",
            "oct16",
            "--lang",
            "wgsl",
            "--out",
            other.path().to_str().unwrap(),
        ],
        "",
    );
    assert!(err.contains("it is a directory"), "{err}");
    assert!(other.path().join("oct16.wgsl").is_dir());
    assert!(
        tree(other.path()).is_empty(),
        "no temporary file may be left behind"
    );
}

#[test]
fn gen_with_one_bad_spec_prints_nothing() {
    let err = fails(&["gen", "oct16", "octt16", "--lang", "wgsl"], "");
    assert!(err.contains("unknown codec 'octt16'"), "{err}");
}

/// `gen SPEC` writes exactly the file `generate` writes for it, Regenerate line included
/// (the tree of the `generate` that filled the shared figure cache, which is only read).
#[test]
fn gen_writes_exactly_the_generated_file() {
    let generated = filled_cache().tree.as_path();
    for (spec, lang) in [
        ("oct16", Lang::Wgsl),
        ("spherical24p", Lang::Glsl),
        ("snorm16x3", Lang::Hlsl),
        ("oct24p_rgb8", Lang::C),
    ] {
        let g = ok(&["gen", spec, "--lang", lang.name()]).stdout;
        let f = std::fs::read_to_string(
            generated
                .join(lang.name())
                .join(format!("{spec}.{}", lang.ext())),
        )
        .unwrap();
        // The header names `gen` itself, so the two are the same bytes.
        assert_eq!(g, f, "{spec}.{lang}");
    }
}

/// `gen` and `generate` keep the figures they state (proven bounds, error statistics) in
/// `$UNITPACK_CACHE_DIR/figures.txt` for the next run of the same executable: a run reads
/// them from there, a file of another build is replaced, a damaged one is ignored, a
/// file that is not the cache is never touched, and set empty the variable writes nothing.
#[test]
fn gen_keeps_its_figures_for_the_next_run() {
    let home = tempdir();
    let dir = home.path().join("cache");
    let file = dir.join("figures.txt");
    let gen_with = |cache: &Path| {
        let mut cmd = unitpack();
        cmd.env("UNITPACK_CACHE_DIR", cache)
            .args(["gen", "oct16", "--lang", "wgsl"]);
        let r = run_cmd(cmd, b"");
        assert_eq!(r.code, 0, "{r:?}");
        r.stdout
    };
    let plain = uncached(None, &["gen", "oct16", "--lang", "wgsl"]).stdout;
    assert!(plain.contains("mean 0.33696°"), "{plain}");
    assert_eq!(gen_with(&dir), plain, "a first run states what it proves");
    let text = std::fs::read_to_string(&file).expect("the first run writes the cache");
    let header = text.lines().next().unwrap().to_string();
    assert!(
        header.starts_with("unitpack figure cache v4 exe="),
        "{header}"
    );
    assert!(text.lines().any(|l| l.starts_with("bound ")), "{text}");

    // The next run takes the figures from the file: one edited there shows in the include.
    let line = text
        .lines()
        .find(|l| l.starts_with("stats ") && l.split(' ').nth(2) == Some("oct16"))
        .expect("oct16's statistics");
    let mut words: Vec<&str> = line.split(' ').collect();
    words[3] = "4029000000000000"; // a mean of 12.5°
    std::fs::write(&file, text.replace(line, &words.join(" "))).unwrap();
    let edited = gen_with(&dir);
    assert!(edited.contains("mean 12.50000°"), "{edited}");
    // Compared as paragraphs: a longer figure may wrap its comment differently.
    let unwrapped = |s: &str| s.replace("\n//   ", " ");
    assert_eq!(
        unwrapped(&edited).replace("mean 12.50000°", "mean 0.33696°"),
        unwrapped(&plain)
    );

    // A frame spec's frame figures are kept too: one edited there shows in the include.
    let frame_gen = |cache: &Path| {
        let mut cmd = unitpack();
        cmd.env("UNITPACK_CACHE_DIR", cache)
            .args(["gen", "octangle32", "--lang", "wgsl"]);
        let r = run_cmd(cmd, b"");
        assert_eq!(r.code, 0, "{r:?}");
        r.stdout
    };
    let frame_plain = frame_gen(&dir);
    let with_frames = std::fs::read_to_string(&file).unwrap();
    let line = with_frames
        .lines()
        .find(|l| l.starts_with("frames octangle32 "))
        .unwrap_or_else(|| panic!("octangle32's frame figures: {with_frames}"));
    let mut words: Vec<&str> = line.split(' ').collect();
    words[4] = "4029000000000000"; // a normal mean of 12.5°
    std::fs::write(&file, with_frames.replace(line, &words.join(" "))).unwrap();
    let edited = unwrapped(&frame_gen(&dir));
    assert!(edited.contains("normal 12.50000°"), "{edited}");
    assert!(
        unwrapped(&frame_plain).contains("normal 0.04180°"),
        "{frame_plain}"
    );
    std::fs::write(&file, &text).unwrap();

    // Another build's file, an older format's, or a damaged one, is not read, and is
    // replaced by this one's.
    for foreign in [
        text.replacen(&header, "unitpack figure cache v4 exe=0123456789abcdef", 1),
        text.replacen(&header, "unitpack figure cache v2 exe=0123456789abcdef", 1),
        format!("{text}bound zz\n"),
    ] {
        std::fs::write(&file, &foreign).unwrap();
        assert_eq!(gen_with(&dir), plain);
        let now = std::fs::read_to_string(&file).unwrap();
        assert!(now.starts_with(&format!("{header}\n")), "{now}");
    }

    // A file of the user's at that path stays as it was.
    std::fs::write(&file, "my notes\n").unwrap();
    assert_eq!(gen_with(&dir), plain);
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "my notes\n");

    // Set empty, the variable turns the cache off.
    let off = home.path().join("off");
    let mut cmd = unitpack();
    cmd.env("UNITPACK_CACHE_DIR", "")
        .env("HOME", &off)
        .env("XDG_CACHE_HOME", &off);
    cmd.args(["gen", "oct16", "--lang", "wgsl"]);
    assert_eq!(run_cmd(cmd, b"").stdout, plain);
    assert!(!off.exists(), "nothing written with the cache off");
}

/// Every committed include names the command that writes it, `unitpack gen <spec> --lang
/// <lang>`, and that command reproduces the file byte for byte (run for each spec in one
/// language, the languages in turn; `generate --check` compares every file).
#[test]
fn every_generated_file_regenerates_from_its_header() {
    let root = committed_generated();
    let ids: Vec<String> = Spec::all().iter().map(Spec::id).collect();
    let (mut checked, mut ran) = (0, 0);
    for (l, lang) in Lang::ALL.into_iter().enumerate() {
        let dir = root.join(lang.name());
        for entry in std::fs::read_dir(&dir).expect("generated language folder") {
            let path = entry.unwrap().path();
            let text = std::fs::read_to_string(&path).unwrap();
            let cmd = text
                .lines()
                .find_map(|l| l.split("Regenerate: ").nth(1))
                .unwrap_or_else(|| panic!("{} has no Regenerate line", path.display()));
            let args: Vec<&str> = cmd.split_whitespace().collect();
            let stem = path.file_stem().unwrap().to_str().unwrap();
            // The header regenerates the file's spec (named as the catalogue writes it,
            // `oct24:layout=rgb8` for `oct24_rgb8`) in the folder's language.
            assert_eq!(args.len(), 5, "{cmd}");
            assert_eq!(args[..2], ["unitpack", "gen"], "{cmd}");
            assert_eq!(args[3..], ["--lang", lang.name()], "{cmd}");
            let spec: Spec = args[2].parse().unwrap();
            assert_eq!(spec.id(), stem, "{}: the header's spec", path.display());
            // The file name (the id) is a spec too.
            assert_eq!(stem.parse::<Spec>().unwrap(), spec);
            // Each spec's command runs in one language, the languages taking turns: the
            // four differ only in `--lang`, and running all would prove every decoder
            // bound four times over.
            let k = ids.iter().position(|i| i == stem).expect("a catalogue id");
            if k % Lang::ALL.len() == l {
                let r = ok(&args[1..]);
                assert!(
                    r.stdout == text,
                    "{cmd} does not reproduce {}",
                    path.display()
                );
                ran += 1;
            }
            checked += 1;
        }
    }
    assert_eq!(checked, ids.len() * Lang::ALL.len());
    assert_eq!(ran, ids.len());
}

#[cfg(unix)]
#[test]
fn gen_out_through_a_symlink_replaces_the_target_and_keeps_the_link() {
    let dir = tempdir();
    let d = dir.path();
    std::fs::create_dir(d.join("real")).unwrap();
    std::fs::write(d.join("real/normals.wgsl"), "old\n").unwrap();
    // A chain: link → link2 → real/normals.wgsl (relative targets).
    std::os::unix::fs::symlink("real/normals.wgsl", d.join("link2")).unwrap();
    std::os::unix::fs::symlink("link2", d.join("link")).unwrap();
    let r = gen_to(&d.join("link"), &[]);
    assert_eq!(r.code, 0, "{r:?}");
    let want = ok(&["gen", "oct16", "--lang", "wgsl"]).stdout;
    assert_eq!(
        std::fs::read_to_string(d.join("real/normals.wgsl")).unwrap(),
        want
    );
    for l in ["link", "link2"] {
        assert!(
            std::fs::symlink_metadata(d.join(l))
                .unwrap()
                .file_type()
                .is_symlink(),
            "{l} is no longer a link"
        );
    }
    // A dangling link: its target is created.
    std::os::unix::fs::symlink("made.wgsl", d.join("dangling")).unwrap();
    assert_eq!(gen_to(&d.join("dangling"), &[]).code, 0);
    assert_eq!(std::fs::read_to_string(d.join("made.wgsl")).unwrap(), want);
    assert!(
        std::fs::symlink_metadata(d.join("dangling"))
            .unwrap()
            .file_type()
            .is_symlink()
    );
}

#[cfg(unix)]
#[test]
fn gen_out_never_carries_setuid_or_setgid_bits() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempdir();
    let p = dir.path().join("x.wgsl");
    std::fs::write(&p, "old\n").unwrap();
    std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o6755)).unwrap();
    assert_eq!(
        std::fs::metadata(&p).unwrap().permissions().mode() & 0o7777,
        0o6755
    );
    assert_eq!(gen_to(&p, &[]).code, 0);
    assert_eq!(
        std::fs::metadata(&p).unwrap().permissions().mode() & 0o7777,
        0o755,
        "the permission bits stay, setuid and setgid go"
    );
}

/// A rename only needs the folder to be writable, so without a check a read-only file
/// would be replaced silently. Tests run as root, whom access(2) lets write anything, so
/// this checks the mode-bit rule (no write bit at all), which holds for root too.
#[cfg(unix)]
#[test]
fn gen_out_refuses_a_read_only_file_unless_forced() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempdir();
    let p = dir.path().join("x.wgsl");
    std::fs::write(&p, "keep me\n").unwrap();
    std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o444)).unwrap();
    let r = gen_to(&p, &[]);
    assert_eq!(r.code, 2, "{r:?}");
    assert!(
        r.stderr.contains("read-only") && r.stderr.contains("--force"),
        "{r:?}"
    );
    assert_eq!(std::fs::read_to_string(&p).unwrap(), "keep me\n");
    let r = gen_to(&p, &["--force"]);
    assert_eq!(r.code, 0, "{r:?}");
    assert_eq!(
        std::fs::read_to_string(&p).unwrap(),
        ok(&["gen", "oct16", "--lang", "wgsl"]).stdout
    );
    assert_eq!(
        std::fs::metadata(&p).unwrap().permissions().mode() & 0o777,
        0o444
    );
    // encode/decode --out follow the same rule.
    let out = dir.path().join("codes.txt");
    std::fs::write(&out, "old\n").unwrap();
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o444)).unwrap();
    let err = fails(
        &["encode", "oct16", "--out", out.to_str().unwrap()],
        "0 0 1\n",
    );
    assert!(err.contains("read-only"), "{err}");
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "old\n");
}

/// The access(2) half of the rule: a file whose mode lets others write it but not this
/// user. Root may write anything, so as root the binary runs as `nobody` (setpriv, from
/// util-linux) in a world-writable folder, where a rename could replace root's file.
#[cfg(target_os = "linux")]
#[test]
fn gen_out_refuses_a_file_the_user_may_not_write() {
    use std::os::unix::fs::PermissionsExt;
    if std::fs::read_to_string("/proc/self/status")
        .unwrap()
        .lines()
        .any(|l| l.starts_with("Uid:") && l.split_whitespace().nth(2) != Some("0"))
    {
        // Not root: nobody else's file can be set up here; the mode-bit test above covers
        // the refusal for this user.
        return;
    }
    let dir = tempdir();
    std::fs::set_permissions(dir.path(), std::fs::Permissions::from_mode(0o777)).unwrap();
    let p = dir.path().join("roots.wgsl");
    std::fs::write(&p, "root's\n").unwrap();
    std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o644)).unwrap();
    let as_nobody = |extra: &[&str]| {
        let mut cmd = Command::new("setpriv");
        cmd.args(["--reuid=65534", "--regid=65534", "--clear-groups", "--"])
            .arg(env!("CARGO_BIN_EXE_unitpack"))
            .args([
                "gen",
                "oct16",
                "--lang",
                "wgsl",
                "--out",
                p.to_str().unwrap(),
            ])
            .args(extra);
        run_cmd(cmd, b"")
    };
    let r = as_nobody(&[]);
    assert_eq!(r.code, 2, "{r:?}");
    assert!(
        r.stderr.contains("not writable by you") && r.stderr.contains("--force"),
        "{r:?}"
    );
    assert_eq!(std::fs::read_to_string(&p).unwrap(), "root's\n");
    let r = as_nobody(&["--force"]);
    assert_eq!(r.code, 0, "{r:?}");
    assert_eq!(
        std::fs::read_to_string(&p).unwrap(),
        ok(&["gen", "oct16", "--lang", "wgsl"]).stdout
    );
}

#[test]
fn gen_out_into_a_full_device_is_a_one_line_error() {
    let err = fails(
        &["gen", "oct16", "--lang", "wgsl", "--out", "/dev/full"],
        "",
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("/dev/full") && err.contains("No space left"),
        "{err}"
    );
    assert!(Path::new("/dev/full").exists(), "the device is still there");
}

/// `gen --lang wesl` prints the spec's WESL module as `generate` writes it, its header
/// naming the `gen` command; a module holds one spec and names its functions without a
/// prefix, so several specs or a prefix are refused.
#[test]
fn gen_writes_a_specs_wesl_module() {
    let r = ok(&["gen", "oct16", "--lang", "wesl"]);
    let stored = std::fs::read_to_string(committed_generated().join("wesl/oct16.wesl")).unwrap();
    assert!(
        r.stdout
            .contains("// Regenerate: unitpack gen oct16 --lang wesl\n")
    );
    assert_eq!(
        r.stdout.replace(
            "Regenerate: unitpack gen oct16 --lang wesl",
            "Regenerate: unitpack generate"
        ),
        stored
    );
    let err = fails(&["gen", "oct16", "oct24", "--lang", "wesl"], "");
    assert!(err.contains("holds one spec"), "{err}");
    let err = fails(&["gen", "oct16", "--lang", "wesl", "--prefix", "my_"], "");
    assert!(err.contains("--prefix does not apply"), "{err}");
    let dir = tempdir();
    let out = format!("{}/", dir.path().display());
    ok(&["gen", "oct16", "--lang", "wgsl,wesl", "--out", &out]);
    let written = std::fs::read_to_string(dir.path().join("oct16.wesl")).unwrap();
    assert_eq!(written, r.stdout);
    assert!(dir.path().join("oct16.wgsl").exists());
}

/// `--out /dev/stdout` on a pipe writes into the pipe (docs/commands.md): the link names
/// `pipe:[…]`, no file beside which a temporary could be made.
#[test]
fn gen_out_to_dev_stdout_writes_into_a_pipe() {
    let piped = ok(&["gen", "oct16", "--lang", "wgsl", "--out", "/dev/stdout"]);
    assert!(piped.stderr.is_empty(), "{}", piped.stderr);
    assert_eq!(piped.stdout, ok(&["gen", "oct16", "--lang", "wgsl"]).stdout);
}

#[test]
fn gen_takes_a_comma_list_of_languages_into_a_directory() {
    let dir = tempdir();
    let out = format!("{}/", dir.path().join("shaders").display());
    ok(&[
        "gen",
        "oct16",
        "hemioct24p",
        "--lang",
        "wgsl,glsl",
        "--out",
        &out,
    ]);
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([
            PathBuf::from("shaders/oct16-hemioct24p.glsl"),
            PathBuf::from("shaders/oct16-hemioct24p.wgsl"),
        ])
    );
    for lang in ["wgsl", "glsl"] {
        assert_eq!(
            std::fs::read_to_string(dir.path().join(format!("shaders/oct16-hemioct24p.{lang}")))
                .unwrap(),
            ok(&["gen", "oct16", "hemioct24p", "--lang", lang]).stdout,
            "{lang}"
        );
    }
    // --name picks the stem; a repeated --lang works as a list too.
    let named = tempdir();
    ok(&[
        "gen",
        "oct16",
        "--lang",
        "hlsl",
        "--lang",
        "wgsl",
        "--name",
        "normals",
        "--out",
        named.path().to_str().unwrap(),
    ]);
    assert_eq!(
        tree(named.path()),
        BTreeSet::from([PathBuf::from("normals.hlsl"), PathBuf::from("normals.wgsl")])
    );
    // Several languages on stdout would be one file of mixed languages: refused.
    let err = fails(&["gen", "oct16", "--lang", "wgsl,glsl"], "");
    assert!(err.contains("--out DIR/"), "{err}");
    for bad in ["../x", ".hidden", ""] {
        let err = fails(
            &[
                "gen",
                "oct16",
                "--lang",
                "wgsl",
                "--name",
                bad,
                "--out",
                named.path().to_str().unwrap(),
            ],
            "",
        );
        assert!(err.contains("--name"), "{bad:?}: {err}");
    }
}

#[test]
fn doc_comments_call_the_maximum_a_sample_maximum() {
    let r = ok(&["gen", "oct16", "--lang", "wgsl"]);
    // Paragraphs whole: a comment's continuation lines start with `//` and three spaces.
    let text = r.stdout.replace("\n//   ", " ");
    let paragraph = |start: &str| {
        text.lines()
            .find(|l| l.starts_with(start))
            .unwrap_or_else(|| panic!("no paragraph {start:?}:\n{text}"))
            .to_string()
    };
    let sample = paragraph("// Round-trip errors (encode, store, decode) are over a sample");
    for s in [
        "seed 0x756e69747061636b5f766563746f7273",
        "a sample maximum is not a bound",
    ] {
        assert!(sample.contains(s), "{sample}");
    }
    let line = paragraph("// Round-trip error over ");
    for s in ["65536 vectors", "sample max"] {
        assert!(line.contains(s), "{line}");
    }
    assert!(!line.contains(", max "), "{line}");
    let readme = std::fs::read_to_string(manifest_dir().join("README.md")).unwrap();
    assert!(readme.contains("sample max"), "README");
    assert!(
        readme.contains("0x756e69747061636b5f766563746f7273"),
        "README names the seed"
    );
}

#[test]
fn gen_writes_c_headers_and_wgsl_import_paths() {
    let r = ok(&["gen", "oct16", "--lang", "c"]);
    assert!(
        r.stdout
            .contains("static inline uint32_t unitpack_oct16_encode(const float v[3]) {"),
        "{r:?}"
    );
    let r = ok(&[
        "gen",
        "oct16",
        "--lang",
        "wgsl",
        "--wgsl-import-path",
        "unitpack::normals",
    ]);
    assert!(
        r.stdout
            .starts_with("#define_import_path unitpack::normals\n"),
        "{r:?}"
    );
    assert!(
        r.stdout.contains(
            "Regenerate: unitpack gen oct16 --lang wgsl --wgsl-import-path unitpack::normals"
        ),
        "{r:?}"
    );
    let err = fails(
        &[
            "gen",
            "oct16",
            "--lang",
            "wgsl",
            "--wgsl-import-path",
            "a b",
        ],
        "",
    );
    assert!(err.contains("invalid WGSL import path"), "{err}");
    // Without WGSL output the path would be dropped without a word: refused instead.
    let err = fails(
        &[
            "gen",
            "oct16",
            "--lang",
            "glsl",
            "--wgsl-import-path",
            "unitpack::normals",
        ],
        "",
    );
    assert!(
        err.contains("--wgsl-import-path") && err.contains("--lang glsl writes none"),
        "{err}"
    );
}

/// Several languages go into a directory, one file each; `--out x.txt` names a file, so it
/// is refused and nothing is created (the binary before this made a directory named
/// x.txt without a word). A directory whose name has a dot is still one when it ends
/// in `/`.
#[test]
fn gen_refuses_a_file_name_for_several_languages() {
    let dir = tempdir();
    let out = dir.path().join("x.txt");
    let err = fails(
        &[
            "gen",
            "oct16",
            "--lang",
            "wgsl,glsl",
            "--out",
            out.to_str().unwrap(),
        ],
        "",
    );
    assert!(
        err.contains("--lang wgsl,glsl writes one file per language into a directory")
            && err.contains(&format!("{} names a file", out.display()))
            && err.contains(&format!("--out {}/", dir.path().join("x").display())),
        "{err}"
    );
    assert!(tree(dir.path()).is_empty(), "nothing created");
    let slashed = format!("{}/", dir.path().join("shaders.v2").display());
    ok(&["gen", "oct16", "--lang", "wgsl,glsl", "--out", &slashed]);
    assert_eq!(
        tree(dir.path()),
        BTreeSet::from([
            PathBuf::from("shaders.v2/oct16.glsl"),
            PathBuf::from("shaders.v2/oct16.wgsl"),
        ])
    );
}
