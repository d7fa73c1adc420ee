//! A private `XDG_RUNTIME_DIR` for `verify`. Mesa's Vulkan driver prints "error:
//! XDG_RUNTIME_DIR is invalid or not set in the environment." to stderr when the variable
//! is unset or wrong, as on CI machines and in containers; that noise is not unitpack's
//! output, and users would take it for a failure.

use std::path::Path;

/// Whether `dir` is what the XDG spec asks for: an absolute path to a directory owned by
/// this user that no one else may enter (mode 0700).
fn valid(dir: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        // SAFETY: geteuid has no preconditions and cannot fail.
        let me = unsafe { libc::geteuid() };
        dir.is_absolute()
            && std::fs::metadata(dir)
                .is_ok_and(|m| m.is_dir() && m.uid() == me && m.mode() & 0o077 == 0)
    }
    #[cfg(not(unix))]
    {
        dir.is_absolute() && dir.is_dir()
    }
}

/// A fresh private directory to point `XDG_RUNTIME_DIR` at, when the current value is
/// unset or invalid; it is removed when the returned guard drops. `None` when the value
/// is fine or no directory could be made (Mesa's message is then the only harm).
pub fn private_runtime_dir() -> Option<tempfile::TempDir> {
    if std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|d| valid(Path::new(&d))) {
        return None;
    }
    // tempfile creates directories with mode 0700.
    tempfile::Builder::new()
        .prefix("unitpack-runtime-")
        .tempdir()
        .ok()
}
