//! The figures every include states, kept on disk between runs of `gen` and `generate`:
//! each decoder's proven bound ([`crate::measure::decode_bound`]) and each spec's error statistics
//! ([`crate::measure::quality`]), a frame spec's frame figures included. Proving and measuring the whole catalogue is two thirds of a
//! `generate`; the figures are a function of the program and its math library alone, so
//! a later run of the same executable can take them as they were.
//!
//! The file is tied to the executable by a hash of its contents, and to the system's
//! math library (the statistics' random vectors and angles call its `ln`, `cos` and
//! `acos`) by a hash of that file where it is a shared library: a rebuilt or upgraded
//! unitpack, or an upgraded libm, ignores the file and writes its own. It lives at
//! `$UNITPACK_CACHE_DIR/figures.txt` when that variable is set (set and empty: no cache),
//! else in the platform's cache folder (`~/.cache/unitpack/` on Linux). Deleting it is
//! always safe. An unreadable or malformed file is ignored, a file there that does not
//! start with this module's header is never replaced, and failing to write costs only the
//! next run's time: the cache never changes what a run prints or writes.

use crate::measure::decode_bound;
use crate::measure::figures::Bound;
use crate::measure::figures::{ErrorStats, FrameStats};
use crate::measure::quality::{self, StatsKey};
use std::fmt::Write as _;
use std::hash::Hasher;
use std::path::PathBuf;

/// The variable that moves the cache folder (or, set empty, turns the cache off).
pub const ENV: &str = "UNITPACK_CACHE_DIR";
/// The cache file's name in its folder.
pub const FILE: &str = "figures.txt";
/// The first line's start: a file without it is not ours. (The format's version follows
/// it, so that any version's file is known as ours and replaced.)
const MAGIC: &str = "unitpack figure cache";

/// The cache file, if there is a place for one.
pub fn path() -> Option<PathBuf> {
    let dir = match std::env::var_os(ENV) {
        Some(d) if d.is_empty() => return None,
        Some(d) => PathBuf::from(d),
        None => dirs::cache_dir()?.join("unitpack"),
    };
    Some(dir.join(FILE))
}

/// The executable's fingerprint: a hash of its bytes and of the shared math library's
/// (std's SipHash, fixed keys; about 10 ms for a release build).
fn fingerprint() -> Option<u64> {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    h.write(&std::fs::read(std::env::current_exe().ok()?).ok()?);
    if let Some(libm) = math_library() {
        h.write(&std::fs::read(libm).ok()?);
    }
    Some(h.finish())
}

/// The file `cos` is loaded from, where the math library is a shared object.
#[cfg(unix)]
pub fn math_library() -> Option<PathBuf> {
    use std::os::unix::ffi::OsStrExt;
    let cos: extern "C" fn(f64) -> f64 = libc_cos;
    // SAFETY: dladdr only reads the loader's tables; `info` is written before it is read,
    // and `dli_fname` is a NUL-terminated string the loader keeps for the process.
    let name = unsafe {
        let mut info: libc::Dl_info = std::mem::zeroed();
        if libc::dladdr(cos as *const libc::c_void, &mut info) == 0 || info.dli_fname.is_null() {
            return None;
        }
        std::ffi::CStr::from_ptr(info.dli_fname)
    };
    let path = PathBuf::from(std::ffi::OsStr::from_bytes(name.to_bytes()));
    (path != std::env::current_exe().ok()?).then_some(path)
}

#[cfg(unix)]
unsafe extern "C" {
    /// The C library's `cos`, the one `f64::cos` calls.
    #[link_name = "cos"]
    safe fn libc_cos(x: f64) -> f64;
}

#[cfg(not(unix))]
pub fn math_library() -> Option<PathBuf> {
    None
}

/// A run's use of the cache: what it loaded, so that it writes only when it learned more.
pub struct Session {
    path: PathBuf,
    header: String,
    loaded: (usize, usize, usize),
}

