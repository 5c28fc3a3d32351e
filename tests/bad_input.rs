//! Bad input: exit status 2, a one-paragraph message that names the file or
//! argument and the problem, no panic, and no output file (not even a
//! partial or temporary one).

mod common;

use std::path::Path;

struct Case {
    name: &'static str,
    /// Arguments after `render`; `{dir}` is replaced by the temp folder.
    args: Vec<String>,
    /// Text the message must contain (the file or argument it names).
    names: &'static str,
}

fn run_case(dir: &Path, case: &Case) {
    let out = dir.join("out.png");
    let args: Vec<String> = case
        .args
        .iter()
        .map(|a| a.replace("{dir}", &dir.display().to_string()))
        .collect();
    let result = common::gonio()
        .arg("render")
        .args(&args)
        .env("XDG_RUNTIME_DIR", dir)
        .output()
        .expect("gonio runs");
    let stderr = String::from_utf8_lossy(&result.stderr);
    // The loader may print harmless Vulkan notices; the error is our line.
    let message: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("gonio: error:"))
        .collect();
    assert_eq!(
        result.status.code(),
        Some(2),
        "{}: exit status; stderr: {stderr}",
        case.name
    );
    assert!(
        !stderr.contains("panicked"),
        "{}: panicked: {stderr}",
        case.name
    );
    assert_eq!(
        message.len(),
        1,
        "{}: expected one error paragraph, got: {stderr}",
        case.name
    );
    assert!(
        message[0].contains(case.names),
        "{}: the message does not name `{}`: {}",
        case.name,
        case.names,
        message[0]
    );
    assert!(!out.exists(), "{}: an output file was written", case.name);
    let leftovers: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".gonio-"))
        .collect();
    assert!(
        leftovers.is_empty(),
        "{}: temporary files left: {leftovers:?}",
        case.name
    );
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> String {
    std::fs::write(dir.join(name), bytes).unwrap();
    dir.join(name).display().to_string()
}

fn s(v: &[&str]) -> Vec<String> {
    v.iter().map(|x| x.to_string()).collect()
}

#[test]
fn bad_inputs_exit_2_with_a_clear_message_and_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = d.join("out.png").display().to_string();

    let invalid_json = write(d, "broken.gltf", b"{ \"asset\": { \"version\": \"2.0\" ");
    let unknown_ext = write(
        d,
        "instancing.gltf",
        br#"{"asset":{"version":"2.0"},"extensionsUsed":["EXT_mesh_gpu_instancing"],"extensionsRequired":["EXT_mesh_gpu_instancing"],"scenes":[{"nodes":[]}],"scene":0}"#,
    );
    let glb = std::fs::read(common::gltf_asset("Box/Box.glb")).unwrap();
    let truncated = write(d, "truncated.glb", &glb[..glb.len() / 2]);
    let bad_toml = write(d, "bad.toml", b"[image]\nwidth = \"wide\"\n");
    let unknown_key = write(
        d,
        "key.toml",
        b"[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 45.0\n",
    );

    let box_gltf = common::gltf_asset("Box/Box.gltf").display().to_string();
    let cases = vec![
        Case {
            name: "a colour of two numbers",
            args: s(&["-o", &out, "--set", "materials.ball.k_d=[0.8,0.1]"]),
            names: "a colour is [r, g, b] (three numbers) or one number; this array has 2 numbers",
        },
        Case {
            name: "a misspelt material",
            args: s(&["-o", &out, "--set", "materials.bal.k_e=3"]),
            names: "no material `bal` (it has ball, floor); did you mean `ball`?",
        },
        Case {
            name: "lights.0 on a glTF without [[lights]]",
            args: s(&[&box_gltf, "-o", &out, "--set", "lights.0.shadows=true"]),
            names: "the scene has no `lights`, so no entry 0",
        },
        Case {
            name: "--exposure with an EXR",
            args: s(&["-o", "{dir}/out.exr", "--exposure", "2"]),
            names: "is an EXR, which holds linear radiance",
        },
        Case {
            name: "a directory as SCENE",
            args: s(&["{dir}", "-o", &out]),
            names: "it is a directory",
        },
        Case {
            name: "missing file",
            args: s(&["{dir}/nope.gltf", "-o", &out]),
            names: "nope.gltf",
        },
        Case {
            name: "invalid JSON",
            args: s(&[&invalid_json, "-o", &out]),
            names: "broken.gltf",
        },
        Case {
            name: "unknown required extension",
            args: s(&[&unknown_ext, "-o", &out]),
            names: "EXT_mesh_gpu_instancing",
        },
        Case {
            name: "truncated glb",
            args: s(&[&truncated, "-o", &out]),
            names: "truncated.glb",
        },
        Case {
            name: "scene type error",
            args: s(&[&bad_toml, "-o", &out]),
            names: "bad.toml",
        },
        Case {
            name: "scene unknown key",
            args: s(&[&unknown_key, "-o", &out]),
            names: "fov",
        },
        Case {
            name: "unknown --set key",
            args: s(&["-o", &out, "--set", "materials.ball.rougness=0.2"]),
            names: "materials.ball.rougness",
        },
        Case {
            name: "NaN parameter",
            args: s(&["-o", &out, "--set", "materials.ball.k_d=nan"]),
            names: "k_d",
        },
        Case {
            name: "negative parameter",
            args: s(&["-o", &out, "--set", "materials.ball.k_s=-0.5"]),
            names: "k_s",
        },
        Case {
            name: "negative intensity",
            args: s(&["-o", &out, "--set", "lights.0.intensity=-3"]),
            names: "intensity",
        },
        Case {
            name: "bad shading mode",
            args: s(&["-o", &out, "--set", "shading.mode=smooth"]),
            names: "smooth",
        },
        Case {
            name: "zero width",
            args: s(&["-o", &out, "--width", "0"]),
            names: "image.width",
        },
        Case {
            name: "unknown image format",
            args: s(&["-o", "{dir}/out.jpg"]),
            names: "out.jpg",
        },
        Case {
            name: "output folder missing",
            args: s(&["-o", "{dir}/no/such/dir/out.png"]),
            names: "out.png",
        },
        Case {
            name: "output is a directory",
            args: s(&["-o", "{dir}"]),
            names: "",
        },
        Case {
            name: "no such adapter",
            args: s(&["-o", &out, "--adapter", "no-such-gpu-anywhere"]),
            names: "available: ",
        },
    ];
    for case in &cases {
        run_case(d, case);
    }
}

