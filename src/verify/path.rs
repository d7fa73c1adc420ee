//! The paths emitted code takes to a driver ([`Path`]), the devices a Vulkan path runs
//! on ([`Device`]) and a report row's path column ([`Run`]).

use super::*;
use crate::emit::Lang;
use std::fmt;

/// One way emitted code reaches the driver.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Path {
    WgslNaga,
    GlslNaga,
    GlslGlslang,
    HlslGlslangOd,
    HlslGlslangDefault,
    /// The HLSL include through Slang's direct SPIR-V backend ([`slang`]), `-O0`.
    HlslSlangO0,
    /// The same at Slang's default optimization.
    HlslSlang,
    /// The same at `-O3`.
    HlslSlangO3,
    /// Through Slang's `-emit-spirv-via-glsl`, the route that keeps `precise`.
    HlslSlangViaGlsl,
    /// The GLSL include through the OpenGL driver's own GLSL compiler (EGL; Mesa's
    /// llvmpipe on the CPU adapter), without `precise`: what a user who leaves
    /// `UNITPACK_PRECISE` undefined gets ([`gl`]).
    GlslGl,
    /// The same with `#define UNITPACK_PRECISE precise`.
    GlslGlPrecise,
    /// The C header through the system C compiler (C99).
    CC,
    /// The same header compiled as C++.
    CCpp,
    /// No emitted code: the model itself on four SSE2 lanes ([`Function::eval_lanes`]),
    /// what the CPU batches run without AVX2. Verified whatever the languages asked for.
    Lanes,
    /// The model on eight AVX2 lanes ([`Function::eval_lanes8`]), what the CPU batches run
    /// where the processor has AVX2. Verified whatever the languages asked for; an error
    /// on a processor without AVX2.
    Lanes8,
    /// The WGSL include through WebGPU in headless Chromium: Tint compiles it, Dawn runs
    /// it on the browser's adapter (SwiftShader without a GPU) ([`browser`]).
    WgslTint,
    /// The GLSL include as GLSL ES 3.00 through WebGL 2 in headless Chromium: ANGLE
    /// translates it for the browser's GL backend (SwiftShader's Vulkan without a GPU).
    GlslAngle,
}

impl Path {
    pub const ALL: [Path; 17] = [
        Path::WgslNaga,
        Path::GlslNaga,
        Path::GlslGlslang,
        Path::HlslGlslangOd,
        Path::HlslGlslangDefault,
        Path::HlslSlangO0,
        Path::HlslSlang,
        Path::HlslSlangO3,
        Path::HlslSlangViaGlsl,
        Path::GlslGl,
        Path::GlslGlPrecise,
        Path::CC,
        Path::CCpp,
        Path::Lanes,
        Path::Lanes8,
        Path::WgslTint,
        Path::GlslAngle,
    ];
    /// The emitted language the path runs, if any.
    pub fn lang(self) -> Option<Lang> {
        match self {
            Path::WgslNaga | Path::WgslTint => Some(Lang::Wgsl),
            Path::GlslNaga
            | Path::GlslGlslang
            | Path::GlslGl
            | Path::GlslGlPrecise
            | Path::GlslAngle => Some(Lang::Glsl),
            Path::HlslGlslangOd
            | Path::HlslGlslangDefault
            | Path::HlslSlangO0
            | Path::HlslSlang
            | Path::HlslSlangO3
            | Path::HlslSlangViaGlsl => Some(Lang::Hlsl),
            Path::CC | Path::CCpp => Some(Lang::C),
            Path::Lanes | Path::Lanes8 => None,
        }
    }
    /// Whether the path runs a shader on the Vulkan adapter.
    pub fn on_vulkan(self) -> bool {
        self.lang().is_some_and(|l| l != Lang::C) && !self.on_gl() && !self.in_browser()
    }
    /// Whether the path runs in headless Chromium ([`browser`]).
    pub fn in_browser(self) -> bool {
        matches!(self, Path::WgslTint | Path::GlslAngle)
    }
    /// Whether the path runs a shader through OpenGL.
    pub(super) fn on_gl(self) -> bool {
        matches!(self, Path::GlslGl | Path::GlslGlPrecise)
    }
    /// How many items of each function the path runs where it runs a sample
    /// ([`sample`]): the paths whose arithmetic another path already runs on every item
    /// with the same code generator, so that what they add is their front end's reading
    /// of the text. `None`: every item.
    pub fn sampled(self) -> Option<usize> {
        match self {
            Path::GlslGl
            | Path::GlslGlPrecise
            | Path::HlslSlangO0
            | Path::HlslSlang
            | Path::HlslSlangO3
            | Path::HlslSlangViaGlsl
            | Path::WgslTint
            | Path::GlslAngle => Some(GL_ITEMS),
            Path::CCpp => Some(CPP_ITEMS),
            _ => None,
        }
    }
    /// Whether the path's compiler regroups float products itself, which the doc comments
    /// exclude ("not where a compiler may reassociate"): Slang's direct SPIR-V at its
    /// default optimization and at `-O3` (it drops `precise`, then its optimizer turns
    /// `(x·k)·(x·k)` into `(x·x)·k²` and the like). There a function with float outputs is
    /// measured, not held to the model's bits; packed codes and indices still are, but for
    /// the lean tier's (an engine format's), whose promise excludes reassociation.
    pub fn regroups(self) -> bool {
        matches!(self, Path::HlslSlang | Path::HlslSlangO3)
    }
    /// Whether the path's compiler contracts float operations the include leaves
    /// unmarked where no other path's does: OpenGL's own GLSL compiler without `precise`
    /// (Mesa fuses `a*b + c` there). A family whose lean-tier arithmetic is contracted
    /// there ([`crate::codecs::Family::contracted`]) is measured there, not held.
    pub fn contracts(self) -> bool {
        self == Path::GlslGl
    }
}

