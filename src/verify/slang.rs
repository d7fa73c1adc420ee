//! The Slang paths: the HLSL include through Slang's compiler library, on each route a
//! user of Slang may take to SPIR-V. Slang compiles HLSL as it is, and its direct SPIR-V
//! backend runs its own optimizer and emits no `NoContraction`, so `precise` is lost there;
//! `-emit-spirv-via-glsl` writes GLSL and compiles it with the glslang Slang bundles, which
//! keeps it. Running each route on the same adapter as the other shader paths shows what
//! Slang itself does to the arithmetic.
//!
//! The library is loaded at run time (`libloading`), from `UNITPACK_SLANG` or from the
//! `slangpy` wheel that Python finds (it ships `libslang-compiler.so`), so that neither
//! building nor running the verifier needs Slang's headers or its SDK. Slang's legacy C
//! API is enough: a session, a compile request given slangc's own command line, and the
//! request's code.

use anyhow::{Context, Result, anyhow, bail};
use std::ffi::{CStr, CString, c_char, c_int, c_void};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{Mutex, OnceLock};

/// A route from HLSL to SPIR-V through Slang.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Route {
    /// Direct SPIR-V, `-O0`.
    O0,
    /// Direct SPIR-V at Slang's default optimization (`-O1`).
    Default,
    /// Direct SPIR-V, `-O3`.
    O3,
    /// `-emit-spirv-via-glsl`: GLSL, then the glslang bundled with Slang.
    ViaGlsl,
}

impl Route {
    /// slangc's flags for the route, after the target and entry point.
    fn flags(self) -> &'static [&'static str] {
        match self {
            Route::O0 => &["-O0"],
            Route::Default => &[],
            Route::O3 => &["-O3"],
            Route::ViaGlsl => &["-emit-spirv-via-glsl"],
        }
    }
}

/// The environment variable naming Slang's compiler library, where Python's `slangpy` is
/// not the one to use.
pub const LIBRARY_VAR: &str = "UNITPACK_SLANG";

const INSTALL: &str = "install the `slangpy` wheel, which ships Slang's compiler library \
     (`pip install slangpy`), or set UNITPACK_SLANG to the path of `libslang-compiler.so`";

type CreateSession = unsafe extern "C" fn(*const c_char) -> *mut c_void;
type CreateRequest = unsafe extern "C" fn(*mut c_void) -> *mut c_void;
type DestroyRequest = unsafe extern "C" fn(*mut c_void);
type ProcessArguments = unsafe extern "C" fn(*mut c_void, *const *const c_char, c_int) -> i32;
type Compile = unsafe extern "C" fn(*mut c_void) -> i32;
type Diagnostics = unsafe extern "C" fn(*mut c_void) -> *const c_char;
type RequestCode = unsafe extern "C" fn(*mut c_void, *mut usize) -> *const c_void;
type BuildTag = unsafe extern "C" fn() -> *const c_char;

/// Slang's compiler library, loaded once per process, with its sessions.
pub struct Slang {
    create_request: CreateRequest,
    destroy_request: DestroyRequest,
    process_arguments: ProcessArguments,
    compile: Compile,
    diagnostics: Diagnostics,
    request_code: RequestCode,
    create_session: CreateSession,
    /// Sessions not in use. A session is used by one thread at a time; the verify
    /// workers take one each, and creating one costs a third of a second.
    sessions: Mutex<Vec<Session>>,
    /// Slang's version, as `spGetBuildTagString` gives it.
    pub version: String,
    /// Keeps the function pointers valid.
    _library: libloading::Library,
}

/// A Slang session pointer, owned by the pool of one [`Slang`].
struct Session(*mut c_void);

// SAFETY: a session is only ever used by the one thread that took it from the pool.
unsafe impl Send for Session {}

