//! Device and adapter selection, headless.

use super::texture_pool::TexturePool;
use crate::{Error, Result};

/// The environment variable that picks an adapter by (part of) its name,
/// like `--adapter`.
pub const ADAPTER_ENV: &str = "GONIO_ADAPTER";

/// How to install the software rasterizer, for error messages and docs.
pub const LAVAPIPE_HINT: &str = "gonio renders with Vulkan; on a machine without a GPU install Mesa's \
software rasterizer lavapipe with `sudo apt-get install mesa-vulkan-drivers libvulkan1` (or run \
./setup.sh), then check with `vulkaninfo --summary` that a device is listed";

/// The backends to look for adapters on: Vulkan, or what `WGPU_BACKEND`
/// names (e.g. `gl`, `vulkan,gl`). A value that names no backend is an
/// error naming it (it used to end in "no adapter found" with advice to
/// install lavapipe).
fn backends() -> Result<wgpu::Backends> {
    match std::env::var("WGPU_BACKEND") {
        Ok(text) if !text.trim().is_empty() => {
            let backends = wgpu::Backends::from_comma_list(&text);
            let built = wgpu::Instance::enabled_backend_features();
            let names = backend_names(built);
            if backends.is_empty() {
                Err(Error::argument(
                    format!("WGPU_BACKEND={text}"),
                    format!(
                        "names no GPU backend; this gonio has {names} (a comma-separated list picks several), or unset it for Vulkan"
                    ),
                ))
            } else if !backends.intersects(built) {
                // wgpu would fail with its internal list of backends
                // (e.g. `WGPU_BACKEND=metal` on Linux).
                Err(Error::argument(
                    format!("WGPU_BACKEND={text}"),
                    format!(
                        "names a backend this gonio is not built with on this system; it has {names} (unset WGPU_BACKEND for Vulkan)"
                    ),
                ))
            } else {
                Ok(backends)
            }
        }
        _ => Ok(wgpu::Backends::VULKAN),
    }
}

/// The message for `--adapter NAME` that matches none of the adapters
/// `names`: the nearest adapter's first word when one is near, how to
/// pick one of those there are, and the advice to install lavapipe only
/// when there is none (it once listed llvmpipe as available and said to
/// install lavapipe).
fn no_adapter_named(name: &str, names: &[String]) -> String {
    if names.is_empty() {
        return format!(
            "no GPU adapter matches `{name}` (from --adapter or {ADAPTER_ENV}): none is available. {LAVAPIPE_HINT}."
        );
    }
    let words: Vec<&str> = names
        .iter()
        .filter_map(|n| n.split_whitespace().next())
        .collect();
    let hint = crate::base::did_you_mean(name, words.iter().copied());
    format!(
        "no GPU adapter matches `{name}` (from --adapter or {ADAPTER_ENV}){hint}; available: {}. The name matches any part of an adapter's name, case-insensitive (e.g. --adapter {}), and without --adapter gonio picks one itself",
        names.join(", "),
        words[0].to_lowercase()
    )
}