impl fmt::Display for Path {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Path::WgslNaga => "wgsl/naga",
            Path::GlslNaga => "glsl/naga",
            Path::GlslGlslang => "glsl/glslang",
            Path::HlslGlslangOd => "hlsl/glslang -Od",
            Path::HlslGlslangDefault => "hlsl/glslang",
            Path::HlslSlangO0 => "hlsl/slang -O0",
            Path::HlslSlang => "hlsl/slang",
            Path::HlslSlangO3 => "hlsl/slang -O3",
            Path::HlslSlangViaGlsl => "hlsl/slang via glsl",
            Path::GlslGl => "glsl/gl",
            Path::GlslGlPrecise => "glsl/gl precise",
            Path::CC => "c/cc -O2",
            Path::CCpp => "c/c++ -O2",
            Path::Lanes => "cpu/4 lanes",
            Path::Lanes8 => "cpu/8 lanes",
            Path::WgslTint => "wgsl/tint",
            Path::GlslAngle => "glsl/angle",
        })
    }
}

/// Where a Vulkan path's module runs: on the run's adapter, or on SwiftShader beside it
/// (a default run on lavapipe runs every SPIR-V route on both).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Device {
    Main,
    SwiftShader,
}

/// One path on one device: a row's `path` column.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Run {
    pub path: Path,
    pub device: Device,
}

impl Run {
    /// How many items of each function the run takes ([`Path::sampled`]); SwiftShader
    /// reads the same module as lavapipe, which runs every item, so it takes a sample.
    pub(super) fn sampled(self) -> Option<usize> {
        match self.device {
            Device::SwiftShader => Some(GL_ITEMS),
            Device::Main => self.path.sampled(),
        }
    }
    /// Whether the run's implementation flushes denormals to zero (SwiftShader, and the
    /// browsers, which run on it without a GPU or on a GPU that may flush), where the model
    /// keeps them: float forms, which take float inputs, are measured there, not held.
    pub(super) fn flushes(self) -> bool {
        self.device == Device::SwiftShader || self.path.in_browser()
    }
}

impl fmt::Display for Run {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.device {
            Device::Main => write!(f, "{}", self.path),
            Device::SwiftShader => write!(f, "{} on swiftshader", self.path),
        }
    }
}