impl Slang {
    /// The process's Slang library, loaded on first use.
    pub fn shared() -> Result<&'static Slang> {
        static SLANG: OnceLock<std::result::Result<Slang, String>> = OnceLock::new();
        SLANG
            .get_or_init(|| Slang::load().map_err(|e| format!("{e:#}")))
            .as_ref()
            .map_err(|e| anyhow!("{e}"))
    }

    fn load() -> Result<Slang> {
        let path = library_path()?;
        // SAFETY: loading Slang's library runs its initialisers, which set up nothing
        // but its own state; each symbol below is declared with the signature slang.h
        // gives it.
        unsafe {
            let library = libloading::Library::new(&path)
                .with_context(|| format!("loading Slang's compiler {}", path.display()))?;
            macro_rules! symbol {
                ($name:literal) => {
                    *library
                        .get(concat!($name, "\0").as_bytes())
                        .with_context(|| format!("{} exports no `{}`", path.display(), $name))?
                };
            }
            let tag: BuildTag = symbol!("spGetBuildTagString");
            let version = CStr::from_ptr(tag()).to_string_lossy().into_owned();
            Ok(Slang {
                create_session: symbol!("spCreateSession"),
                create_request: symbol!("spCreateCompileRequest"),
                destroy_request: symbol!("spDestroyCompileRequest"),
                process_arguments: symbol!("spProcessCommandLineArguments"),
                compile: symbol!("spCompile"),
                diagnostics: symbol!("spGetDiagnosticOutput"),
                request_code: symbol!("spGetCompileRequestCode"),
                sessions: Mutex::new(Vec::new()),
                version,
                _library: library,
            })
        }
    }

    /// Compiles the HLSL compute kernel `source` (entry point `main`) on `route` and
    /// returns its SPIR-V, made acceptable to `spirv-val` (see [`plain_source_language`]).
    pub fn spirv(&self, source: &str, route: Route) -> Result<Vec<u32>> {
        let session = self.take_session()?;
        let result = self.compile_with(&session, source, route);
        self.sessions
            .lock()
            .map_err(|_| anyhow!("Slang's session pool is poisoned"))?
            .push(session);
        let mut words = result?;
        plain_source_language(&mut words)?;
        Ok(words)
    }

    /// An idle session, or a new one. Sessions are created under the pool's lock, one at a
    /// time, since creating one loads Slang's core module into shared state; they are kept
    /// for the life of the process.
    fn take_session(&self) -> Result<Session> {
        let mut idle = self
            .sessions
            .lock()
            .map_err(|_| anyhow!("Slang's session pool is poisoned"))?;
        if let Some(s) = idle.pop() {
            return Ok(s);
        }
        // SAFETY: `spCreateSession` takes a deprecated, nullable argument.
        let session = unsafe { (self.create_session)(std::ptr::null()) };
        drop(idle);
        if session.is_null() {
            bail!("Slang could not create a session");
        }
        Ok(Session(session))
    }

    fn compile_with(&self, session: &Session, source: &str, route: Route) -> Result<Vec<u32>> {
        // slangc reads the source from a file, as a user's build would.
        let file = super::tools::temp_file("hlsl", source.as_bytes())?;
        let path = file
            .path()
            .to_str()
            .context("a temporary path that is not UTF-8")?;
        let mut args = vec![
            path, "-target", "spirv", "-entry", "main", "-stage", "compute",
        ];
        args.extend(route.flags());
        let args: Vec<CString> = args
            .into_iter()
            .map(CString::new)
            .collect::<std::result::Result<_, _>>()
            .context("an argument with a NUL byte")?;
        let argv: Vec<*const c_char> = args.iter().map(|a| a.as_ptr()).collect();
        let argc = c_int::try_from(argv.len()).context("argument count")?;
        // SAFETY: the session is this thread's; the request is destroyed on every exit
        // below; `argv` holds `argc` NUL-terminated strings that outlive the calls; the
        // code pointer is read for the size Slang gives before the request is destroyed.
        unsafe {
            let request = (self.create_request)(session.0);
            if request.is_null() {
                bail!("Slang could not create a compile request");
            }
            let diagnostics = |request| {
                let p = (self.diagnostics)(request);
                if p.is_null() {
                    String::new()
                } else {
                    CStr::from_ptr(p).to_string_lossy().into_owned()
                }
            };
            let result = if (self.process_arguments)(request, argv.as_ptr(), argc) < 0 {
                Err(anyhow!(
                    "Slang refused its arguments {args:?}:\n{}",
                    diagnostics(request)
                ))
            } else if (self.compile)(request) < 0 {
                Err(anyhow!(
                    "Slang failed ({}):\n{}",
                    route_text(route),
                    diagnostics(request)
                ))
            } else {
                let mut size = 0usize;
                let code = (self.request_code)(request, &mut size);
                if code.is_null() || size == 0 || !size.is_multiple_of(4) {
                    Err(anyhow!(
                        "Slang gave no SPIR-V ({}):\n{}",
                        route_text(route),
                        diagnostics(request)
                    ))
                } else {
                    let bytes = std::slice::from_raw_parts(code.cast::<u8>(), size);
                    Ok(bytes
                        .chunks_exact(4)
                        .map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]]))
                        .collect())
                }
            };
            (self.destroy_request)(request);
            result
        }
    }
}

