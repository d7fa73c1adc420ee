//! Running compute kernels on the Vulkan CPU adapter (lavapipe) through wgpu, so emitted
//! shader functions can be compared bit for bit with the Rust model.
//!
//! # Binding contract
//!
//! Every kernel has entry point `main`, workgroup size 64×1×1, and two bindings in
//! descriptor set / bind group 0:
//!
//! * binding 0: read-only storage buffer, a runtime-sized array of `u32` (the input: `n` items
//!   of `IN_WORDS` words each, floats passed as their bits);
//! * binding 1: read-write storage buffer, a runtime-sized array of `u32` (the output: `n`
//!   items of `OUT_WORDS` words each).
//!
//! [`Gpu::run`] dispatches `ceil(items / 64)` workgroups per chunk and binds buffers of exactly
//! the chunk's size, so each kernel bounds-checks itself with
//! `global_invocation_id.x < arrayLength(output) / OUT_WORDS`.
//!
//! # Selecting kernels
//!
//! `verify` compiles one kernel per spec and path for all the functions it runs, so that
//! each front end reads the include once per spec rather than once per function. Such a
//! kernel's `main` switches on specialization constant 0 (`layout(constant_id = 0)` in
//! GLSL, `[[vk::constant_id(0)]]` in HLSL, `@id(0) override` in WGSL) and calls that
//! function's runner, which bounds-checks with its own `OUT_WORDS` as above.
//! [`Gpu::selecting`] parses and validates the module once; [`Gpu::run_selected`] builds
//! the pipeline of one function: with the pipeline constant set (naga paths) or, since
//! passthrough SPIR-V takes no specialization info, with the selector made a plain
//! constant in a copy of the words. Either way the driver sees a constant and compiles
//! that function's case alone; a selector read at run time would have a CPU driver run
//! every case under masks. (`crate::emit::lang::Backend::kernel` writes these kernels; `tests/gpu_smoke.rs`
//! runs one on every path.)
//!
//! # Kernel skeletons
//!
//! Minimal single-function kernels for each path, verified by `tests/gpu_smoke.rs`.
//! Replace `IN_WORDS`, `OUT_WORDS` and the `// body` part; everything else is the
//! required shape.
//!
//! ## 1. WGSL, compiled by naga inside wgpu ([`Shader::Wgsl`])
//!
//! ```text
//! @group(0) @binding(0) var<storage, read> input_words: array<u32>;
//! @group(0) @binding(1) var<storage, read_write> output_words: array<u32>;
//!
//! const IN_WORDS: u32 = 2u;
//! const OUT_WORDS: u32 = 3u;
//!
//! @compute @workgroup_size(64)
//! fn main(@builtin(global_invocation_id) id: vec3<u32>) {
//!     let i = id.x;
//!     if (i >= arrayLength(&output_words) / OUT_WORDS) {
//!         return;
//!     }
//!     let a = bitcast<f32>(input_words[i * IN_WORDS + 0u]);
//!     let b = bitcast<f32>(input_words[i * IN_WORDS + 1u]);
//!     // body
//!     output_words[i * OUT_WORDS + 0u] = bitcast<u32>(a / sqrt(b));
//! }
//! ```
//!
//! ## 2. GLSL 450 compute, compiled by naga's GLSL frontend inside wgpu ([`Shader::GlslNaga`])
//!
//! ## 3. The same GLSL through `glslangValidator -V`, run as SPIR-V passthrough ([`Shader::SpirV`])
//!
//! One source serves both paths (naga accepts anonymous blocks, `std430` and `.length()`;
//! as GLSL requires, `#version 450` comes before anything else, so an include goes after it):
//!
//! ```text
//! #version 450
//! layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;
//!
//! layout(set = 0, binding = 0, std430) readonly buffer InputWords { uint input_words[]; };
//! layout(set = 0, binding = 1, std430) buffer OutputWords { uint output_words[]; };
//!
//! const uint IN_WORDS = 2u;
//! const uint OUT_WORDS = 3u;
//!
//! void main() {
//!     uint i = gl_GlobalInvocationID.x;
//!     if (i >= uint(output_words.length()) / OUT_WORDS) {
//!         return;
//!     }
//!     float a = uintBitsToFloat(input_words[i * IN_WORDS + 0u]);
//!     float b = uintBitsToFloat(input_words[i * IN_WORDS + 1u]);
//!     // body
//!     output_words[i * OUT_WORDS + 0u] = floatBitsToUint(a / sqrt(b));
//! }
//! ```
//!
//! glslang: `tools::glslang_spirv(src, GlslangInput::Glsl { stage: "comp" }, HlslOpt::Default)`,
//! after `verify` has made the version line `#version 430` (the first with compute shaders)
//! and defined the precise macro as `precise`.
//!
//! ## 4. HLSL compute through `glslangValidator -D -V` (`-Od` and default), SPIR-V passthrough
//!
//! `[[vk::binding(binding, set)]]` pins the Vulkan binding (glslang would otherwise derive it
//! from `register()`); `StructuredBuffer<uint>` becomes a read-only (`NonWritable`) storage
//! block and `RWStructuredBuffer<uint>` a writable one. No counter buffer is generated as long
//! as `IncrementCounter`/`Append` are not used. `GetDimensions(count, stride)` on a structured
//! buffer compiles to `OpArrayLength`, i.e. the element count of the bound range. The entry
//! point keeps the name given with `-e` (`main`). `static const` is required for constants.
//!
//! ```text
//! [[vk::binding(0, 0)]] StructuredBuffer<uint> input_words;
//! [[vk::binding(1, 0)]] RWStructuredBuffer<uint> output_words;
//!
//! static const uint IN_WORDS = 2u;
//! static const uint OUT_WORDS = 3u;
//!
//! [numthreads(64, 1, 1)]
//! void main(uint3 id : SV_DispatchThreadID)
//! {
//!     uint out_len, out_stride;
//!     output_words.GetDimensions(out_len, out_stride);
//!     uint i = id.x;
//!     if (i >= out_len / OUT_WORDS) {
//!         return;
//!     }
//!     float a = asfloat(input_words[i * IN_WORDS + 0u]);
//!     float b = asfloat(input_words[i * IN_WORDS + 1u]);
//!     // body
//!     output_words[i * OUT_WORDS + 0u] = asuint(a / sqrt(b));
//! }
//! ```
//!
//! glslang: `tools::glslang_spirv(src, GlslangInput::Hlsl { stage: "comp", entry: "main" },
//! HlslOpt::Od)` (or `HlslOpt::Default`); run `tools::spirv_val` on the words before
//! [`Gpu::run`], since passthrough SPIR-V reaches the driver unvalidated.
//!
//! # Notes on the driver (lavapipe, Mesa 22.3.6, LLVM 15)
//!
//! On this driver `a * b + c` is not contracted into an FMA, denormals are neither flushed
//! on input nor on output, and `/`, `sqrt`, `inverseSqrt`, `length`, `normalize`, `dot`,
//! WGSL `round` / GLSL `roundEven` / HLSL `round` (all ties-to-even here; GLSL's plain `round`
//! leaves ties implementation-defined, so emit `roundEven`), `fract`, float<->int conversions
//! match correctly rounded Rust f32 arithmetic on every path; `cos`, `atan2` and other transcendentals do not (they are
//! approximations, as the Vulkan spec allows). Real GPUs are looser than lavapipe (e.g.
//! `inverseSqrt`, division and FMA contraction), so bit-exactness proven here is a property of
//! the emitted code on a correctly rounded implementation, not of every GPU.