/// Loads the figures an earlier run of this executable saved into this process, and
/// returns the session that [`Session::save`]s what this run adds. `None` when there is
/// no cache: no folder, no fingerprint, or a file at the path that is not ours.
pub fn open() -> Option<Session> {
    let path = path()?;
    let header = format!("{MAGIC} v4 exe={:016x}", fingerprint()?);
    let mut loaded = (0, 0, 0);
    match std::fs::symlink_metadata(&path) {
        // Only a plain file can be ours (a FIFO would block the read).
        Ok(m) if !m.is_file() => return None,
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => return None,
        _ => {}
    }
    match std::fs::read_to_string(&path) {
        Ok(text) if !text.starts_with(MAGIC) => return None,
        Ok(text) => {
            if let Some((bounds, stats)) = parse(&text, &header) {
                let frames = parse_frames(&text);
                loaded = (bounds.len(), stats.len(), frames.len());
                decode_bound::import(bounds);
                quality::import(stats);
                quality::import_frames(frames);
            }
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        // Unreadable (not UTF-8, no permission): not known to be ours, so left alone.
        Err(_) => return None,
    }
    Some(Session {
        path,
        header,
        loaded,
    })
}

impl Session {
    /// Writes every figure this process knows, atomically, when it knows more than it
    /// loaded. A failure is silent: the cache is only ever a saving of time.
    pub fn save(self) {
        let (bounds, stats) = (decode_bound::export(), quality::export());
        let frames = quality::export_frames();
        if (bounds.len(), stats.len(), frames.len()) == self.loaded {
            return;
        }
        let mut text = format(&self.header, &bounds, &stats);
        text.push_str(&format_frames(&frames));
        let _ = crate::support::atomic::write_atomic(&self.path, text.as_bytes());
    }
}

pub fn format(
    header: &str,
    bounds: &[(u128, Option<Bound>)],
    stats: &[(StatsKey, Option<ErrorStats>)],
) -> String {
    let mut t = format!("{header}\n");
    for (key, b) in bounds {
        let _ = match b {
            None => writeln!(t, "bound {key:032x} none"),
            Some(b) => {
                let at: Vec<String> = b.at.iter().map(|(lo, hi)| format!("{lo}:{hi}")).collect();
                writeln!(
                    t,
                    "bound {key:016x} {:016x} {:016x} {}",
                    b.units.to_bits(),
                    b.reached.to_bits(),
                    at.join(",")
                )
            }
        };
    }
    for ((spec, samples), s) in stats {
        let _ = match s {
            None => writeln!(t, "stats {samples} {spec} none"),
            Some(s) => writeln!(
                t,
                "stats {samples} {spec} {:016x} {:016x} {:016x}",
                s.mean.to_bits(),
                s.max.to_bits(),
                s.mse.to_bits()
            ),
        };
    }
    t
}

/// An f64 written as its bits in hex, as every figure in the file is.
fn float(s: &str) -> Option<f64> {
    u64::from_str_radix(s, 16).ok().map(f64::from_bits)
}

type Parsed = (
    Vec<(u128, Option<Bound>)>,
    Vec<(StatsKey, Option<ErrorStats>)>,
);

/// The figures in `text` if it is this executable's whole, well-formed file.
pub fn parse(text: &str, header: &str) -> Option<Parsed> {
    let mut lines = text.lines();
    if lines.next()? != header {
        return None;
    }
    let key = |s: &str| u128::from_str_radix(s, 16).ok();
    let (mut bounds, mut stats) = (Vec::new(), Vec::new());
    for line in lines {
        let w: Vec<&str> = line.split(' ').collect();
        match w[..] {
            ["bound", k, "none"] => bounds.push((key(k)?, None)),
            ["bound", k, units, reached, at] => {
                let at = at
                    .split(',')
                    .map(|r| {
                        let (lo, hi) = r.split_once(':')?;
                        Some((lo.parse().ok()?, hi.parse().ok()?))
                    })
                    .collect::<Option<Vec<(i64, i64)>>>()?;
                let (units, reached) = (float(units)?, float(reached)?);
                bounds.push((key(k)?, Some(Bound { units, at, reached })));
            }
            ["stats", samples, spec, "none"] => {
                stats.push(((spec.to_string(), samples.parse().ok()?), None))
            }
            ["stats", samples, spec, mean, max, mse] => {
                let samples = samples.parse().ok()?;
                let s = ErrorStats {
                    mean: float(mean)?,
                    max: float(max)?,
                    mse: float(mse)?,
                    samples,
                };
                stats.push(((spec.to_string(), samples), Some(s)));
            }
            ["frames", ..] => {}
            _ => return None,
        }
    }
    Some((bounds, stats))
}

/// The lines of the frame specs' figures ([`quality::measure_frames`]): `frames`, the id,
/// the sample size, the flips and the six angles' bits (normal, tangent and bitangent,
/// each mean then sample max).
pub fn format_frames(frames: &[(String, Option<FrameStats>)]) -> String {
    let mut t = String::new();
    for (id, s) in frames {
        let _ = match s {
            None => writeln!(t, "frames {id} none"),
            Some(s) => {
                let angles: Vec<String> = [s.normal, s.tangent, s.bitangent]
                    .iter()
                    .flatten()
                    .map(|a| format!("{:016x}", a.to_bits()))
                    .collect();
                writeln!(
                    t,
                    "frames {id} {} {} {}",
                    s.samples,
                    s.flips,
                    angles.join(" ")
                )
            }
        };
    }
    t
}

/// The frame figures of a file [`parse`] accepted: its well-formed `frames` lines.
pub fn parse_frames(text: &str) -> Vec<(String, Option<FrameStats>)> {
    text.lines()
        .filter_map(|line| {
            let w: Vec<&str> = line.split(' ').collect();
            match w[..] {
                ["frames", id, "none"] => Some((id.to_string(), None)),
                ["frames", id, samples, flips, ref angles @ ..] if angles.len() == 6 => {
                    let a: Vec<f64> = angles.iter().map(|x| float(x)).collect::<Option<_>>()?;
                    let s = FrameStats {
                        samples: samples.parse().ok()?,
                        normal: [a[0], a[1]],
                        tangent: [a[2], a[3]],
                        bitangent: [a[4], a[5]],
                        flips: flips.parse().ok()?,
                    };
                    Some((id.to_string(), Some(s)))
                }
                _ => None,
            }
        })
        .collect()
}
