//! Replacing a file so that a user can trust it with their files: readers see the old
//! file or the new one, never half of one; a failure leaves the old file as it was and no
//! temporary file behind; errors name the user's path, never the temporary one.
//!
//! The policy, in the order it is applied:
//! - A symlink is followed (chains included) and its final target is replaced; the link
//!   stays a link.
//! - Missing parent directories are created, as `generate` creates its folders.
//! - A directory is never replaced. A character device or FIFO (`/dev/stdout`, `/dev/null`,
//!   a named pipe) is written into directly: renaming over it would replace the device.
//! - An existing file the user cannot write — no write bit at all (`chmod a-w`), or
//!   `access(2)` refuses — is replaced only with `force`: a rename needs write permission
//!   on the directory only, so without this check a read-only file would be silently
//!   replaced. Root passes `access(2)` for every file, so for root only the mode bits count.
//! - The new file gets the old file's permission bits without setuid, setgid and sticky,
//!   and (best effort: only root may give a file away) its owner and group; a new file
//!   gets `0666` less the umask.

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

type Result<T> = io::Result<T>;

/// An error whose message says what could not be done to the user's path.
fn fail(kind: io::ErrorKind, msg: String) -> io::Error {
    io::Error::new(kind, msg)
}

/// Adds what was being done to an I/O error, keeping its kind.
trait Context<T> {
    fn with_context(self, what: impl FnOnce() -> String) -> Result<T>;
}

impl<T> Context<T> for Result<T> {
    fn with_context(self, what: impl FnOnce() -> String) -> Result<T> {
        self.map_err(|e| fail(e.kind(), format!("{}: {e}", what())))
    }
}

/// Symlink hops followed before giving up (Linux's own limit).
const MAX_LINKS: usize = 40;

/// A file being written. [`AtomicFile::commit`] puts it in place; dropping it without a
/// commit removes the temporary file and leaves the target untouched.
pub struct AtomicFile {
    /// The path as the user gave it, for messages.
    shown: PathBuf,
    /// The file actually replaced (the final target of a symlink chain).
    target: PathBuf,
    /// `None` when writing directly into a device or FIFO.
    tmp: Option<PathBuf>,
    file: BufWriter<File>,
    /// Mode and owner to give the new file.
    keep: Option<(u32, u32, u32)>,
}

/// Follows `path` through symlinks to the file a write should replace.
fn resolve(path: &Path) -> Result<PathBuf> {
    let mut p = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        match fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let link = fs::read_link(&p).with_context(|| {
                    format!("cannot write {}: cannot read the link", path.display())
                })?;
                p = match p.parent() {
                    Some(dir) => dir.join(link),
                    None => link,
                };
            }
            _ => return Ok(p),
        }
    }
    Err(fail(
        io::ErrorKind::InvalidInput,
        format!(
            "cannot write {}: more than {MAX_LINKS} symlinks in a chain",
            path.display()
        ),
    ))
}

/// Whether the user may replace the existing file `path` (see the module's policy).
#[cfg(unix)]
fn user_may_write(path: &Path, mode: u32) -> bool {
    use std::os::unix::ffi::OsStrExt;
    if mode & 0o222 == 0 {
        return false;
    }
    let Ok(c) = std::ffi::CString::new(path.as_os_str().as_bytes()) else {
        return false;
    };
    // SAFETY: `c` is a valid NUL-terminated string that outlives the call.
    unsafe { libc::faccessat(libc::AT_FDCWD, c.as_ptr(), libc::W_OK, libc::AT_EACCESS) == 0 }
}

#[cfg(not(unix))]
fn user_may_write(_path: &Path, _mode: u32) -> bool {
    true
}

/// A name for the temporary file beside `target`, unique within this process and across
/// processes (the pid), so that parallel runs never share one.
fn temp_name(target: &Path) -> PathBuf {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let name = target
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    target.with_file_name(format!(".{name}.{}-{n}.unitpack-tmp", std::process::id()))
}

