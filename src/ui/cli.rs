//! `gonio view`: the command line of the viewer.

use std::path::PathBuf;

/// `gonio view [SCENE] ...`
#[derive(Debug, Clone, clap::Args)]
pub struct ViewArgs {
    /// A scene `.toml`, a `.gltf` or a `.glb`. Without it: the built-in
    /// scene. Another file can be opened from the panel or dropped on the
    /// window.
    pub scene: Option<PathBuf>,
    /// Override any scene-file key by its dotted path, as for `gonio render`.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Compare mode: a material to compare with the selected one, as
    /// `MODEL[,KEY=VALUE]...` (the syntax of `gonio brdf --compare`, e.g.
    /// `cook-torrance,preset=gold,roughness=0.1`). Every plot overlays it;
    /// the 3D view is split, the right half showing the selected material
    /// replaced by the first compared one. Repeatable; `--edit
    /// FRAME:compare.N.KEY=VALUE` edits compared material N (from 0).
    #[arg(long = "compare", value_name = "SPEC")]
    pub compare: Vec<String>,
    /// Compare the scene's first material, a measured one, with its fit
    /// under MODEL (a `gonio fit` model label such as `ct-ggx-conductor`,
    /// `ward`, `abc`, or a `gonio fit --model` spec): the parameters in
    /// docs/fit/fits.toml where that material was fitted, else fitted now.
    #[arg(long = "compare-fit", value_name = "MODEL")]
    pub compare_fit: Option<String>,
    /// Window size in pixels, e.g. `1280x720`.
    #[arg(long, value_name = "WxH", default_value = "1280x720", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Present without waiting for the display's refresh (measures the
    /// real frame time; may tear).
    #[arg(long)]
    pub no_vsync: bool,
    /// Exposure in stops, as `gonio render --exposure`.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub exposure: f64,
    /// Hide the side panel (the 3D view fills the window).
    #[arg(long)]
    pub no_panel: bool,
    /// Hide the overlay (frame time, triangles, adapter) over the 3D area.
    #[arg(long)]
    pub no_overlay: bool,
    /// Scripted mode: render this many frames, then exit (tests,
    /// benchmarks). Scripted runs draw continuously; the interactive
    /// viewer draws only when something changes (src/ui/pacing.rs).
    #[arg(long, value_name = "N")]
    pub frames: Option<u32>,
    /// Exit once this many seconds pass with no frame drawn and the
    /// panel's background plots done and shown, printing the frames drawn
    /// (tests and measurements of the idle viewer; not with `--frames` or
    /// `--spin`, which draw continuously). A viewer that never idles
    /// gives up after 60 s with an error.
    #[arg(long, value_name = "SECONDS")]
    pub exit_when_idle: Option<f64>,
    /// Write a screenshot of the window to this PNG after the last scripted
    /// frame (with `--frames`; the F12 key and the panel's button save one
    /// any time). Prints the 3D area's rectangle in the window.
    #[arg(long, value_name = "PNG")]
    pub screenshot: Option<PathBuf>,
    /// Print frame-time statistics (median, quartiles) at exit, over the
    /// frames after the first `--warmup`, and what was sent to the GPU
    /// by kind (calls and bytes) in the first frame and in the later ones.
    #[arg(long)]
    pub frame_times: bool,
    /// Frames excluded from `--frame-times` (pipeline compilation, shadow
    /// maps, first presents).
    #[arg(long, default_value_t = 10, value_name = "N")]
    pub warmup: u32,
    /// Scripted edit: at frame FRAME, change KEY to VALUE as the panel
    /// does (materials in place, lights by reloading), e.g.
    /// `--edit 3:materials.ball.k_d=[0,0,1]`; the environment map's keys
    /// too (`--edit 3:environment.sh_order=4`, `environment.enabled=false`
    /// switches the map off), compared materials (`compare.N.KEY`,
    /// `compare.split`, `compare.shown`) and the plots' settings
    /// (`plots.theta_i`, `plots.phi_i`, `plots.phi_d`,
    /// `plots.quantity=f_r|f_r-cos`, `plots.channel`, `plots.log`,
    /// `plots.decades`, `plots.probe=TH,TD`,
    /// `plots.layer=all|base|sheen|clearcoat|each` (a layered gltf-pbr
    /// material's whole, one layer's term, or each apart), the views `plots.slice`,
    /// `plots.albedo`, `plots.halfdiff`, `plots.lobe`); the panel's
    /// sections with `panel.show=SECTION` (open it and scroll it to the
    /// top: `--edit 1:panel.show=Plots`) and `panel.hide=SECTION`; the
    /// material variant of the glTF files (`gltf.variant=NAME`,
    /// KHR_materials_variants: the scene is loaded again in it).
    /// Repeatable.
    #[arg(long = "edit", value_name = "FRAME:KEY=VALUE", value_parser = parse_edit)]
    pub edits: Vec<(u32, String)>,
    /// Scripted file drop: at frame FRAME, open PATH as if it were dropped
    /// on the window (a bad file shows its error and keeps the scene; a
    /// `.hdr` or `.exr` becomes the environment map).
    #[arg(long = "drop", value_name = "FRAME:PATH", value_parser = parse_drop)]
    pub drops: Vec<(u32, PathBuf)>,
    /// Scripted resize: at frame FRAME, ask for a window of WxH pixels
    /// (`0x0` minimizes it). Repeatable.
    #[arg(long = "resize", value_name = "FRAME:WxH", value_parser = parse_resize)]
    pub resizes: Vec<(u32, (u32, u32))>,
    /// Orbit the camera by this many degrees per frame (scripted runs that
    /// measure a moving view).
    #[arg(
        long,
        default_value_t = 0.0,
        value_name = "DEG",
        allow_negative_numbers = true
    )]
    pub spin: f64,
    /// Orbit every `[[lights]]` entry about the vertical axis through the
    /// camera's target by this many degrees per frame, so the shadow maps
    /// are drawn anew every frame (scripted runs that measure a moving
    /// light; src/ui/lights/spin.rs).
    #[arg(
        long,
        default_value_t = 0.0,
        value_name = "DEG",
        allow_negative_numbers = true
    )]
    pub spin_lights: f64,
    /// GPU adapter to use (as for `gonio render`; also GONIO_ADAPTER).
    #[arg(long, value_name = "NAME")]
    pub adapter: Option<String>,
    /// Raise a cap on what input files may hold (as for `gonio render`).
    #[arg(long = "limit", value_name = "KEY=VALUE")]
    pub limits: Vec<String>,
    /// Print the adapter and the shader features.
    #[arg(short, long)]
    pub verbose: bool,
}