/// The `WGPU_BACKEND` names of `backends`, e.g. "vulkan, gl".
fn backend_names(backends: wgpu::Backends) -> String {
    let known = [
        (wgpu::Backends::VULKAN, "vulkan"),
        (wgpu::Backends::GL, "gl"),
        (wgpu::Backends::METAL, "metal"),
        (wgpu::Backends::DX12, "dx12"),
    ];
    known
        .iter()
        .filter(|(b, _)| backends.contains(*b))
        .map(|(_, n)| *n)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Which adapter to use.
#[derive(Clone, Debug, Default)]
pub enum AdapterChoice {
    /// The environment's `GONIO_ADAPTER` if set, else wgpu's default pick
    /// (high performance preference).
    #[default]
    Auto,
    /// The first adapter whose name contains this text (case-insensitive).
    Named(String),
}

impl AdapterChoice {
    /// `--adapter NAME` if given, else `GONIO_ADAPTER`, else automatic.
    pub fn from_flag_or_env(flag: Option<&str>) -> Self {
        match flag
            .map(str::to_string)
            .or_else(|| std::env::var(ADAPTER_ENV).ok().filter(|s| !s.is_empty()))
        {
            Some(name) => AdapterChoice::Named(name),
            None => AdapterChoice::Auto,
        }
    }
}

/// A device ready to render, and what it can do.
pub struct GpuContext {
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter_info: wgpu::AdapterInfo,
    /// Timestamp queries were requested and granted.
    pub timestamps: bool,
    /// The textures one offscreen render leaves for the next
    /// (src/gpu/texture_pool.rs).
    pub textures: TexturePool,
}

impl GpuContext {
    /// Opens a device on the chosen adapter. Backends: Vulkan unless
    /// `WGPU_BACKEND` says otherwise.
    pub fn new(choice: &AdapterChoice) -> Result<Self> {
        pollster::block_on(Self::new_async(choice))
    }

    async fn new_async(choice: &AdapterChoice) -> Result<Self> {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = backends()?;
        let instance = wgpu::Instance::new(desc);
        let ctx = Self::open(&instance, choice, None).await?;
        ctx.check_radiance_format()?;
        Ok(ctx)
    }

    /// The offscreen radiance format of this adapter: `Rgba32Float`
    /// ([`super::formats::COLOR_FORMAT`]) where it can render into it,
    /// else `Rgba32Uint` holding the same f32 bits (wgpu's GL backend on
    /// Mesa's llvmpipe, `WGPU_BACKEND=gl`, lacks `EXT_color_buffer_float`
    /// and panicked in pipeline creation). Both read back the
    /// same bytes; the integer target cannot be multisampled and resolved,
    /// which `image.msaa` then says. `None` if neither is renderable.
    pub fn radiance_format(&self) -> Option<wgpu::TextureFormat> {
        [
            super::formats::COLOR_FORMAT,
            super::formats::COLOR_BITS_FORMAT,
        ]
        .into_iter()
        .find(|&format| {
            self.adapter
                .get_texture_format_features(format)
                .allowed_usages
                .contains(wgpu::TextureUsages::RENDER_ATTACHMENT)
        })
    }

    /// Whether scene pipelines can blend into `format` (alpha BLEND):
    /// 32-bit float targets need the device's `FLOAT32_BLENDABLE`, every
    /// format the adapter's blendable flag.
    pub fn blendable(&self, format: wgpu::TextureFormat) -> bool {
        let float32 = matches!(
            format,
            wgpu::TextureFormat::Rgba32Float
                | wgpu::TextureFormat::Rg32Float
                | wgpu::TextureFormat::R32Float
        );
        (!float32
            || self
                .device
                .features()
                .contains(wgpu::Features::FLOAT32_BLENDABLE))
            && self
                .adapter
                .get_texture_format_features(format)
                .flags
                .contains(wgpu::TextureFormatFeatureFlags::BLENDABLE)
    }

    /// Refuses an adapter without `Rgba32Float` targets for `gonio bench`,
    /// whose hand-written floor shaders (the unlit pass, the minimal
    /// shader) write f32 radiance and have no bits fallback.
    pub fn require_float_radiance(&self, who: &str) -> Result<()> {
        if self.radiance_format() == Some(super::formats::COLOR_FORMAT) {
            return Ok(());
        }
        Err(Error::NoAdapter(format!(
            "{who} needs Rgba32Float render targets, which the GPU adapter `{}` ({:?} backend) lacks; use another backend (unset WGPU_BACKEND for Vulkan; `gonio render` works on this one)",
            self.adapter_info.name, self.adapter_info.backend
        )))
    }

    /// Refuses an adapter with no [`Self::radiance_format`] before
    /// anything is drawn.
    fn check_radiance_format(&self) -> Result<()> {
        if self.radiance_format().is_some() {
            return Ok(());
        }
        Err(Error::NoAdapter(format!(
            "the GPU adapter `{}` ({:?} backend) can render into neither Rgba32Float nor Rgba32Uint targets, one of which holds gonio's linear radiance; use another backend (unset WGPU_BACKEND for Vulkan; `gonio view` may still work on this one)",
            self.adapter_info.name, self.adapter_info.backend
        )))
    }

    /// Opens a device that can present to `window`, and the window's
    /// surface (the viewer). Same adapter choice as [`GpuContext::new`].
    pub fn with_window<W>(
        choice: &AdapterChoice,
        window: W,
    ) -> Result<(Self, wgpu::Surface<'static>)>
    where
        W: wgpu::WindowHandle + wgpu::rwh::HasDisplayHandle + std::fmt::Debug + Clone + 'static,
    {
        let mut desc = wgpu::InstanceDescriptor::new_with_display_handle(Box::new(window.clone()));
        desc.backends = backends()?;
        let instance = wgpu::Instance::new(desc);
        let surface = instance.create_surface(window).map_err(|e| {
            Error::NoAdapter(format!(
                "cannot draw into the window ({e}). {LAVAPIPE_HINT}."
            ))
        })?;
        let context = pollster::block_on(Self::open(&instance, choice, Some(&surface)))?;
        Ok((context, surface))
    }

    async fn open(
        instance: &wgpu::Instance,
        choice: &AdapterChoice,
        surface: Option<&wgpu::Surface<'_>>,
    ) -> Result<Self> {
        let adapters = instance.enumerate_adapters(wgpu::Backends::all()).await;
        let adapter = match choice {
            AdapterChoice::Named(name) => {
                let wanted = name.to_lowercase();
                let names: Vec<String> = adapters.iter().map(|a| a.get_info().name).collect();
                adapters
                    .into_iter()
                    .find(|a| a.get_info().name.to_lowercase().contains(&wanted))
                    .ok_or_else(|| Error::NoAdapter(no_adapter_named(name, &names)))?
            }
            AdapterChoice::Auto => instance
                .request_adapter(&wgpu::RequestAdapterOptions {
                    power_preference: wgpu::PowerPreference::HighPerformance,
                    force_fallback_adapter: false,
                    compatible_surface: surface,
                    apply_limit_buckets: false,
                })
                .await
                .map_err(|e| {
                    // A backend chosen by WGPU_BACKEND is named: the
                    // lavapipe advice alone misled when it was `gl` and
                    // no GL library was installed.
                    let chosen = std::env::var("WGPU_BACKEND")
                        .map(|b| format!(" for WGPU_BACKEND={b} (unset it to use Vulkan)"))
                        .unwrap_or_default();
                    Error::NoAdapter(format!(
                        "no GPU adapter found{chosen} ({e}). {LAVAPIPE_HINT}."
                    ))
                })?,
        };
        let adapter_info = adapter.get_info();
        let timestamps = adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        let mut required_features = wgpu::Features::empty();
        if timestamps {
            required_features |= wgpu::Features::TIMESTAMP_QUERY;
        }
        // Multisampled Rgba32Float targets (image.msaa) need the adapter's
        // own format capabilities, beyond WebGPU's portable set.
        if adapter
            .features()
            .contains(wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES)
        {
            required_features |= wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES;
        }
        // Alpha BLEND into the Rgba32Float radiance target.
        if adapter
            .features()
            .contains(wgpu::Features::FLOAT32_BLENDABLE)
        {
            required_features |= wgpu::Features::FLOAT32_BLENDABLE;
        }
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("gonio"),
                required_features,
                required_limits: adapter.limits(),
                ..Default::default()
            })
            .await
            .map_err(|e| {
                Error::NoAdapter(format!(
                    "the GPU adapter `{}` refused to open a device ({e}). {LAVAPIPE_HINT}.",
                    adapter_info.name
                ))
            })?;
        Ok(GpuContext {
            adapter,
            device,
            queue,
            adapter_info,
            timestamps,
            textures: TexturePool::default(),
        })
    }

    /// "name (backend, device type, driver)" for `--verbose`.
    pub fn describe(&self) -> String {
        let i = &self.adapter_info;
        format!(
            "{} ({:?}, {:?}, driver {} {})",
            i.name, i.backend, i.device_type, i.driver, i.driver_info
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_unknown_adapter_name_lists_the_adapters_there_are() {
        let names = ["llvmpipe (LLVM 15.0.6, 256 bits)".to_string()];
        let m = no_adapter_named("llvmpip", &names);
        assert!(m.contains("did you mean `llvmpipe`?"), "{m}");
        let m = no_adapter_named("nosuch", &names);
        assert!(
            m.contains("available: llvmpipe") && !m.contains("apt-get"),
            "{m}"
        );
        assert!(no_adapter_named("x", &[]).contains("apt-get"));
    }
}
