//! Helpers shared by the integration tests.
#![allow(dead_code)]

use gonio::gpu::{AdapterChoice, GpuContext, GpuRenderer};
use std::path::PathBuf;

/// A GPU renderer on the default adapter (lavapipe in CI). Tests never skip:
/// without an adapter they fail, and the message says how to install one.
pub fn gpu_renderer() -> GpuRenderer {
    match GpuContext::new(&AdapterChoice::from_flag_or_env(None)) {
        Ok(ctx) => GpuRenderer::new(ctx),
        Err(e) => panic!("GPU tests need a Vulkan adapter and none could be opened: {e}"),
    }
}

/// The glTF sample models shipped in `assets/gltf`.
pub fn gltf_asset(relative: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/gltf")
        .join(relative)
}

/// Appended to failures of tests that run the binary on the GPU: the
/// binary's own error names the missing adapter; this says what to do.
pub const LAVAPIPE_TEST_HINT: &str = "\n(if no GPU adapter was found: install lavapipe with `sudo apt-get install mesa-vulkan-drivers libvulkan1`, or run ./setup.sh)";

/// The gonio binary built for this test run.
pub fn gonio() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_gonio"))
}

// ---------------------------------------------------------------------
// The derived GPU-vs-reference tolerance (the same derivation as
// tests/gpu_vs_cpu.rs; see its module docs and gonio::output::compare).

use gonio::frame::Frame;
use gonio::material::Material;
use gonio::output::compare::{Comparison, JITTER_OFFSETS, Tolerance, compare_with_jitter};
use gonio::scene::Scene;

/// Sample-point jitter of the geometric tolerance (lavapipe snaps to
/// 1/256 px; see tests/gpu_vs_cpu.rs).
pub const JITTER_PX: f64 = 1.0 / 128.0;
/// f32 unit roundoff, 2⁻²⁴.
pub const EPS: f64 = 1.0 / 16_777_216.0;

/// The arithmetic tolerance for `scene`: the largest over its materials.
pub fn tolerance(scene: &Scene, reference: &Frame) -> Tolerance {
    let rel = scene
        .effective_materials()
        .iter()
        .map(|m| arithmetic_rel(&narrowest_lobes(scene, m)))
        .fold(64.0 * EPS, f64::max);
    Tolerance {
        rel,
        abs: 64.0 * EPS * reference.max_radiance() as f64,
    }
}

/// `m` with each lobe width a texture multiplies at its smallest: the
/// factor times the texture's smallest texel in its channel (filtering
/// and mip levels only average texels, so none is smaller), then the
/// pixel footprint's floor, as the renderers apply it after texturing.
/// The f32 error of the microfacet and Ward lobes grows as they narrow,
/// so this is the width whose error bounds every pixel's.
pub fn narrowest_lobes(scene: &Scene, m: &Material) -> Material {
    use gonio::material::texture::TextureTarget;
    let mut narrow = m.clone();
    for t in &m.textures {
        let TextureTarget::Param(key) = t.target else {
            continue;
        };
        let level = &scene.images[t.image].levels[0];
        let smallest = (0..level.height)
            .flat_map(|y| (0..level.width).map(move |x| level.texel(x, y)[t.channel]))
            .fold(f64::INFINITY, f64::min);
        match key {
            "roughness" => narrow.roughness *= smallest,
            "sigma_x" => narrow.sigma_x *= smallest,
            "sigma_y" => narrow.sigma_y *= smallest,
            _ => {}
        }
    }
    narrow.with_textured_widths_floored(scene.roughness_floor())
}

/// Relative f32 error of one material's shading beyond the light loop's
/// 64ε (derivation: tests/gpu_vs_cpu.rs): its model's row says it.
pub fn arithmetic_rel(m: &Material) -> f64 {
    let compensation = if m.energy_compensation {
        gonio::material::brdf::energy::F32_ERROR
    } else {
        0.0
    };
    (m.model.row().f32_error)(m) + compensation
}

/// The reference frame at the pixel centres and the four jittered ones.
pub fn reference_with_jitter(scene: &Scene) -> (Frame, [Frame; 4]) {
    let center = gonio::reference::render(scene);
    let jittered = JITTER_OFFSETS
        .map(|(dx, dy)| gonio::reference::render_offset(scene, dx * JITTER_PX, dy * JITTER_PX));
    (center, jittered)
}

