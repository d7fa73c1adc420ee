//! The C path: a generated header plus its test driver, compiled by the system C and C++
//! compilers with the flags the header asks for, and run over the verify inputs as raw
//! little-endian words through a pipe.

use anyhow::{Context, Result, bail};
use std::io::{ErrorKind, Write};
use std::path::PathBuf;
use std::process::{Command, Stdio};

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

/// A compiled driver, deleted with its directory.
pub struct Program {
    _dir: tempfile::TempDir,
    exe: PathBuf,
}

/// Compiles `source` (the driver with the header inlined).
pub fn compile(compiler: Compiler, source: &str) -> Result<Program> {
    let dir = tempfile::tempdir().context("creating a temporary directory")?;
    let src = dir.path().join("driver.c");
    std::fs::write(&src, source).context("writing the C driver")?;
    let exe = dir.path().join("driver");
    let (cc, lang_flags) = compiler.command();
    let mut cmd = Command::new(cc);
    cmd.args(lang_flags)
        .args(FLAGS)
        .arg(&src)
        .arg("-o")
        .arg(&exe)
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
    Ok(Program { _dir: dir, exe })
}

impl Program {
    /// Runs function number `index` of the driver over `input` words through its
    /// standard input and output.
    pub fn run(&self, index: usize, input: &[u32]) -> Result<Vec<u32>> {
        let mut child = Command::new(&self.exe)
            .arg(index.to_string())
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .context("running the C driver")?;
        let mut stdin = child.stdin.take().expect("piped stdin");
        // The driver reads and writes native-endian words, as this process holds them.
        let bytes: Vec<u8> = bytemuck::cast_slice(input).to_vec();
        // Feed the input while the output is read, so neither pipe fills up and blocks.
        let writer = std::thread::spawn(move || stdin.write_all(&bytes));
        let out = child
            .wait_with_output()
            .context("reading the C driver's output")?;
        writer
            .join()
            .expect("input writer")
            .context("writing the C driver's input")?;
        if !out.status.success() {
            bail!("the C driver failed ({})", out.status);
        }
        Ok(out
            .stdout
            .chunks_exact(4)
            .map(|c| u32::from_ne_bytes([c[0], c[1], c[2], c[3]]))
            .collect())
    }
}