use std::borrow::Cow;
use std::sync::mpsc;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Duration;

use anyhow::{Context, anyhow, bail};

/// Workgroup size every kernel must declare (`@workgroup_size(64)`, `local_size_x = 64`,
/// `[numthreads(64, 1, 1)]`); [`Gpu::run`] dispatches `ceil(items / 64)` workgroups per chunk.
pub const WORKGROUP_SIZE: u32 = 64;

/// Upper bound on the number of items per dispatch. Inputs larger than this are split into
/// several dispatches, so `pub` lets tests pick an item count that is guaranteed to exercise
/// chunking. The effective chunk can be smaller when items are so wide that a chunk's buffer
/// would exceed the device's storage-binding limit (see [`Gpu::chunk_items`]).
pub const MAX_CHUNK_ITEMS: usize = 1 << 20;

/// How long one chunk may run before [`Gpu::run`] gives up. A kernel that never terminates
/// (or a wedged driver) must surface as an error rather than hang the test process forever.
/// Generous, because lavapipe on a small CI machine shared by parallel tests is slow.
pub const CHUNK_TIMEOUT: Duration = Duration::from_secs(600);

/// Which way a compute shader reaches the driver.
///
/// All three use the same binding layout (see the module docs), so one kernel body can be
/// wrapped for each path and the outputs compared bit for bit.
#[derive(Debug, Clone, Copy)]
pub enum Shader<'a> {
    /// WGSL source, compiled by naga inside wgpu (WGSL -> naga IR -> SPIR-V).
    Wgsl(&'a str),
    /// A GLSL 450 compute shader compiled by naga's GLSL frontend inside wgpu
    /// (`ShaderSource::Glsl`, stage compute), i.e. GLSL -> naga IR -> SPIR-V.
    GlslNaga(&'a str),
    /// SPIR-V words (e.g. from glslang), handed to the Vulkan driver untouched via
    /// `Device::create_shader_module_passthrough` (needs `Features::PASSTHROUGH_SHADERS`),
    /// so that what runs is exactly what glslang produced, with no naga round trip.
    SpirV(&'a [u32]),
}

impl Shader<'_> {
    fn kind(&self) -> &'static str {
        match self {
            Shader::Wgsl(_) => "WGSL (naga)",
            Shader::GlslNaga(_) => "GLSL (naga)",
            Shader::SpirV(_) => "SPIR-V (passthrough)",
        }
    }
}

/// A selecting kernel's module, parsed and validated once ([`Gpu::selecting`]), from which
/// [`Gpu::run_selected`] builds each function's pipeline.
pub struct Selecting {
    module: SelectingModule,
    kind: &'static str,
}

enum SelectingModule {
    /// A naga module: the selector is set as a pipeline constant.
    Naga(wgpu::ShaderModule),
    /// Passthrough SPIR-V, which takes no pipeline constants: the selector is made a
    /// constant in a copy of the words ([`with_selector`]) for each function.
    SpirV(Vec<u32>),
}