/// Sizes over the GPU's limits: each side fits, but the
/// readback buffer (16384 × 8192 × 16 bytes = 2 GiB) or the vertex buffer
/// (the flat-shaded 3200-segment plane: 2.2 GB) does not. Both panicked in
/// wgpu; now exit 2 naming the setting and what would fit.
#[test]
fn buffers_over_the_gpus_limits_are_refused_before_creation() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let exr = d.join("out.exr").display().to_string();
    let out = d.join("out.png").display().to_string();
    let cases = [
        Case {
            name: "readback buffer over max_buffer_size",
            args: s(&["-o", &exr, "--width", "16384", "--height", "8192"]),
            names: "--width 16384 --height 8192",
        },
        Case {
            name: "camera beyond f32 range",
            args: s(&["-o", &out, "--set", "camera.position=[1e300,1e300,1e300]"]),
            names: "camera.position = [1e300, 1e300, 1e300] is beyond",
        },
        Case {
            name: "light intensity beyond f32 range",
            args: s(&["-o", &out, "--set", "lights.0.intensity=3.5e38"]),
            names: "intensity = [3.5e38, 3.5e38, 3.5e38] is over 1e20",
        },
        Case {
            name: "light position beyond f32 range",
            args: s(&["-o", &out, "--set", "lights.0.position=[1e39,1e39,1e39]"]),
            names: "position = [1e39, 1e39, 1e39] is beyond",
        },
        Case {
            name: "ambient radiance beyond f32 range",
            args: s(&["-o", &out, "--set", "ambient.radiance=[1e39,1e39,1e39]"]),
            names: "ambient.radiance = [1e39, 1e39, 1e39] is over",
        },
        Case {
            name: "shadow maps over their memory cap",
            args: s(&[
                "-o",
                &out,
                "--set",
                "lights.0.shadows=true",
                "--set",
                "lights.0.shadow_map_size=8192",
            ]),
            names: "lights.N.shadow_map_size or [shadows] map_size",
        },
        Case {
            name: "vertex buffer over max_buffer_size",
            args: s(&[
                "-o",
                &out,
                "--shading",
                "flat",
                "--set",
                "objects.1.segments=3200",
            ]),
            names: "segments",
        },
        Case {
            name: "vertex buffer over max_buffer_size, 4096 segments (the limits allow it)",
            args: s(&[
                "-o",
                &out,
                "--shading",
                "flat",
                "--set",
                "objects.1.segments=4096",
            ]),
            names: "segments",
        },
        // The renderers' own allocations count against `--limit memory`
        // (the reference on a 4096-segment plane peaked at 10.5 GB within
        // the default limits): a 512-segment plane (528,256 triangles with the sphere)
        // needs about 100 MiB in the reference and 40 MiB on the GPU path,
        // both over a 16 MiB limit.
        Case {
            name: "reference hierarchy over --limit memory",
            args: s(&[
                "-o",
                &out,
                "--reference",
                "--set",
                "objects.1.segments=512",
                "--limit",
                "memory=16Mi",
            ]),
            names: "the CPU reference's ray-casting hierarchy for 528256 triangles",
        },
        Case {
            name: "vertex stream over --limit memory",
            args: s(&[
                "-o",
                &out,
                "--set",
                "objects.1.segments=512",
                "--limit",
                "memory=16Mi",
            ]),
            names: "--limit memory",
        },
    ];
    for case in &cases {
        run_case(d, case);
    }
}

