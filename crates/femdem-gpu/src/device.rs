//! The device: a Vulkan adapter with 64-bit floats in compute shaders,
//! opened with the limits the model needs.
//!
//! femdem computes in double precision throughout: joint openings before
//! the peak are ~10⁻⁸ m on coordinates of ~10⁻² m, which single precision
//! (ε ≈ 6·10⁻⁸) cannot resolve. So an adapter without
//! [`wgpu::Features::SHADER_F64`] is refused, with its name, rather than run
//! in single precision.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

use thiserror::Error;

use crate::staging::Pool;
use crate::transfers::{Log, Phase};

/// Why no device could be opened.
#[derive(Debug, Error)]
pub enum GpuError {
    /// No Vulkan adapter at all (no driver, or no Vulkan loader).
    #[error(
        "no Vulkan adapter found: install a Vulkan driver and its loader (on Debian: `libvulkan1` with the GPU's \
         driver, or `mesa-vulkan-drivers` for lavapipe, a software device on the CPU)"
    )]
    NoAdapter,
    /// Adapters exist, but none computes in 64-bit floats.
    #[error("no Vulkan adapter with 64-bit floats in compute shaders (found: {0})")]
    NoF64(String),
    /// The adapter refused the device (limits or features).
    #[error("the adapter {adapter} refused a device: {reason}")]
    Device {
        /// The adapter's name.
        adapter: String,
        /// What it said.
        reason: String,
    },
    /// A buffer the model needs is larger than the device allows for one
    /// storage binding.
    #[error("{what} needs {bytes} bytes in one binding; the adapter {adapter} allows {limit}")]
    TooLarge {
        /// Which array.
        what: &'static str,
        /// Its size, bytes.
        bytes: u64,
        /// The adapter's name.
        adapter: String,
        /// The adapter's limit for one storage binding, bytes.
        limit: u64,
    },
    /// A kernel failed to compile or validate (a bug in femdem, or a driver
    /// that rejects valid code).
    #[error("kernel `{kernel}` was refused by {adapter}: {reason}")]
    Kernel {
        /// The kernel's name.
        kernel: &'static str,
        /// The adapter's name.
        adapter: String,
        /// The validation error.
        reason: String,
    },
}

/// An opened device and its queue.
#[derive(Clone, Debug)]
pub struct Gpu {
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    info: Arc<wgpu::AdapterInfo>,
    limits: wgpu::Limits,
    /// Read-back buffers kept for the next read-back (allocating host
    /// memory every step costs more than the copy).
    staging: Arc<Mutex<Pool<wgpu::Buffer>>>,
    /// Whether a read-back waits by polling the device in a loop rather
    /// than blocking ([`Gpu::set_spin_wait`]).
    spin: Arc<AtomicBool>,
    /// The host's time around each read-back, for benchmarks.
    pub(crate) transfers: Arc<Log>,
}

