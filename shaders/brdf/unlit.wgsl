// Unlit: no reflection, the surface shows its base colour as radiance
// (glTF KHR_materials_unlit: "the material's base color is the final
// color of the fragment"; contract "Other glTF material extensions").
// f64 twin: src/material/brdf/unlit.rs.

// f_r = 0: no light and no environment reaches the viewer by reflection.
fn unlit_f_r() -> vec3<f32> {
    return vec3<f32>(0.0);
}

// The radiance the surface shows, L = b, with textures and COLOR_0
// already multiplied into b (surface.wgsl, textures.wgsl).
fn unlit_radiance(base_color: vec3<f32>) -> vec3<f32> {
    return base_color;
}