/// Compares a GPU frame with the reference under the derived tolerance;
/// a scene with textures also gets the spread of the reference with the
/// textures' level of detail moved within ±½, the most Vulkan lets an
/// implementation's λ differ (derivation: tests/textures.rs;
/// [`lod_envelope`]).
pub fn compare_to_reference(
    scene: &Scene,
    gpu: &Frame,
    center: &Frame,
    jittered: &[Frame; 4],
) -> Comparison {
    if !scene.has_textures() {
        return compare_with_jitter(gpu, center, jittered, tolerance(scene, center));
    }
    let (low, high) = lod_envelope(scene, center);
    gonio::output::compare::compare_with_spreads(
        gpu,
        center,
        &[
            (&jittered[0], &jittered[1]),
            (&jittered[2], &jittered[3]),
            (&low, &high),
        ],
        tolerance(scene, center),
    )
}

/// The smallest and largest value of each pixel's channels over the
/// reference rendered with λ moved across [−½, ½] in steps of ⅛ (with
/// `center`, λ itself). The whole interval and not only its ends: where a
/// lobe is narrower than a normal map's variation between mip levels
/// (a glint on NormalTangentTest's smooth metal under the pixel
/// footprint's roughness floor), the radiance is not monotonic in λ; at
/// one pixel it measured 0.002, 0.77, 196, 3.2, 0.17 and 0.03 at
/// λ − ½, − ⅕, − ⅛, − 1/16, ±0 and + 1/16. A sampled interval, so a peak
/// narrower than ⅛ in λ could still fall between samples.
pub fn lod_envelope(scene: &Scene, center: &Frame) -> (Frame, Frame) {
    let (mut low, mut high) = (center.clone(), center.clone());
    for step in [-4, -3, -2, -1, 1, 2, 3, 4] {
        let f = gonio::reference::render_with_lod_bias(scene, f64::from(step) / 8.0);
        for k in 0..f.len() {
            // A texture's alpha (MASK) may move coverage: marked in
            // `high`, so the pixel counts as a silhouette.
            if f.coverage[k] != center.coverage[k] {
                high.coverage[k] = f.coverage[k];
            }
            for c in 0..3 {
                low.radiance[k][c] = low.radiance[k][c].min(f.radiance[k][c]);
                high.radiance[k][c] = high.radiance[k][c].max(f.radiance[k][c]);
            }
        }
    }
    (low, high)
}

/// Where a failing image test leaves its pictures:
/// `target/tmp/image-failures/LABEL/`.
pub fn failure_dir(label: &str) -> PathBuf {
    let safe: String = label
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("image-failures")
        .join(safe)
}

/// Asserts that `c` (a comparison of `actual` with `expected`) passed. On
/// failure it first writes the actual frame, the expected one and their
/// difference ([`gonio::output::failure::write_failure_images`]) and names
/// the folder in the panic message.
pub fn assert_agrees(label: &str, what: &str, c: &Comparison, actual: &Frame, expected: &Frame) {
    if c.passed() {
        return;
    }
    let dir = failure_dir(label);
    let saved = match gonio::output::failure::write_failure_images(&dir, actual, expected) {
        Ok(_) => format!(
            "actual, expected and difference images in {}",
            dir.display()
        ),
        Err(e) => format!("(could not save the images: {e})"),
    };
    panic!("{label}: {what}: {}\n{saved}", c.summary());
}

/// Pixels whose radiance differs in any bit between `a` and `b` (their
/// coverage must be equal).
pub fn differing_pixels(a: &gonio::frame::Frame, b: &gonio::frame::Frame) -> usize {
    assert_eq!(a.coverage, b.coverage, "coverage");
    a.radiance
        .iter()
        .zip(&b.radiance)
        .filter(|(x, y)| x.map(f32::to_bits) != y.map(f32::to_bits))
        .count()
}

/// A `lights=[...]` value: shadowed point lights of intensity 20 at
/// `positions`.
pub fn shadowed_point_lights(positions: &[[f64; 3]]) -> String {
    let lights: Vec<String> = positions
        .iter()
        .map(|[x, y, z]| {
            format!(
                "{{kind=\"point\", position=[{x}, {y}, {z}], intensity=[20.0, 20.0, 20.0], shadows=true}}"
            )
        })
        .collect();
    format!("lights=[{}]", lights.join(", "))
}

