//! The built-in scene, kept as a scene file so users can read and copy it
//! (`assets/scenes/default.toml`) and override any key with `--set`.

/// Text of the built-in scene file.
pub const DEFAULT_SCENE_TOML: &str = include_str!("../../assets/scenes/default.toml");