fn parse_edit(text: &str) -> Result<(u32, String), String> {
    let (frame, assignment) = text
        .split_once(':')
        .ok_or_else(|| format!("`{text}` is not FRAME:KEY=VALUE"))?;
    let frame = frame
        .trim()
        .parse::<u32>()
        .map_err(|_| format!("`{frame}` in `{text}` is not a frame number"))?;
    if !assignment.contains('=') {
        return Err(format!("`{assignment}` in `{text}` is not KEY=VALUE"));
    }
    Ok((frame, assignment.to_string()))
}

fn parse_drop(text: &str) -> Result<(u32, PathBuf), String> {
    let (frame, path) = text
        .split_once(':')
        .ok_or_else(|| format!("`{text}` is not FRAME:PATH"))?;
    let frame = frame
        .trim()
        .parse::<u32>()
        .map_err(|_| format!("`{frame}` in `{text}` is not a frame number"))?;
    Ok((frame, PathBuf::from(path)))
}

fn parse_resize(text: &str) -> Result<(u32, (u32, u32)), String> {
    let (frame, size) = text
        .split_once(':')
        .ok_or_else(|| format!("`{text}` is not FRAME:WxH"))?;
    let frame = frame
        .trim()
        .parse::<u32>()
        .map_err(|_| format!("`{frame}` in `{text}` is not a frame number"))?;
    if size == "0x0" {
        return Ok((frame, (0, 0)));
    }
    Ok((frame, parse_size(size)?))
}

fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("`{text}` is not WIDTHxHEIGHT, e.g. 1280x720"))?;
    let side = |s: &str| -> Result<u32, String> {
        match s.trim().parse::<u32>() {
            Ok(v) if (16..=8192).contains(&v) => Ok(v),
            _ => Err(format!(
                "`{s}` in `{text}` is not a side of 16..=8192 pixels"
            )),
        }
    };
    Ok((side(w)?, side(h)?))
}

#[cfg(test)]
mod tests {
    use super::parse_size;

    #[test]
    fn sizes_parse_and_range_check() {
        assert_eq!(parse_size("1280x720"), Ok((1280, 720)));
        assert_eq!(parse_size("64X48"), Ok((64, 48)));
        assert!(parse_size("1280").is_err());
        assert!(parse_size("0x10").is_err());
        assert!(parse_size("99999x10").is_err());
    }
}
