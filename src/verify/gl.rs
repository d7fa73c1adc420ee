//! OpenGL as a verify path: the GLSL include compiled by the OpenGL driver's own GLSL
//! compiler (Mesa's, on llvmpipe, through EGL without a window), with and without
//! `#define UNITPACK_PRECISE precise`. The Vulkan paths hand the driver SPIR-V that
//! glslang or naga already lowered; here the driver parses the text itself, and Mesa's
//! GLSL front end folds comparisons and rewrites arithmetic on its own terms where no
//! `precise` forbids it. That is where a NaN test written as a float comparison was
//! folded away (`docs/design/portability.md`), so both forms run here.
//!
//! A few independent contexts serve the threads of a run: a caller takes a free one to
//! compile a program, so compiles proceed in parallel, and the program is run and deleted
//! in that context only, and llvmpipe spreads each dispatch over the cores. Programs are not
//! shared between contexts: with one share group, a program linked in one context and
//! dispatched in another crashed some full verify runs on the 2-core machine (a SIGSEGV
//! inside llvmpipe's `swrast_dri.so`, under `Gl::run_selected`).

use anyhow::{Context as _, Result, anyhow, bail};
use glow::HasContext;
use khronos_egl as egl;
use std::sync::{Mutex, OnceLock};

/// `EGL_PLATFORM_SURFACELESS_MESA`: a display without a window system.
const PLATFORM_SURFACELESS_MESA: egl::Enum = 0x31DD;

/// What to install when no EGL or no OpenGL 4.3 driver answers.
const NO_GL: &str = "no OpenGL 4.3 context through EGL; install the Debian packages \
    libegl1 libegl-mesa0 libgl1-mesa-dri (Mesa's EGL and llvmpipe)";

/// Items per dispatch: 65535 groups of 64, so that the offsets of a chunk's buffer ranges
/// (a multiple of 65535·64·4 bytes) are multiples of 256, every driver's alignment.
const CHUNK: usize = 65535 * 64;

type Egl = egl::DynamicInstance<egl::EGL1_5>;

struct State {
    context: egl::Context,
    gl: glow::Context,
}

/// Independent OpenGL 4.3 core contexts, shared by the threads of a verify run.
pub struct Gl {
    egl: Egl,
    display: egl::Display,
    states: Vec<Mutex<State>>,
    /// `GL_RENDERER`, for reports (`llvmpipe (LLVM 15.0.6, 256 bits)`).
    pub renderer: String,
}

// The EGL handles are raw pointers that EGL allows any thread to use; the context is
// only ever current on the thread holding the lock.
unsafe impl Send for Gl {}
unsafe impl Sync for Gl {}

/// A compiled selecting kernel: one program, its selector uniform, and the context that
/// owns it (the only one it is used in).
pub struct Program {
    program: glow::Program,
    selector: Option<glow::UniformLocation>,
    context: usize,
}

/// A context made current on this thread for as long as the guard lives.
struct Current<'a> {
    gl: &'a Gl,
    state: std::sync::MutexGuard<'a, State>,
    /// Which of [`Gl::states`] this is.
    index: usize,
}

impl Drop for Current<'_> {
    fn drop(&mut self) {
        let _ = self.gl.egl.make_current(self.gl.display, None, None, None);
    }
}