/// `WGPU_BACKEND` naming no backend is named in the message (it ended in
/// "no adapter" with advice to install lavapipe), and the GL backend,
/// whose llvmpipe cannot render into the Rgba32Float radiance target,
/// renders (into Rgba32Uint) where it panicked, and `bench --smoke` there
/// fails with a message instead of a panic.
#[test]
fn the_backend_variable_is_checked_and_gl_renders() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.png");
    let run = |backend: &str, args: &[&str]| {
        let result = common::gonio()
            .args(args)
            .env("WGPU_BACKEND", backend)
            .current_dir(dir.path())
            .output()
            .expect("gonio runs");
        let stderr = String::from_utf8_lossy(&result.stderr).into_owned();
        (result.status.code(), stderr)
    };
    let render = ["render", "-o", out.to_str().unwrap()];
    let (code, stderr) = run("nonsense", &render);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("WGPU_BACKEND=nonsense"), "{stderr}");
    assert!(!out.exists());
    // GL renders (./setup.sh installs Mesa's EGL and GLES), into an
    // Rgba32Uint target on llvmpipe (tests/gl_backend.rs checks the
    // pixels); the bench, whose floor shaders write f32 targets, says
    // that it needs them: exit 2 with the message, not a panic.
    let (code, stderr) = run("gl", &render);
    assert_eq!(code, Some(0), "render on GL: {stderr}");
    assert!(out.exists(), "render on GL wrote nothing");
    let (code, stderr) = run("gl", &["bench", "--smoke"]);
    assert!(!stderr.contains("panicked"), "bench on GL: {stderr}");
    assert!(
        code == Some(0) || (code == Some(2) && stderr.contains("needs Rgba32Float render targets")),
        "bench on GL: exit {code:?}: {stderr}"
    );
}

/// Runs `gonio ARGS`; the exit status and stderr.
fn gonio_status(args: &[&str], dir: &Path) -> (Option<i32>, String) {
    let result = common::gonio()
        .args(args)
        .env("XDG_RUNTIME_DIR", dir)
        .output()
        .expect("gonio runs");
    (
        result.status.code(),
        String::from_utf8_lossy(&result.stderr).into_owned(),
    )
}

/// The names in `dir`, sorted.
fn names_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// `-o missing/dir/FILE` is refused alike by `fit`,
/// `render` and `brdf` (fit created the folders), and the message names
/// the folder, not the temporary file (`.gonio-…partial`).
#[test]
fn a_missing_output_folder_is_refused_alike_and_named_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let missing = |name: &str| d.join("missing/dir").join(name).display().to_string();
    let cases: [Vec<String>; 3] = [
        s(&["fit", "chrome", "--model", "ward", "-o", &missing("f.toml")]),
        s(&[
            "render",
            "--width",
            "16",
            "--height",
            "12",
            "-o",
            &missing("x.png"),
        ]),
        s(&[
            "brdf",
            "--model",
            "lambert",
            "--plot-albedo",
            &missing("x.svg"),
        ]),
    ];
    for args in &cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (code, stderr) = gonio_status(&args, d);
        assert_eq!(code, Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains("does not exist"), "{args:?}: {stderr}");
        assert!(stderr.contains("missing/dir"), "{args:?}: {stderr}");
        assert!(
            !stderr.contains(".partial") && !stderr.contains(".gonio-"),
            "{args:?}: {stderr}"
        );
        assert!(!d.join("missing").exists(), "{args:?} created the folder");
    }
}