impl Gpu {
    /// Opens the first Vulkan adapter with 64-bit floats, a discrete or
    /// integrated GPU before a software one, with the adapter's own limits
    /// (the defaults are a portable minimum: 8 storage buffers and 128 MiB
    /// per binding).
    pub fn new() -> Result<Gpu, GpuError> {
        let instance = wgpu::Instance::new(&wgpu::InstanceDescriptor {
            backends: wgpu::Backends::VULKAN,
            ..wgpu::InstanceDescriptor::default()
        });
        let adapters = instance.enumerate_adapters(wgpu::Backends::VULKAN);
        if adapters.is_empty() {
            return Err(GpuError::NoAdapter);
        }
        let rank = |a: &wgpu::Adapter| match a.get_info().device_type {
            wgpu::DeviceType::DiscreteGpu => 0,
            wgpu::DeviceType::IntegratedGpu => 1,
            wgpu::DeviceType::VirtualGpu => 2,
            wgpu::DeviceType::Other => 3,
            wgpu::DeviceType::Cpu => 4,
        };
        let names = adapters.iter().map(|a| a.get_info().name).collect::<Vec<_>>().join(", ");
        let mut usable: Vec<wgpu::Adapter> =
            adapters.into_iter().filter(|a| a.features().contains(wgpu::Features::SHADER_F64)).collect();
        usable.sort_by_key(rank);
        let Some(adapter) = usable.into_iter().next() else {
            return Err(GpuError::NoF64(names));
        };
        let info = adapter.get_info();
        let limits = adapter.limits();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("femdem"),
            required_features: wgpu::Features::SHADER_F64,
            required_limits: limits.clone(),
            ..wgpu::DeviceDescriptor::default()
        }))
        .map_err(|e| GpuError::Device { adapter: info.name.clone(), reason: e.to_string() })?;
        // A GPU answers a poll in microseconds, and the host has nothing
        // else to do while it waits; lavapipe computes on the host's own
        // cores, which a polling loop would take from it.
        let spin = Arc::new(AtomicBool::new(info.device_type != wgpu::DeviceType::Cpu));
        Ok(Gpu {
            device,
            queue,
            info: Arc::new(info),
            limits,
            staging: Arc::default(),
            spin,
            transfers: Arc::default(),
        })
    }

    /// The device for a test: `Some` where one opens; `None`, with a line
    /// on stderr, where none does and the environment variable
    /// `FEMDEM_GPU_REQUIRED` is not set; a panic where it is set (CI
    /// requires a device).
    pub fn for_tests() -> Option<Gpu> {
        match Gpu::new() {
            Ok(g) => Some(g),
            Err(e) if std::env::var_os("FEMDEM_GPU_REQUIRED").is_none() => {
                eprintln!("no device, GPU test not run: {e}");
                None
            }
            Err(e) => panic!("FEMDEM_GPU_REQUIRED is set and no device opened: {e}"),
        }
    }

    /// The adapter's name and driver, e.g. `llvmpipe (LLVM 15.0.6, 256
    /// bits), Mesa 22.3.6` or `NVIDIA H100 80GB HBM3, 550.54`.
    pub fn adapter(&self) -> String {
        format!("{}, {}", self.info.name, self.info.driver_info)
    }

    /// Whether the adapter is a software device on the CPU (lavapipe):
    /// correct, not fast.
    pub fn is_software(&self) -> bool {
        self.info.device_type == wgpu::DeviceType::Cpu
    }

    /// Makes read-backs wait for the device by polling it in a loop (one
    /// CPU core busy while the device works) instead of blocking until it
    /// signals; `Bulk::timings` measures both. On by default for a GPU
    /// (on an H200, 1.1–1.3× the resident step's rate: a blocking wait
    /// costs about 50 µs, a polled one 20–30 µs), off for a software
    /// device (lavapipe computes on the cores a loop would take).
    pub fn set_spin_wait(&self, spin: bool) {
        self.spin.store(spin, Ordering::Relaxed);
    }

    /// Whether read-backs poll the device in a loop ([`Gpu::set_spin_wait`]).
    pub fn spin_wait(&self) -> bool {
        self.spin.load(Ordering::Relaxed)
    }

    /// A read-back buffer of at least `bytes` bytes: a kept one, or a new
    /// one (sized to a power of two, so that a few serve every size).
    pub(crate) fn take_staging(&self, bytes: u64) -> wgpu::Buffer {
        if let Some(kept) = self.staging.lock().expect("the read-back pool").take(bytes) {
            return kept;
        }
        self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("read-back"),
            size: bytes.next_power_of_two().max(256),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    /// Keeps an unmapped read-back buffer for [`Gpu::take_staging`]
    /// (which ones: `staging.rs`).
    pub(crate) fn keep_staging(&self, buffer: wgpu::Buffer) {
        self.staging.lock().expect("the read-back pool").keep(buffer);
    }

    /// Waits until the submitted work is done and `done` is set (by a
    /// mapping's callback): blocking, or polling in a loop
    /// ([`Gpu::set_spin_wait`]).
    pub(crate) fn wait(&self, done: &AtomicBool) {
        if self.spin_wait() {
            while !done.load(Ordering::Acquire) {
                self.device.poll(wgpu::PollType::Poll).expect("polling the device");
                std::hint::spin_loop();
            }
        } else {
            self.device.poll(wgpu::PollType::wait_indefinitely()).expect("waiting for the device");
        }
        assert!(done.load(Ordering::Acquire), "the read-back is mapped once the device is done");
    }

    /// The host's time around each kind of read-back since the last call
    /// (submitting, waiting for the device, reading the mapped bytes; the
    /// contact pairs' upload too), emptying the log: where a device step's
    /// transfers go, for benchmarks.
    pub fn take_transfers(&self) -> Vec<Phase> {
        self.transfers.take()
    }

    /// The largest storage binding, bytes.
    pub fn max_binding(&self) -> u64 {
        u64::from(self.limits.max_storage_buffer_binding_size).min(self.limits.max_buffer_size)
    }

    /// The largest number of workgroups along one dimension of a dispatch.
    pub(crate) fn max_groups(&self) -> u32 {
        self.limits.max_compute_workgroups_per_dimension
    }

    /// `Err(TooLarge)` if `bytes` do not fit one storage binding.
    pub(crate) fn check_size(&self, what: &'static str, bytes: u64) -> Result<(), GpuError> {
        let limit = self.max_binding();
        if bytes > limit {
            return Err(GpuError::TooLarge { what, bytes, adapter: self.info.name.clone(), limit });
        }
        Ok(())
    }

    /// Compiles a WGSL module, turning a validation error into
    /// [`GpuError::Kernel`].
    pub(crate) fn module(&self, kernel: &'static str, source: &str) -> Result<wgpu::ShaderModule, GpuError> {
        self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = self.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(kernel),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        match pollster::block_on(self.device.pop_error_scope()) {
            Some(e) => Err(GpuError::Kernel { kernel, adapter: self.info.name.clone(), reason: e.to_string() }),
            None => Ok(module),
        }
    }

    /// A compute pipeline for entry point `main` of `module`.
    pub(crate) fn pipeline(
        &self,
        kernel: &'static str,
        module: &wgpu::ShaderModule,
    ) -> Result<wgpu::ComputePipeline, GpuError> {
        self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let pipeline = self.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(kernel),
            layout: None,
            module,
            entry_point: Some("main"),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            cache: None,
        });
        match pollster::block_on(self.device.pop_error_scope()) {
            Some(e) => Err(GpuError::Kernel { kernel, adapter: self.info.name.clone(), reason: e.to_string() }),
            None => Ok(pipeline),
        }
    }
}
