//! Standard output for every verb. `print!` panics when stdout is closed (`unitpack list |
//! head -1`) or full, so nothing here uses it: output goes through [`Stdout`], which tags a
//! closed reader's error so that `main` can end quietly while any other write error (a full
//! disk) is reported on one line.

use anyhow::{Context, Result};
use std::fmt;
use std::io::{self, BufWriter, ErrorKind, StdoutLock, Write};
use std::path::Path;

/// Whether an output path is `-`, which every verb reads as standard output (as `cat`,
/// `tar` and most tools do), so that `--out -` never leaves a file named `-` behind.
pub fn is_stdout(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// The cause attached to the `BrokenPipe` error of a write to a closed stdout. A reader
/// that went away asked for no more output; that is not an error worth a message.
#[derive(Debug)]
pub struct StdoutClosed;

impl fmt::Display for StdoutClosed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("the reader of stdout went away")
    }
}

impl std::error::Error for StdoutClosed {}

/// Buffered stdout whose write errors are tagged: a broken pipe carries [`StdoutClosed`].
pub struct Stdout {
    inner: BufWriter<StdoutLock<'static>>,
}

/// Output is buffered in blocks this large; lines are not flushed one by one.
const BUFFER: usize = 64 * 1024;

/// Locks stdout for the rest of the verb.
pub fn stdout() -> Stdout {
    Stdout {
        inner: BufWriter::with_capacity(BUFFER, io::stdout().lock()),
    }
}

fn tag(e: io::Error) -> io::Error {
    if e.kind() == ErrorKind::BrokenPipe {
        io::Error::new(ErrorKind::BrokenPipe, StdoutClosed)
    } else {
        e
    }
}

impl Write for Stdout {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.inner.write(buf).map_err(tag)
    }
    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        self.inner.write_all(buf).map_err(tag)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush().map_err(tag)
    }
}

/// Writes `text` to stdout and flushes it, so that a full disk is reported here rather
/// than lost when the process exits. A closed stdout is not an error: the verb keeps the
/// exit status it earned (`verify` still fails when a check failed).
pub fn print(text: &str) -> Result<()> {
    let mut out = stdout();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.get_ref().is_some_and(|c| c.is::<StdoutClosed>()) => Ok(()),
        r => r.context("cannot write to stdout"),
    }
}

/// Whether `e` comes from a write to a closed stdout (see [`StdoutClosed`]).
pub fn is_stdout_closed(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        c.downcast_ref::<io::Error>()
            .and_then(|io| io.get_ref())
            .is_some_and(|inner| inner.is::<StdoutClosed>())
    })
}