/// The slangc command line of a route, for messages.
fn route_text(route: Route) -> String {
    let mut s = "slangc -target spirv -entry main -stage compute".to_string();
    for f in route.flags() {
        s.push(' ');
        s.push_str(f);
    }
    s
}

/// Slang's `OpSource` names its own source language (11), which `spirv-val` releases
/// before 2024 reject; the operand is debug information, so it is set to Unknown (0).
fn plain_source_language(words: &mut [u32]) -> Result<()> {
    const OP_SOURCE: u32 = 3;
    if words.len() < 5 || words[0] != 0x0723_0203 {
        bail!("Slang's output is not SPIR-V");
    }
    let mut at = 5;
    while at < words.len() {
        let (count, op) = ((words[at] >> 16) as usize, words[at] & 0xffff);
        if count == 0 {
            bail!("Slang's SPIR-V has an instruction of no words at word {at}");
        }
        if op == OP_SOURCE && count >= 2 {
            words[at + 1] = 0;
        }
        at += count;
    }
    Ok(())
}

/// Where Slang's compiler library is: `UNITPACK_SLANG`, or the `slangpy` package that
/// `python3` finds (located without importing it, which would need its dependencies).
fn library_path() -> Result<PathBuf> {
    if let Some(p) = std::env::var_os(LIBRARY_VAR) {
        let p = PathBuf::from(p);
        if !p.is_file() {
            bail!("{LIBRARY_VAR} names {}, which is not a file", p.display());
        }
        return Ok(p);
    }
    let find = "import importlib.util as u\n\
                s = u.find_spec('slangpy')\n\
                print(s.submodule_search_locations[0] if s and s.submodule_search_locations else '')";
    let out = Command::new("python3").args(["-c", find]).output();
    let dir = match out {
        Ok(o) if o.status.success() => String::from_utf8_lossy(&o.stdout).trim().to_string(),
        _ => String::new(),
    };
    if dir.is_empty() {
        bail!("Slang's compiler library not found: {INSTALL}");
    }
    find_library(Path::new(&dir))
        .with_context(|| format!("no Slang compiler library in {dir}: {INSTALL}"))
}

/// `libslang-compiler.so*` (the wheel's name) or `libslang.so*` (the SDK's) in `dir`.
fn find_library(dir: &Path) -> Result<PathBuf> {
    let mut found: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("reading {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.file_name().and_then(|n| n.to_str()).is_some_and(|n| {
                n.starts_with("libslang-compiler.so") || n.starts_with("libslang.so")
            })
        })
        .collect();
    found.sort();
    found.into_iter().next().context("no libslang-compiler.so")
}