/// A destination that exists and is not a regular file
/// is written in place (a character device) or refused (a FIFO nobody
/// reads), never replaced by a regular file, which a rename as root did
/// to device nodes. Device nodes are made with `mknod` in a temporary
/// folder (the tests run as root here; elsewhere the case says so and
/// checks the FIFO only).
#[cfg(unix)]
#[test]
fn outputs_that_are_not_regular_files_are_never_replaced() {
    use std::os::unix::fs::{FileTypeExt, symlink};
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let path = |name: &str| d.join(name).display().to_string();
    let kind = |name: &str| std::fs::symlink_metadata(d.join(name)).unwrap().file_type();
    let mknod = |name: &str, minor: &str| {
        std::process::Command::new("mknod")
            .args([&path(name), "c", "1", minor])
            .status()
            .is_ok_and(|s| s.success())
    };
    // /dev/null's and /dev/full's numbers (1, 3) and (1, 7).
    let devices = mknod("null.png", "3")
        && mknod("null.svg", "3")
        && mknod("null.toml", "3")
        && mknod("full.png", "7");
    if devices {
        let (code, stderr) = gonio_status(
            &[
                "render",
                "--width",
                "16",
                "--height",
                "12",
                "-o",
                &path("null.png"),
            ],
            d,
        );
        assert_eq!(code, Some(0), "{stderr}");
        let (code, stderr) = gonio_status(
            &[
                "brdf",
                "--model",
                "lambert",
                "--plot-albedo",
                &path("null.svg"),
            ],
            d,
        );
        assert_eq!(code, Some(0), "{stderr}");
        let (code, stderr) = gonio_status(
            &[
                "fit",
                "chrome",
                "--model",
                "lambert",
                "-o",
                &path("null.toml"),
            ],
            d,
        );
        assert_eq!(code, Some(0), "{stderr}");
        // A link to a device is followed, and the link stays.
        symlink(d.join("null.png"), d.join("link.png")).unwrap();
        let (code, stderr) = gonio_status(
            &[
                "render",
                "--width",
                "16",
                "--height",
                "12",
                "-o",
                &path("link.png"),
            ],
            d,
        );
        assert_eq!(code, Some(0), "{stderr}");
        assert!(kind("link.png").is_symlink());
        // A device that refuses the bytes: an error naming it.
        let (code, stderr) = gonio_status(
            &[
                "render",
                "--width",
                "16",
                "--height",
                "12",
                "-o",
                &path("full.png"),
            ],
            d,
        );
        assert_eq!(code, Some(2), "{stderr}");
        assert!(stderr.contains("full.png"), "{stderr}");
        for name in ["null.png", "null.svg", "null.toml", "full.png"] {
            assert!(kind(name).is_char_device(), "{name} was replaced");
        }
    } else {
        eprintln!("mknod is not permitted here: only the FIFO and link cases run");
    }
    let status = std::process::Command::new("mkfifo")
        .arg(d.join("pipe.png"))
        .status()
        .unwrap();
    assert!(status.success());
    let (code, stderr) = gonio_status(
        &[
            "render",
            "--width",
            "16",
            "--height",
            "12",
            "-o",
            &path("pipe.png"),
        ],
        d,
    );
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("no process reads"), "{stderr}");
    assert!(kind("pipe.png").is_fifo());
    // A link to a regular file: the file is replaced, the link stays.
    std::fs::write(d.join("real.png"), b"old").unwrap();
    symlink(d.join("real.png"), d.join("to-real.png")).unwrap();
    let (code, stderr) = gonio_status(
        &[
            "render",
            "--width",
            "16",
            "--height",
            "12",
            "-o",
            &path("to-real.png"),
        ],
        d,
    );
    assert_eq!(code, Some(0), "{stderr}");
    assert!(kind("to-real.png").is_symlink());
    assert!(
        std::fs::read(d.join("real.png"))
            .unwrap()
            .starts_with(b"\x89PNG")
    );
    // No temporary is left behind, whatever happened.
    assert!(
        names_in(d).iter().all(|n| !n.starts_with(".gonio-")),
        "{:?}",
        names_in(d)
    );
}