/// `words` with specialization constant 0 (the selecting kernel's selector) made the
/// plain constant `value`: its `OpSpecConstant` an `OpConstant`, its `SpecId` decoration
/// gone. The passthrough path gives the driver no specialization info, so the selector
/// would be its default anyway; as a constant, every driver drops the other functions
/// before it compiles. With the selector left a specialization constant, SwiftShader
/// took about three times as long to create and run each pipeline, with the same bits
/// (docs/design/speed.md).
pub fn with_selector(words: &[u32], value: u32) -> anyhow::Result<Vec<u32>> {
    const OP_CONSTANT: u32 = 43;
    const OP_SPEC_CONSTANT: u32 = 50;
    const OP_DECORATE: u32 = 71;
    const SPEC_ID: u32 = 1;
    let instructions = |words: &[u32]| -> anyhow::Result<Vec<usize>> {
        let mut at = 5; // after the header
        let mut starts = Vec::new();
        while at < words.len() {
            let count = (words[at] >> 16) as usize;
            if count == 0 || at + count > words.len() {
                bail!("malformed SPIR-V at word {at}");
            }
            starts.push(at);
            at += count;
        }
        Ok(starts)
    };
    let starts = instructions(words)?;
    let op = |at: usize| (words[at] & 0xffff, (words[at] >> 16) as usize);
    let decoration = *starts
        .iter()
        .find(|&&at| {
            let (code, count) = op(at);
            code == OP_DECORATE && count == 4 && words[at + 2] == SPEC_ID && words[at + 3] == 0
        })
        .ok_or_else(|| anyhow!("the SPIR-V has no specialization constant 0 (the selector)"))?;
    let id = words[decoration + 1];
    let constant = *starts
        .iter()
        .find(|&&at| {
            let (code, count) = op(at);
            code == OP_SPEC_CONSTANT && count == 4 && words[at + 2] == id
        })
        .ok_or_else(|| anyhow!("specialization constant 0 is not a 32-bit OpSpecConstant"))?;
    let mut out = words.to_vec();
    out[constant] = (4 << 16) | OP_CONSTANT;
    out[constant + 3] = value;
    // Removed last: decorations precede constants, so this moves the constant's words.
    out.drain(decoration..decoration + 4);
    Ok(out)
}

/// Which Vulkan adapter a [`Gpu`] runs on (`verify --adapter cpu|gpu`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Adapter {
    /// The CPU adapter (Mesa's lavapipe), where the canonical arithmetic is proven: it
    /// rounds correctly, keeps denormals and never fuses. The default.
    #[default]
    Cpu,
    #[cfg_attr(feature = "cli", value(name = "gpu"))]
    /// The first adapter that is not a CPU: the machine's own GPU, which the graphics APIs
    /// allow to round, flush and fuse differently (`verify --portable` models those
    /// liberties, alone and together).
    Hardware,
    /// SwiftShader, the Vulkan implementation Chromium ships (the Debian package
    /// `chromium` puts its driver in /usr/lib/chromium): what WebGPU and WebGL run on in a
    /// browser without a GPU. It flushes denormal inputs and results to zero and is
    /// otherwise correctly rounded and unfused, so packed codes hold and float forms are
    /// measured where a denormal is involved.
    #[cfg_attr(feature = "cli", value(name = "swiftshader"))]
    SwiftShader,
}

/// SwiftShader's Vulkan driver manifest, as Debian's `chromium` package installs it.
pub const SWIFTSHADER_ICD: &str = "/usr/lib/chromium/vk_swiftshader_icd.json";

/// Lets the Vulkan loader find SwiftShader beside the system's drivers: it reads
/// `VK_ADD_DRIVER_FILES` when an instance is created, so this runs before the process's
/// first instance, whichever adapter that one is for. Set only where the user has not set
/// it, and only once.
fn add_swiftshader_driver() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        if std::env::var_os("VK_ADD_DRIVER_FILES").is_none()
            && std::path::Path::new(SWIFTSHADER_ICD).exists()
        {
            // SAFETY: the verifier reads no environment on other threads while its first
            // Vulkan instance is being opened; glibc keeps earlier environment arrays
            // alive, so a concurrent reader elsewhere sees the old or the new one.
            unsafe { std::env::set_var("VK_ADD_DRIVER_FILES", SWIFTSHADER_ICD) };
        }
    });
}

/// Whether a Vulkan adapter is SwiftShader.
fn is_swiftshader(a: &wgpu::Adapter) -> bool {
    a.get_info().name.contains("SwiftShader")
}

/// A wgpu device on the Vulkan CPU adapter (lavapipe), plus the fixed binding layout that
/// every verification kernel uses.
///
/// `Gpu` is `Send + Sync`; one instance may be shared by many threads (wgpu error scopes
/// are thread-local, so concurrent [`Gpu::run`] calls do not see each other's errors), and
/// creating several instances in one process is fine too.
pub struct Gpu {
    device: wgpu::Device,
    queue: wgpu::Queue,
    adapter_name: String,
    driver: String,
    passthrough: bool,
    /// Largest storage-buffer binding the device accepts, in bytes.
    max_binding_bytes: u64,
    bind_group_layout: wgpu::BindGroupLayout,
    pipeline_layout: wgpu::PipelineLayout,
    /// Set by the device-lost callback, so later calls fail with the reason instead of hanging.
    lost: Arc<Mutex<Option<String>>>,
    /// Buffers of finished dispatches, for the next ([`Gpu::dispatch`]).
    spare: Mutex<Vec<Buffers>>,
}

/// One dispatch's input and output buffers, both mapped by the host
/// (`Features::MAPPABLE_PRIMARY_BUFFERS`): the input written in place, the output read in
/// place. Through staging buffers every word crossed memory twice more (a copy into the
/// staging buffer and the driver's copy out of it, the same again for the results), which
/// on lavapipe, whose device memory is host memory, cost more than a cheap kernel
/// (docs/design/speed.md). A dispatch takes spare buffers large enough rather than new
/// ones: the driver maps fresh memory page by page as it is first written. Each chunk
/// clears its output range first, so that what a kernel does not write reads as zeros, as
/// in a new buffer.
struct Buffers {
    input: wgpu::Buffer,
    output: wgpu::Buffer,
}

// Tests share one `Gpu` across threads; keep that guaranteed.
const _: fn() = || {
    fn assert_send_sync<T: Send + Sync>() {}
    assert_send_sync::<Gpu>();
};