/// Runs `main` of the WGSL compute shader `src` (workgroups of 64) over
/// `invocations`, with `groups` bound as (group, [(binding, buffer)]) on
/// the pipeline's own layout, and returns the bytes of `output` (a
/// STORAGE | COPY_SRC buffer one of the groups writes). The harness of
/// the tests that run the renderer's WGSL beside its f64 or matrix twin.
pub fn run_compute(
    ctx: &GpuContext,
    label: &str,
    src: &str,
    groups: &[(u32, Vec<(u32, &wgpu::Buffer)>)],
    invocations: usize,
    output: &wgpu::Buffer,
) -> Vec<u8> {
    let device = &ctx.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(src.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let bind_groups: Vec<(u32, wgpu::BindGroup)> = groups
        .iter()
        .map(|(index, entries)| {
            let entries: Vec<wgpu::BindGroupEntry> = entries
                .iter()
                .map(|&(binding, buffer)| wgpu::BindGroupEntry {
                    binding,
                    resource: buffer.as_entire_binding(),
                })
                .collect();
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: None,
                layout: &pipeline.get_bind_group_layout(*index),
                entries: &entries,
            });
            (*index, group)
        })
        .collect();
    let size = output.size();
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        for (index, group) in &bind_groups {
            pass.set_bind_group(*index, group, &[]);
        }
        pass.dispatch_workgroups((invocations as u32).div_ceil(64), 1, 1);
    }
    encoder.copy_buffer_to_buffer(output, 0, &readback, 0, size);
    ctx.queue.submit([encoder.finish()]);
    gonio::gpu::readback::map_read(device, &readback).expect("compute readback")
}

/// A STORAGE | COPY_SRC buffer of `size` bytes for [`run_compute`]'s
/// output.
pub fn compute_output(ctx: &GpuContext, size: u64) -> wgpu::Buffer {
    ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    })
}

/// A command run in a window under `xvfb-run`, reporting the program's own
/// exit status. `xvfb-run` exits 5 when removing its X authority directory
/// fails after the program has ended (seen on the CI runner when the
/// program exits within milliseconds of starting), which would hide a
/// refusal's exit 2 behind xvfb-run's own error; a shell between the two
/// writes the program's status to a file that [`Xvfb::output`] reads back.
pub struct Xvfb {
    command: std::process::Command,
    status: tempfile::NamedTempFile,
}

/// Fails, saying how to install it, where `xvfb-run` is missing: the
/// viewer tests open a real window under Xvfb (they never skip).
pub fn require_xvfb_run() {
    let found = std::process::Command::new("sh")
        .args(["-c", "command -v xvfb-run"])
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    assert!(
        found,
        "xvfb-run is missing: the viewer tests open a real window under Xvfb. Install it with `sudo apt-get install xvfb xauth` (or run ./setup.sh)"
    );
}

/// `xvfb-run` with a screen large enough for the viewer tests' windows.
pub fn xvfb() -> Xvfb {
    require_xvfb_run();
    let status = tempfile::NamedTempFile::new().expect("a temporary file for the exit status");
    let mut command = std::process::Command::new("xvfb-run");
    command
        .args(["-a", "-s", "-screen 0 1280x720x24", "sh", "-c"])
        .arg(r#"status="$0"; "$@"; echo $? > "$status""#)
        .arg(status.path());
    Xvfb { command, status }
}

impl Xvfb {
    pub fn arg(&mut self, arg: impl AsRef<std::ffi::OsStr>) -> &mut Self {
        self.command.arg(arg);
        self
    }

    pub fn args<I, S>(&mut self, args: I) -> &mut Self
    where
        I: IntoIterator<Item = S>,
        S: AsRef<std::ffi::OsStr>,
    {
        self.command.args(args);
        self
    }

    pub fn env(
        &mut self,
        key: impl AsRef<std::ffi::OsStr>,
        value: impl AsRef<std::ffi::OsStr>,
    ) -> &mut Self {
        self.command.env(key, value);
        self
    }

    /// Runs the program to its end; `status` is the program's own (a
    /// signal's death reads as status 128 + the signal, as the shell
    /// reports it). Without a status written, xvfb-run's own is kept: the
    /// program never ran, and xvfb-run's message says why.
    pub fn output(&mut self) -> std::io::Result<std::process::Output> {
        use std::os::unix::process::ExitStatusExt;
        let mut out = self.command.output()?;
        let written = std::fs::read_to_string(self.status.path()).unwrap_or_default();
        if let Ok(code) = written.trim().parse::<i32>() {
            out.status = std::process::ExitStatus::from_raw(code << 8);
        }
        Ok(out)
    }
}