/// The directory `path` lives in (`.` for a bare file name).
fn parent_dir(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

impl AtomicFile {
    /// Starts replacing `path` (see the module's policy for what is refused).
    pub fn create(path: &Path, force: bool) -> Result<AtomicFile> {
        let shown = path.to_path_buf();
        let cannot = |what: &str| format!("cannot write {}: {what}", shown.display());
        // A device or FIFO is written in place. Asked first, of the path as given: the
        // kernel follows a link such as `/dev/stdout` to a pipe, whose `/proc/self/fd/1`
        // link names no file that `resolve` could follow.
        #[cfg(unix)]
        if let Ok(m) = fs::metadata(path) {
            use std::os::unix::fs::FileTypeExt;
            let t = m.file_type();
            if t.is_char_device() || t.is_fifo() || t.is_socket() {
                let file = OpenOptions::new()
                    .write(true)
                    .open(path)
                    .with_context(|| cannot("cannot open it"))?;
                return Ok(AtomicFile {
                    shown,
                    target: path.to_path_buf(),
                    tmp: None,
                    file: BufWriter::new(file),
                    keep: None,
                });
            }
        }
        let target = resolve(path)?;
        let mut keep = None;
        match fs::metadata(&target) {
            Ok(m) if m.is_dir() => {
                return Err(fail(
                    io::ErrorKind::IsADirectory,
                    cannot("it is a directory"),
                ));
            }
            Ok(m) if m.is_file() => {
                #[cfg(unix)]
                {
                    use std::os::unix::fs::MetadataExt;
                    if !force && !user_may_write(&target, m.mode()) {
                        let why = if m.mode() & 0o222 == 0 {
                            "is read-only"
                        } else {
                            "is not writable by you"
                        };
                        return Err(fail(
                            io::ErrorKind::PermissionDenied,
                            format!(
                                "{} {why} (mode {:04o}, owner uid {}); pass --force to replace it",
                                shown.display(),
                                m.mode() & 0o7777,
                                m.uid()
                            ),
                        ));
                    }
                    keep = Some((m.mode() & 0o777, m.uid(), m.gid()));
                }
            }
            Ok(_) => {
                return Err(fail(
                    io::ErrorKind::InvalidInput,
                    cannot("it is not a regular file"),
                ));
            }
            Err(e) if e.kind() == io::ErrorKind::NotFound => {}
            Err(e) if e.kind() == io::ErrorKind::NotADirectory => {
                return Err(fail(
                    io::ErrorKind::NotADirectory,
                    cannot("a directory in its path is a file"),
                ));
            }
            Err(e) => return Err(e).with_context(|| cannot("cannot inspect it")),
        }
        let dir = parent_dir(&target);
        fs::create_dir_all(dir)
            .with_context(|| cannot(&format!("cannot create directory {}", dir.display())))?;
        let tmp = temp_name(&target);
        let mut options = OpenOptions::new();
        options.write(true).create_new(true);
        #[cfg(unix)]
        {
            use std::os::unix::fs::OpenOptionsExt;
            // Private while it is written when it will get another file's mode; else the
            // usual mode less the umask, which is also what it keeps.
            options.mode(if keep.is_some() { 0o600 } else { 0o666 });
        }
        let file = options
            .open(&tmp)
            .with_context(|| cannot(&format!("cannot create a file in {}", dir.display())))?;
        Ok(AtomicFile {
            shown,
            target,
            tmp: Some(tmp),
            file: BufWriter::with_capacity(64 * 1024, file),
            keep,
        })
    }

    /// The path as the user gave it.
    pub fn path(&self) -> &Path {
        &self.shown
    }

    /// Puts the new contents in place: flush, the old file's mode and owner, rename.
    pub fn commit(mut self) -> Result<()> {
        let shown = self.shown.clone();
        let cannot = || format!("cannot write {}", shown.display());
        self.file.flush().with_context(cannot)?;
        let Some(tmp) = self.tmp.clone() else {
            return Ok(());
        };
        let file = self.file.get_ref();
        #[cfg(unix)]
        if let Some((mode, uid, gid)) = self.keep {
            use std::os::unix::fs::PermissionsExt;
            // Giving a file away needs root; for anyone else the new file stays theirs.
            let _ = std::os::unix::fs::fchown(file, Some(uid), Some(gid));
            // After chown, which clears setuid/setgid; `mode` has neither.
            file.set_permissions(fs::Permissions::from_mode(mode))
                .with_context(cannot)?;
        }
        file.sync_all().with_context(cannot)?;
        fs::rename(&tmp, &self.target).with_context(cannot)?;
        self.tmp = None;
        Ok(())
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.file.write(buf)
    }
    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        self.file.write_all(buf)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.file.flush()
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if let Some(tmp) = &self.tmp {
            let _ = fs::remove_file(tmp);
        }
    }
}

/// Writes `bytes` to `path` atomically (see the module's policy); refuses a read-only file.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    write_atomic_with(path, bytes, false)
}

/// [`write_atomic`], replacing a read-only file too when `force` is set.
pub fn write_atomic_with(path: &Path, bytes: &[u8], force: bool) -> Result<()> {
    let mut f = AtomicFile::create(path, force)?;
    f.write_all(bytes)
        .with_context(|| format!("cannot write {}", path.display()))?;
    f.commit()
}