impl std::fmt::Debug for Gpu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Gpu")
            .field("adapter_name", &self.adapter_name)
            .field("driver", &self.driver)
            .field("passthrough", &self.passthrough)
            .field("max_binding_bytes", &self.max_binding_bytes)
            .finish_non_exhaustive()
    }
}

const NO_ADAPTER: &str = "no Vulkan adapter found; install the Debian package \
`mesa-vulkan-drivers` (lavapipe, the Vulkan CPU driver)";

impl Gpu {
    /// Opens the Vulkan CPU adapter (lavapipe): [`Gpu::open`] with [`Adapter::Cpu`].
    pub fn new() -> anyhow::Result<Gpu> {
        Self::open(Adapter::Cpu)
    }

    /// Opens the adapter `which` asks for.
    ///
    /// [`Adapter::Cpu`] prefers the CPU adapter because it is deterministic and available
    /// on any CI machine; if there is none, the first Vulkan adapter is used. If no Vulkan
    /// adapter exists at all, the error tells the user to install `mesa-vulkan-drivers`.
    /// [`Adapter::Hardware`] takes the first adapter that is not a CPU, and its error lists
    /// the adapters that were found.
    pub fn open(which: Adapter) -> anyhow::Result<Gpu> {
        pollster::block_on(Self::new_async(which))
    }

