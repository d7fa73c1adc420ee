//! The C path: a generated header plus its test driver, compiled by the system C and C++
//! compilers with the flags the header asks for into a shared library, loaded into this
//! process and run over the verify inputs in place: no item is copied through a pipe,
//! which had cost more than the functions themselves on 2^24-code decoders.

use crate::emit::lang::c::DRIVER_ENTRY;
use anyhow::{Context, Result, bail};
use std::io::ErrorKind;
use std::process::Command;

/// A compiler and its flags for one verification path.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Compiler {
    /// `cc -std=c99`
    C,
    /// `c++ -x c++ -std=c++11`
    Cpp,
}

/// The flags every build of a header must keep: optimized, no contraction, no
/// fast-math, warnings as errors so that a sloppy header fails here first.
pub const FLAGS: [&str; 5] = ["-O2", "-ffp-contract=off", "-Wall", "-Wextra", "-Werror"];

impl Compiler {
    fn command(self) -> (&'static str, &'static [&'static str]) {
        match self {
            Compiler::C => ("cc", &["-std=c99", "-pedantic"]),
            Compiler::Cpp => ("c++", &["-x", "c++", "-std=c++11"]),
        }
    }
}

/// The driver's entry: `(index, in_words, out_words, in, out, n)` (see
/// [`crate::emit::lang::c::driver`]).
type Entry = unsafe extern "C" fn(u32, u32, u32, *const u32, *mut u32, usize) -> i32;

/// A compiled driver, loaded; its file is deleted with its directory.
pub struct Program {
    entry: Entry,
    /// Keeps `entry` valid.
    _library: libloading::Library,
    _dir: tempfile::TempDir,
}

/// Compiles `source` (the driver with the header inlined) and loads it.
pub fn compile(compiler: Compiler, source: &str) -> Result<Program> {
    let dir = tempfile::tempdir().context("creating a temporary directory")?;
    let src = dir.path().join("driver.c");
    std::fs::write(&src, source).context("writing the C driver")?;
    let lib = dir.path().join("driver.so");
    let (cc, lang_flags) = compiler.command();
    let mut cmd = Command::new(cc);
    cmd.args(lang_flags)
        .args(FLAGS)
        .args(["-shared", "-fPIC"])
        .arg(&src)
        .arg("-o")
        .arg(&lib)
        .arg("-lm");
    let out = match cmd.output() {
        Ok(o) => o,
        Err(e) if e.kind() == ErrorKind::NotFound => {
            bail!("`{cc}` not found on PATH; install the Debian packages `gcc` and `g++`")
        }
        Err(e) => return Err(e).context(format!("running `{cc}`")),
    };
    if !out.status.success() {
        bail!(
            "`{cc} {} {}` failed:\n{}{}",
            lang_flags.join(" "),
            FLAGS.join(" "),
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
    }
    // SAFETY: the library is the driver just compiled from generated code: loading it
    // runs no initialisers of ours, and its entry has the signature `Entry` by
    // construction (`driver` declares it so, with C linkage in both languages).
    let (library, entry) = unsafe {
        let library = libloading::Library::new(&lib)
            .with_context(|| format!("loading the C driver {}", lib.display()))?;
        let entry = *library
            .get::<Entry>(DRIVER_ENTRY.as_bytes())
            .with_context(|| format!("the C driver exports no `{DRIVER_ENTRY}`"))?;
        (library, entry)
    };
    Ok(Program {
        entry,
        _library: library,
        _dir: dir,
    })
}

impl Program {
    /// Runs function number `index` of the driver over `input`, items of `in_words`
    /// words, writing `out_words` words per item to `out`.
    pub fn run(
        &self,
        index: usize,
        input: &[u32],
        in_words: usize,
        out_words: usize,
        out: &mut [u32],
    ) -> Result<()> {
        if in_words == 0 || !input.len().is_multiple_of(in_words) {
            bail!(
                "{} input words are not whole items of {in_words}",
                input.len()
            );
        }
        if out.len() != input.len() / in_words * out_words {
            bail!(
                "room for {} output words, not the {} of {} items",
                out.len(),
                input.len() / in_words * out_words,
                input.len() / in_words
            );
        }
        let index = u32::try_from(index).context("function index")?;
        let widths = (
            u32::try_from(in_words).context("input width")?,
            u32::try_from(out_words).context("output width")?,
        );
        let entry = self.entry;
        let rc = std::sync::atomic::AtomicI32::new(0);
        super::on_all_cores(input, out, in_words, out_words, |i, o| {
            let n = i.len() / in_words;
            // SAFETY: `i` holds `n` items of `in_words` and `o` room for `n` items of
            // `out_words`; the driver refuses widths that are not its function's before
            // touching either, and the generated functions touch no other memory.
            let r = unsafe { entry(index, widths.0, widths.1, i.as_ptr(), o.as_mut_ptr(), n) };
            rc.fetch_max(r, std::sync::atomic::Ordering::Relaxed);
        });
        match rc.into_inner() {
            0 => Ok(()),
            2 => bail!("the C driver has no function {index}"),
            3 => bail!("C driver function {index} does not take {in_words} words to {out_words}"),
            rc => bail!("the C driver returned {rc} for function {index}"),
        }
    }
}