impl Gl {
    /// The process's contexts for the CPU (`software`) or the GPU, opened on first use
    /// with `contexts` contexts and never closed: unloading libEGL while the driver's
    /// threads live would crash the process at exit, as would terminating a display
    /// another run still uses.
    pub fn shared(software: bool, contexts: usize) -> Result<&'static Gl> {
        static SHARED: [OnceLock<Result<Gl, String>>; 2] = [OnceLock::new(), OnceLock::new()];
        SHARED[usize::from(software)]
            .get_or_init(|| Gl::new(software, contexts).map_err(|e| format!("{e:#}")))
            .as_ref()
            .map_err(|e| anyhow!("{e}"))
    }

    /// `contexts` OpenGL 4.3 core contexts of the surfaceless EGL display (for a GPU
    /// without that platform, the default display). With
    /// `software`, the renderer must be llvmpipe, the CPU implementation that rounds like
    /// lavapipe; without, it must not be (a GPU run's rows are the GPU's).
    fn new(software: bool, contexts: usize) -> Result<Gl> {
        // SAFETY: loading libEGL runs its initializers, as any EGL client does.
        let lib = unsafe { libloading::Library::new("libEGL.so.1") }.context(NO_GL)?;
        let egl = unsafe { Egl::load_required_from(lib) }
            .map_err(|e| anyhow!("{e}"))
            .context(NO_GL)?;
        // SAFETY: the surfaceless platform takes no native display.
        let surfaceless = unsafe {
            egl.get_platform_display(
                PLATFORM_SURFACELESS_MESA,
                egl::DEFAULT_DISPLAY,
                &[egl::ATTRIB_NONE],
            )
        }
        .map_err(anyhow::Error::from)
        .and_then(|d| {
            egl.initialize(d)?;
            Ok(d)
        });
        let display = match surfaceless {
            Ok(d) => d,
            // A GPU vendor's EGL without Mesa's surfaceless platform (NVIDIA's) opens
            // its headless device as the default display.
            Err(_) if !software => {
                // SAFETY: the default display takes no native display either.
                let d = unsafe { egl.get_display(egl::DEFAULT_DISPLAY) }
                    .ok_or_else(|| anyhow!("EGL has no default display").context(NO_GL))?;
                egl.initialize(d).context(NO_GL)?;
                d
            }
            Err(e) => return Err(e.context(NO_GL)),
        };
        egl.bind_api(egl::OPENGL_API).context(NO_GL)?;
        let config = egl
            .choose_first_config(
                display,
                &[
                    egl::RENDERABLE_TYPE,
                    egl::OPENGL_BIT,
                    egl::SURFACE_TYPE,
                    0,
                    egl::NONE,
                ],
            )
            .context(NO_GL)?
            .ok_or_else(|| anyhow!("EGL offers no OpenGL configuration").context(NO_GL))?;
        let attributes = [
            egl::CONTEXT_MAJOR_VERSION,
            4,
            egl::CONTEXT_MINOR_VERSION,
            3,
            egl::CONTEXT_OPENGL_PROFILE_MASK,
            egl::CONTEXT_OPENGL_CORE_PROFILE_BIT,
            egl::NONE,
        ];
        let mut states = Vec::new();
        let mut renderer = String::new();
        for _ in 0..contexts.max(1) {
            let context = egl
                .create_context(display, config, None, &attributes)
                .context(NO_GL)?;
            egl.make_current(display, None, None, Some(context))
                .context(NO_GL)?;
            // SAFETY: the context is current on this thread; the loader returns its
            // entry points (null for what it lacks, which glow then never calls).
            let gl = unsafe {
                glow::Context::from_loader_function(|name| {
                    egl.get_proc_address(name)
                        .map_or(std::ptr::null(), |f| f as *const _)
                })
            };
            renderer = unsafe { gl.get_parameter_string(glow::RENDERER) };
            egl.make_current(display, None, None, None)
                .context("releasing the OpenGL context")?;
            states.push(Mutex::new(State { context, gl }));
        }
        let cpu = renderer.contains("llvmpipe");
        if software && !cpu {
            bail!(
                "the OpenGL renderer is {renderer}, not llvmpipe: set LIBGL_ALWAYS_SOFTWARE=1 \
                 for the CPU adapter, or use --adapter gpu"
            );
        }
        if !software && cpu {
            bail!(
                "the OpenGL renderer is {renderer}, the CPU: no GPU answers through EGL \
                 (leave out --lang glsl, or verify on the CPU adapter)"
            );
        }
        Ok(Gl {
            egl,
            display,
            states,
            renderer,
        })
    }

    /// A free context (or the first, once it is free) made current on this thread.
    fn current(&self) -> Result<Current<'_>> {
        let free = self
            .states
            .iter()
            .enumerate()
            .find_map(|(i, m)| m.try_lock().ok().map(|s| (i, s)));
        match free {
            Some((index, state)) => self.make_current(index, state),
            None => self.current_at(0),
        }
    }

    /// Context `index`, once it is free, made current on this thread.
    fn current_at(&self, index: usize) -> Result<Current<'_>> {
        let state = self.states[index]
            .lock()
            .map_err(|_| anyhow!("an OpenGL call panicked on another thread"))?;
        self.make_current(index, state)
    }

    fn make_current<'a>(
        &'a self,
        index: usize,
        state: std::sync::MutexGuard<'a, State>,
    ) -> Result<Current<'a>> {
        self.egl
            .make_current(self.display, None, None, Some(state.context))
            .context("making the OpenGL context current")?;
        Ok(Current {
            gl: self,
            state,
            index,
        })
    }

    /// Compiles and links a compute shader; the driver's log is the error.
    pub fn program(&self, source: &str, selector: &str) -> Result<Program> {
        let cur = self.current()?;
        let gl = &cur.state.gl;
        // SAFETY: the context is current; every object is checked before use.
        unsafe {
            let shader = gl
                .create_shader(glow::COMPUTE_SHADER)
                .map_err(|e| anyhow!("creating a compute shader: {e}"))?;
            gl.shader_source(shader, source);
            gl.compile_shader(shader);
            if !gl.get_shader_compile_status(shader) {
                let log = gl.get_shader_info_log(shader);
                gl.delete_shader(shader);
                bail!("the OpenGL driver's GLSL compiler rejected the kernel:\n{log}");
            }
            let program = gl
                .create_program()
                .map_err(|e| anyhow!("creating a program: {e}"))?;
            gl.attach_shader(program, shader);
            gl.link_program(program);
            gl.delete_shader(shader);
            if !gl.get_program_link_status(program) {
                let log = gl.get_program_info_log(program);
                gl.delete_program(program);
                bail!("linking the kernel failed:\n{log}");
            }
            let selector = gl.get_uniform_location(program, selector);
            Ok(Program {
                program,
                selector,
                context: cur.index,
            })
        }
    }

    /// Runs function `index` of a selecting kernel over `input`, chunk by chunk; `sink`
    /// takes each chunk's output words.
    pub fn run_selected(
        &self,
        p: &Program,
        index: u32,
        input: &[u32],
        in_words: usize,
        out_words: usize,
        sink: &mut dyn FnMut(&[u32]),
    ) -> Result<()> {
        if in_words == 0 || out_words == 0 || !input.len().is_multiple_of(in_words) {
            bail!(
                "{} input words are no whole number of {in_words}-word items",
                input.len()
            );
        }
        let cur = self.current_at(p.context)?;
        let gl = &cur.state.gl;
        let n = input.len() / in_words;
        // SAFETY: the context is current; buffers are sized before they are bound.
        unsafe {
            gl.use_program(Some(p.program));
            if let Some(loc) = &p.selector {
                gl.uniform_1_u32(Some(loc), index);
            } else if index != 0 {
                bail!("the kernel has no selector, so it runs only function 0");
            }
            let (bi, bo) = (
                gl.create_buffer().map_err(|e| anyhow!("{e}"))?,
                gl.create_buffer().map_err(|e| anyhow!("{e}"))?,
            );
            let bytes: &[u8] = bytemuck::cast_slice(input);
            gl.bind_buffer(glow::SHADER_STORAGE_BUFFER, Some(bi));
            gl.buffer_data_u8_slice(glow::SHADER_STORAGE_BUFFER, bytes, glow::STATIC_DRAW);
            let out_len = (n.min(CHUNK) * out_words * 4) as i32;
            gl.bind_buffer(glow::SHADER_STORAGE_BUFFER, Some(bo));
            gl.buffer_data_size(glow::SHADER_STORAGE_BUFFER, out_len, glow::DYNAMIC_READ);
            let mut out = vec![0u32; n.min(CHUNK) * out_words];
            let mut start = 0;
            let result = loop {
                if start >= n {
                    break Ok(());
                }
                let items = (n - start).min(CHUNK);
                gl.bind_buffer_range(
                    glow::SHADER_STORAGE_BUFFER,
                    0,
                    Some(bi),
                    (start * in_words * 4) as i32,
                    (items * in_words * 4) as i32,
                );
                gl.bind_buffer_range(
                    glow::SHADER_STORAGE_BUFFER,
                    1,
                    Some(bo),
                    0,
                    (items * out_words * 4) as i32,
                );
                gl.dispatch_compute(items.div_ceil(64) as u32, 1, 1);
                gl.memory_barrier(glow::BUFFER_UPDATE_BARRIER_BIT);
                let got = &mut out[..items * out_words];
                gl.bind_buffer(glow::SHADER_STORAGE_BUFFER, Some(bo));
                gl.get_buffer_sub_data(
                    glow::SHADER_STORAGE_BUFFER,
                    0,
                    bytemuck::cast_slice_mut(got),
                );
                let err = gl.get_error();
                if err != glow::NO_ERROR {
                    break Err(anyhow!("OpenGL error 0x{err:x} running the kernel"));
                }
                sink(got);
                start += items;
            };
            gl.delete_buffer(bi);
            gl.delete_buffer(bo);
            result
        }
    }
}

/// The contexts live as long as the process, so a run deletes what it compiles.
impl Program {
    /// Frees the program now (a run compiles one per spec and form).
    pub fn delete(self, gl: &Gl) -> Result<()> {
        let cur = gl.current_at(self.context)?;
        // SAFETY: the context that made the program is current.
        unsafe { cur.state.gl.delete_program(self.program) };
        Ok(())
    }
}