    /// A process-wide `Gpu`, created on first use. Tests running in parallel threads can
    /// share it instead of each opening a device (which costs lavapipe a few threads and
    /// some memory each). The creation error, if any, is remembered and returned every time.
    pub fn shared() -> anyhow::Result<&'static Gpu> {
        Self::shared_on(Adapter::Cpu)
    }

    /// The process-wide `Gpu` on the adapter `which` asks for, as [`Gpu::shared`].
    pub fn shared_on(which: Adapter) -> anyhow::Result<&'static Gpu> {
        static SHARED: [OnceLock<Result<Gpu, String>>; 3] =
            [OnceLock::new(), OnceLock::new(), OnceLock::new()];
        SHARED[which as usize]
            .get_or_init(|| Gpu::open(which).map_err(|e| format!("{e:#}")))
            .as_ref()
            .map_err(|e| anyhow!("{e}"))
    }

    async fn new_async(which: Adapter) -> anyhow::Result<Gpu> {
        add_swiftshader_driver();
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = wgpu::Backends::VULKAN;
        desc.flags = wgpu::InstanceFlags::from_build_config().with_env();
        let instance = wgpu::Instance::new(desc);

        let adapters = instance.enumerate_adapters(wgpu::Backends::VULKAN).await;
        let is_cpu = |a: &wgpu::Adapter| a.get_info().device_type == wgpu::DeviceType::Cpu;
        let adapter = match which {
            Adapter::Cpu => match adapters
                .iter()
                .position(|a| is_cpu(a) && !is_swiftshader(a))
            {
                Some(i) => adapters.into_iter().nth(i),
                None => adapters.into_iter().next(),
            }
            .ok_or_else(|| anyhow!(NO_ADAPTER))?,
            Adapter::Hardware => {
                let found: Vec<String> = adapters
                    .iter()
                    .map(|a| format!("{:?} ({:?})", a.get_info().name, a.get_info().device_type))
                    .collect();
                adapters.into_iter().find(|a| !is_cpu(a)).ok_or_else(|| {
                    anyhow!(
                        "no hardware Vulkan adapter found (adapters: {}); install the \
                             GPU vendor's Vulkan driver and the Vulkan loader (Debian package \
                             `libvulkan1`)",
                        if found.is_empty() {
                            "none".to_string()
                        } else {
                            found.join(", ")
                        }
                    )
                })?
            }
            Adapter::SwiftShader => adapters.into_iter().find(is_swiftshader).ok_or_else(|| {
                anyhow!(
                    "no SwiftShader Vulkan adapter found: install the Debian package \
                     `chromium`, which ships its driver ({SWIFTSHADER_ICD})"
                )
            })?,
        };
        let info = adapter.get_info();

        // Passthrough is only needed for `Shader::SpirV`; without it the other paths still work.
        let passthrough = adapter
            .features()
            .contains(wgpu::Features::PASSTHROUGH_SHADERS);
        let mut required_features = wgpu::Features::MAPPABLE_PRIMARY_BUFFERS;
        if passthrough {
            required_features |= wgpu::Features::PASSTHROUGH_SHADERS;
        }
        // Every Vulkan adapter has it (wgpu-hal's Vulkan backend offers it unconditionally);
        // the dispatches map their storage buffers directly ([`Buffers`]).
        if !adapter
            .features()
            .contains(wgpu::Features::MAPPABLE_PRIMARY_BUFFERS)
        {
            bail!(
                "the Vulkan adapter {:?} (driver {:?}) cannot map storage buffers \
                 (wgpu's MAPPABLE_PRIMARY_BUFFERS), which the verifier's dispatches need",
                info.name,
                info.driver
            );
        }

        // WebGPU default limits, except that buffer sizes are raised to what the adapter
        // offers: everything else staying at the defaults keeps the kernels honest for real
        // GPUs, while large bindings only change how many items fit in one chunk.
        let adapter_limits = adapter.limits();
        let required_limits = wgpu::Limits {
            max_storage_buffer_binding_size: adapter_limits.max_storage_buffer_binding_size,
            max_buffer_size: adapter_limits.max_buffer_size,
            ..wgpu::Limits::default()
        };

        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("unitpack verify"),
                required_features,
                required_limits,
                experimental_features: wgpu::ExperimentalFeatures::disabled(),
                memory_hints: wgpu::MemoryHints::Performance,
                trace: wgpu::Trace::Off,
            })
            .await
            .with_context(|| {
                format!(
                    "requesting a device from Vulkan adapter {:?} (driver {:?})",
                    info.name, info.driver
                )
            })?;

        // By default wgpu panics on errors that no error scope caught. Every operation in
        // `run` is wrapped in scopes, so anything reaching this handler is unexpected; print
        // it instead of aborting a whole test binary from a wgpu-internal thread.
        device.on_uncaptured_error(Arc::new(|e: wgpu::Error| {
            // Not eprintln!, which panics when stderr is closed.
            let msg = format!("unitpack::verify::gpu: uncaptured wgpu error: {e}\n");
            let _ = std::io::Write::write_all(&mut std::io::stderr(), msg.as_bytes());
        }));
        let lost = Arc::new(Mutex::new(None));
        {
            let lost = Arc::clone(&lost);
            device.set_device_lost_callback(move |reason, message| {
                if let Ok(mut l) = lost.lock() {
                    *l = Some(format!("{reason:?}: {message}"));
                }
            });
        }

        let storage = |binding, read_only| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let bind_group_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("unitpack verify: input/output"),
            entries: &[storage(0, true), storage(1, false)],
        });
        // Explicit layout for every shader kind: passthrough SPIR-V has no reflection, and
        // using the same layout everywhere means all paths are bound identically.
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("unitpack verify"),
            bind_group_layouts: &[Some(&bind_group_layout)],
            immediate_size: 0,
        });

        let max_binding_bytes = device
            .limits()
            .max_storage_buffer_binding_size
            .min(device.limits().max_buffer_size);

        Ok(Gpu {
            device,
            queue,
            adapter_name: info.name,
            driver: if info.driver_info.is_empty() {
                info.driver
            } else {
                format!("{} ({})", info.driver, info.driver_info)
            },
            passthrough,
            max_binding_bytes,
            bind_group_layout,
            pipeline_layout,
            lost,
            spare: Mutex::new(Vec::new()),
        })
    }

    /// Adapter name, e.g. `"llvmpipe (LLVM 15.0.6, 256 bits)"`, for reports.
    pub fn adapter_name(&self) -> &str {
        &self.adapter_name
    }

    /// Driver name and driver info, e.g. `"llvmpipe (Mesa 22.3.6 (LLVM 15.0.6))"`, for reports.
    pub fn driver(&self) -> &str {
        &self.driver
    }

    /// Items per dispatch for a kernel with the given item widths: [`MAX_CHUNK_ITEMS`], or
    /// fewer if a chunk's input or output buffer would exceed the storage-binding limit.
    pub fn chunk_items(&self, in_words: usize, out_words: usize) -> usize {
        let widest = in_words.max(out_words).max(1) as u64 * 4;
        let fit = (self.max_binding_bytes / widest) as usize;
        // Keep whole workgroups in all but the last chunk.
        let fit = (fit / WORKGROUP_SIZE as usize * WORKGROUP_SIZE as usize).max(1);
        fit.min(MAX_CHUNK_ITEMS)
    }

    fn check_lost(&self) -> anyhow::Result<()> {
        match self.lost.lock().ok().and_then(|l| l.clone()) {
            Some(reason) => bail!("the wgpu device was lost ({reason})"),
            None => Ok(()),
        }
    }

    /// Runs `shader` (entry point `main`, workgroup size 64) over `input`, which holds `n`
    /// items of `in_words` u32 each, and returns `n` items of `out_words` u32 each.
    ///
    /// Binding layout (group 0): binding 0 = read-only storage buffer of u32 (input), binding
    /// 1 = read-write storage buffer of u32 (output). Large inputs are split into chunks of
    /// [`Gpu::chunk_items`] items; each chunk dispatches `ceil(items / 64)` workgroups along x
    /// and binds buffers of exactly `items * words` u32, so the kernel's own bounds check
    /// `id.x < arrayLength(output) / out_words` is right for every chunk. The pipeline is
    /// created once per call and reused for all chunks.
    ///
    /// Compilation, validation and pipeline-creation errors are caught with error scopes
    /// and returned as errors carrying wgpu's/naga's message.
    pub fn run(
        &self,
        shader: &Shader,
        input: &[u32],
        in_words: usize,
        out_words: usize,
    ) -> anyhow::Result<Vec<u32>> {
        let mut out = Vec::with_capacity(input.len() / in_words.max(1) * out_words);
        self.run_each(shader, input, in_words, out_words, &mut |words| {
            out.extend_from_slice(words)
        })?;
        Ok(out)
    }

    /// [`Gpu::run`], handing each chunk's output words to `sink`, in order, while the
    /// output buffer is mapped, instead of collecting them: a check of 2^24 items then
    /// never holds their outputs all at once.
    pub fn run_each(
        &self,
        shader: &Shader,
        input: &[u32],
        in_words: usize,
        out_words: usize,
        sink: &mut dyn FnMut(&[u32]),
    ) -> anyhow::Result<()> {
        Self::check_widths(input, in_words, out_words)?;
        self.check_lost()?;
        let pipeline = self
            .module(shader)
            .and_then(|module| self.pipeline_of(&module, &[]))
            .with_context(|| format!("creating the {} compute pipeline", shader.kind()))?;
        self.dispatch(&pipeline, shader.kind(), input, in_words, out_words, sink)
    }

    /// Compiles a selecting kernel's module once (see the module docs); each
    /// [`Gpu::run_selected`] then builds the pipeline of one of its functions.
    pub fn selecting(&self, shader: &Shader) -> anyhow::Result<Selecting> {
        self.check_lost()?;
        let module = match *shader {
            Shader::SpirV(words) => {
                // Checked here, so that a module without the selector fails once.
                with_selector(words, 0)?;
                SelectingModule::SpirV(words.to_vec())
            }
            _ => SelectingModule::Naga(self.module(shader)?),
        };
        Ok(Selecting {
            module,
            kind: shader.kind(),
        })
    }

    /// [`Gpu::run_each`] for function `index` of a selecting kernel: its pipeline built
    /// with specialization constant 0 set to `index`.
    pub fn run_selected(
        &self,
        kernel: &Selecting,
        index: u32,
        input: &[u32],
        in_words: usize,
        out_words: usize,
        sink: &mut dyn FnMut(&[u32]),
    ) -> anyhow::Result<()> {
        Self::check_widths(input, in_words, out_words)?;
        self.check_lost()?;
        let pipeline = match &kernel.module {
            SelectingModule::Naga(module) => self.pipeline_of(module, &[("0", f64::from(index))]),
            SelectingModule::SpirV(words) => {
                let words = with_selector(words, index)?;
                self.module(&Shader::SpirV(&words))
                    .and_then(|module| self.pipeline_of(&module, &[]))
            }
        }
        .with_context(|| {
            format!(
                "creating the {} compute pipeline of function {index}",
                kernel.kind
            )
        })?;
        self.dispatch(&pipeline, kernel.kind, input, in_words, out_words, sink)
    }

    fn check_widths(input: &[u32], in_words: usize, out_words: usize) -> anyhow::Result<()> {
        if in_words == 0 || out_words == 0 {
            bail!("in_words ({in_words}) and out_words ({out_words}) must both be at least 1");
        }
        if !input.len().is_multiple_of(in_words) {
            bail!(
                "input holds {} u32, which is not a whole number of {in_words}-word items",
                input.len()
            );
        }
        Ok(())
    }

    /// Runs a pipeline over every chunk of `input` (the device checked by the caller).
    fn dispatch(
        &self,
        pipeline: &wgpu::ComputePipeline,
        kind: &str,
        input: &[u32],
        in_words: usize,
        out_words: usize,
        sink: &mut dyn FnMut(&[u32]),
    ) -> anyhow::Result<()> {
        let n = input.len() / in_words;
        let chunk = self.chunk_items(in_words, out_words);
        if n == 0 {
            return Ok(());
        }
        // Buffers sized for one full chunk, reused for every chunk; the last (short) chunk
        // binds only a prefix so arrayLength() still reports that chunk's size.
        let first = n.min(chunk);
        let bytes = |items: usize, words: usize| (items * words * 4) as u64;
        let buffers = self.buffers(bytes(first, in_words), bytes(first, out_words))?;
        for (index, items) in input.chunks(chunk * in_words).enumerate() {
            let items_here = items.len() / in_words;
            let start = index * chunk;
            self.run_chunk(
                pipeline,
                items,
                items_here,
                out_words,
                [&buffers.input, &buffers.output],
                sink,
            )
            .with_context(|| {
                format!(
                    "{kind} kernel, items {start}..{} of {n}",
                    start + items_here
                )
            })?;
        }
        // Only after a dispatch that went through: a failed one may leave a buffer mapped.
        self.spare.lock().expect("spare buffers").push(buffers);
        Ok(())
    }

    /// Spare [`Buffers`] holding at least `in_bytes` and `out_bytes`, or new ones. New
    /// ones are sized to the next power of two, so that later dispatches find them large
    /// enough; one that is too small is dropped in their place, which keeps as many as
    /// there are dispatches at once.
    fn buffers(&self, in_bytes: u64, out_bytes: u64) -> anyhow::Result<Buffers> {
        let mut spare = self.spare.lock().expect("spare buffers");
        if let Some(k) = spare
            .iter()
            .position(|b| b.input.size() >= in_bytes && b.output.size() >= out_bytes)
        {
            return Ok(spare.swap_remove(k));
        }
        let (small_in, small_out) = spare
            .pop()
            .map_or((0, 0), |b| (b.input.size(), b.output.size()));
        drop(spare);
        let (in_size, out_size) = (
            in_bytes.max(small_in).next_power_of_two(),
            out_bytes.max(small_out).next_power_of_two(),
        );
        let scopes = ErrorScopes::push(&self.device);
        let buffer = |label, size, usage| {
            self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        use wgpu::BufferUsages as U;
        let buffers = Buffers {
            input: buffer("unitpack verify: input", in_size, U::STORAGE | U::MAP_WRITE),
            output: buffer(
                "unitpack verify: output",
                out_size,
                U::STORAGE | U::MAP_READ | U::COPY_DST,
            ),
        };
        scopes.check().context("allocating buffers")?;
        Ok(buffers)
    }

    fn run_chunk(
        &self,
        pipeline: &wgpu::ComputePipeline,
        input: &[u32],
        items: usize,
        out_words: usize,
        [input_buf, output_buf]: [&wgpu::Buffer; 2],
        sink: &mut dyn FnMut(&[u32]),
    ) -> anyhow::Result<()> {
        let in_bytes = std::mem::size_of_val(input) as u64;
        let out_bytes = (items * out_words * 4) as u64;

        self.map(input_buf, in_bytes, wgpu::MapMode::Write, None)
            .context("mapping the input buffer")?;
        input_buf
            .get_mapped_range_mut(..in_bytes)
            .map_err(|e| anyhow!("writing the mapped input buffer: {e}"))?
            .copy_from_slice(bytemuck::cast_slice(input));
        input_buf.unmap();

        let scopes = ErrorScopes::push(&self.device);
        let bind_group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("unitpack verify"),
            layout: &self.bind_group_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: input_buf,
                        offset: 0,
                        size: wgpu::BufferSize::new(in_bytes),
                    }),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: output_buf,
                        offset: 0,
                        size: wgpu::BufferSize::new(out_bytes),
                    }),
                },
            ],
        });
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("unitpack verify"),
            });
        // Zeros, as in a new buffer: a kernel that leaves an output unwritten must not
        // pass on what an earlier dispatch left there.
        encoder.clear_buffer(output_buf, 0, Some(out_bytes));
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("unitpack verify"),
                timestamp_writes: None,
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            let groups = items.div_ceil(WORKGROUP_SIZE as usize) as u32;
            pass.dispatch_workgroups(groups, 1, 1);
        }
        let submission = self.queue.submit([encoder.finish()]);
        // Validation errors in the recorded work are known now; don't wait on a broken submit.
        scopes.check().context("recording the dispatch")?;
        self.map(output_buf, out_bytes, wgpu::MapMode::Read, Some(submission))
            .context("waiting for the dispatch to finish")?;
        {
            let view = output_buf
                .get_mapped_range(..out_bytes)
                .map_err(|e| anyhow!("reading the mapped output buffer: {e}"))?;
            sink(bytemuck::cast_slice(&view));
        }
        output_buf.unmap();
        Ok(())
    }

    /// Maps the first `bytes` of `buffer` for `mode` and waits until it is mapped: after
    /// `submission`, where given, has finished.
    fn map(
        &self,
        buffer: &wgpu::Buffer,
        bytes: u64,
        mode: wgpu::MapMode,
        submission: Option<wgpu::SubmissionIndex>,
    ) -> anyhow::Result<()> {
        let (tx, rx) = mpsc::channel();
        buffer.slice(..bytes).map_async(mode, move |r| {
            let _ = tx.send(r);
        });
        // A buffer no submission uses maps at the next poll, without waiting for the other
        // threads' dispatches; should it not, the wait below covers every submission.
        if submission.is_none() {
            self.device
                .poll(wgpu::PollType::Poll)
                .map_err(|e| anyhow!("{e}"))?;
            if let Ok(mapped) = rx.try_recv() {
                return mapped.map_err(|e| anyhow!("{e}"));
            }
        }
        let polled = self.device.poll(wgpu::PollType::Wait {
            submission_index: submission,
            timeout: Some(CHUNK_TIMEOUT),
        });
        self.check_lost()?;
        polled.map_err(|e| anyhow!("{e}"))?;
        // Polling fires the callbacks of finished work; a short timeout only guards
        // against a wgpu bug turning into a hang.
        rx.recv_timeout(Duration::from_secs(60))
            .map_err(|_| anyhow!("the buffer was never mapped"))?
            .map_err(|e| anyhow!("{e}"))
    }

    /// Runs a WGSL kernel over the texels of an RGBA8 unorm texture: `texels` (R in the
    /// lowest byte, rows of `width`) are uploaded as a `width`-wide texture, which the
    /// kernel sees at binding 0 (`texture_2d<f32>`) beside a nearest-filtering sampler at
    /// binding 1, and writes `out_words` u32 to the storage buffer at binding 2
    /// for each of `items` invocations along x, bounds-checked by the kernel as in
    /// [`Gpu::run`]. A non-empty `input` is bound at binding 3 as a read-only `array<u32>`
    /// (what the kernel looks up in the texture, for a lookup table).
    /// This is how a shader meets a normal map: through the texture unit's unorm8
    /// conversion, not a buffer of floats.
    pub fn run_texture(
        &self,
        wgsl: &str,
        texels: &[u32],
        width: u32,
        input: &[u32],
        items: usize,
        out_words: usize,
    ) -> anyhow::Result<Vec<u32>> {
        if width == 0 || !texels.len().is_multiple_of(width as usize) || out_words == 0 {
            bail!("{} texels do not fill rows of {width}", texels.len());
        }
        if items == 0 {
            bail!("no invocations to run");
        }
        self.check_lost()?;
        let height = (texels.len() / width as usize) as u32;
        let scopes = ErrorScopes::push(&self.device);
        let module = self
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("unitpack texture kernel"),
                source: wgpu::ShaderSource::Wgsl(Cow::Borrowed(wgsl)),
            });
        scopes.check().context("compiling the texture kernel")?;
        let scopes = ErrorScopes::push(&self.device);
        let pipeline = self
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("unitpack texture kernel"),
                layout: None,
                module: &module,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                cache: None,
            });
        let size = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        };
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("unitpack texels"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        self.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            bytemuck::cast_slice(texels),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * width),
                rows_per_image: Some(height),
            },
            size,
        );
        let sampler = self.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("unitpack nearest"),
            ..Default::default()
        });
        let out_bytes = (items * out_words * 4) as u64;
        // wgpu rejects empty buffers: a kernel without input binds none.
        let input_buf = (!input.is_empty()).then(|| {
            let b = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("unitpack texture input"),
                size: (input.len() * 4) as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            self.queue.write_buffer(&b, 0, bytemuck::cast_slice(input));
            b
        });
        let output = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("unitpack texture output"),
            size: out_bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let readback = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("unitpack texture readback"),
            size: out_bytes,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let bind_group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("unitpack texture kernel"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Sampler(&sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: output.as_entire_binding(),
                },
            ]
            .into_iter()
            .chain(input_buf.as_ref().map(|b| wgpu::BindGroupEntry {
                binding: 3,
                resource: b.as_entire_binding(),
            }))
            .collect::<Vec<_>>(),
        });
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("unitpack texture kernel"),
            });
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("unitpack texture kernel"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups(items.div_ceil(WORKGROUP_SIZE as usize) as u32, 1, 1);
        }
        encoder.copy_buffer_to_buffer(&output, 0, &readback, 0, out_bytes);
        let submission = self.queue.submit([encoder.finish()]);
        scopes.check().context("running the texture kernel")?;
        self.map(&readback, out_bytes, wgpu::MapMode::Read, Some(submission))
            .context("waiting for the texture kernel")?;
        let out = {
            let view = readback
                .get_mapped_range(..)
                .map_err(|e| anyhow!("reading the mapped readback buffer: {e}"))?;
            bytemuck::cast_slice(&view).to_vec()
        };
        readback.unmap();
        Ok(out)
    }

    /// Creates the shader module, turning a compilation or validation error into an `Err`
    /// with the message.
    fn module(&self, shader: &Shader) -> anyhow::Result<wgpu::ShaderModule> {
        let scopes = ErrorScopes::push(&self.device);
        let module = match *shader {
            Shader::Wgsl(src) => self
                .device
                .create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("unitpack verify (WGSL)"),
                    source: wgpu::ShaderSource::Wgsl(Cow::Borrowed(src)),
                }),
            Shader::GlslNaga(src) => {
                self.device
                    .create_shader_module(wgpu::ShaderModuleDescriptor {
                        label: Some("unitpack verify (GLSL)"),
                        source: wgpu::ShaderSource::Glsl {
                            shader: Cow::Borrowed(src),
                            stage: wgpu::naga::ShaderStage::Compute,
                            defines: &[],
                        },
                    })
            }
            Shader::SpirV(words) => {
                if !self.passthrough {
                    bail!(
                        "the adapter {:?} does not support Features::PASSTHROUGH_SHADERS, \
                         so raw SPIR-V cannot be run",
                        self.adapter_name
                    );
                }
                // The driver would get these words unchecked; reject obvious garbage here.
                if words.len() < 5 || words[0] != 0x0723_0203 {
                    bail!(
                        "not a SPIR-V module (length {} words, first word {:#010x?})",
                        words.len(),
                        words.first()
                    );
                }
                let entry = [wgpu::PassthroughShaderEntryPoint {
                    name: Cow::Borrowed("main"),
                    workgroup_size: (WORKGROUP_SIZE, 1, 1),
                }];
                // SAFETY: wgpu hands the words to vkCreateShaderModule without validating
                // them. Callers are expected to have run `spirv-val` (see
                // `verify::tools::spirv_val`) on glslang output; the binding layout is the
                // one documented for kernels, which the explicit pipeline layout matches.
                unsafe {
                    self.device.create_shader_module_passthrough(
                        wgpu::ShaderModuleDescriptorPassthrough {
                            label: Some("unitpack verify (SPIR-V)"),
                            entry_points: Cow::Borrowed(&entry),
                            spirv: Some(Cow::Borrowed(words)),
                            ..Default::default()
                        },
                    )
                }
            }
        };
        // Check the module on its own first: a broken module makes pipeline creation fail
        // too, and its message (naga's diagnostic) is the useful one.
        scopes.check().context("compiling the shader module")?;
        Ok(module)
    }

    /// Creates the compute pipeline of `module` with the pipeline constants `constants`.
    fn pipeline_of(
        &self,
        module: &wgpu::ShaderModule,
        constants: &[(&str, f64)],
    ) -> anyhow::Result<wgpu::ComputePipeline> {
        let scopes = ErrorScopes::push(&self.device);
        let pipeline = self
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("unitpack verify"),
                layout: Some(&self.pipeline_layout),
                module,
                entry_point: Some("main"),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants,
                    ..Default::default()
                },
                cache: None,
            });
        scopes.check().context("creating the compute pipeline")?;
        Ok(pipeline)
    }
}

/// Validation, out-of-memory and internal error scopes pushed together, popped in reverse.
struct ErrorScopes {
    // Innermost last.
    guards: Vec<(&'static str, wgpu::ErrorScopeGuard)>,
}

/// wgpu panics if scopes are popped out of order, and a `Vec` drops its elements front to
/// back, so an early return (`?`) between push and `check` must pop innermost first.
impl Drop for ErrorScopes {
    fn drop(&mut self) {
        while let Some(guard) = self.guards.pop() {
            drop(guard);
        }
    }
}

impl ErrorScopes {
    fn push(device: &wgpu::Device) -> Self {
        let guards = [
            ("internal", wgpu::ErrorFilter::Internal),
            ("out of memory", wgpu::ErrorFilter::OutOfMemory),
            ("validation", wgpu::ErrorFilter::Validation),
        ]
        .into_iter()
        .map(|(name, filter)| (name, device.push_error_scope(filter)))
        .collect();
        ErrorScopes { guards }
    }

    /// Pops all scopes; returns the errors they caught, if any, as one error.
    fn check(mut self) -> anyhow::Result<()> {
        let mut errors = Vec::new();
        while let Some((name, guard)) = self.guards.pop() {
            if let Some(e) = pollster::block_on(guard.pop()) {
                errors.push(format!("wgpu {name} error: {}", describe(&e)));
            }
        }
        if errors.is_empty() {
            Ok(())
        } else {
            Err(anyhow!(errors.join("\n")))
        }
    }
}

/// The error's description followed by its source chain (wgpu puts naga's rendered
/// diagnostic, with the offending source line, in the description or the sources).
fn describe(e: &wgpu::Error) -> String {
    let mut text = e.to_string();
    let mut source = std::error::Error::source(e);
    while let Some(s) = source {
        let s_text = s.to_string();
        if !text.contains(&s_text) {
            text.push_str("\n  caused by: ");
            text.push_str(&s_text);
        }
        source = s.source();
    }
    text
}
