// The shading frame and the one-sided BRDF wrapper every model shares.
// `eval_brdf` is in shaders/brdf/eval.wgsl; its CPU twin is
// material::brdf::eval.

// An orthonormal shading frame. Twin: brdf::SurfaceFrame.
struct SurfaceFrame {
    n: vec3<f32>,
    t: vec3<f32>,
    b: vec3<f32>,
}

// A unit vector orthogonal to n. Twin: brdf::any_tangent.
fn any_tangent(n: vec3<f32>) -> vec3<f32> {
    var axis = vec3<f32>(1.0, 0.0, 0.0);
    if abs(n.x) >= 0.9 {
        axis = vec3<f32>(0.0, 0.0, 1.0);
    }
    return normalize_or_zero(axis - n * dot(n, axis));
}

// Frame around n with t made orthogonal (Gram-Schmidt). Twin: SurfaceFrame::new.
fn surface_frame(n: vec3<f32>, t: vec3<f32>) -> SurfaceFrame {
    let projected = t - n * dot(n, t);
    var tangent = any_tangent(n);
    if dot(projected, projected) > 1e-12 {
        tangent = normalize(projected);
    }
    return SurfaceFrame(n, tangent, cross(n, tangent));
}

#if facing_normals
// FACING_COS_MIN of src/base/frame.rs.
const FACING_COS_MIN: f32 = 1e-3;

// The frame with its normal turned toward wo where it faces away
// (n·wo < FACING_COS_MIN): n' = normalize(n + (FACING_COS_MIN − n·wo)·wo),
// the tangent made orthogonal again; unchanged otherwise. A silhouette's
// interpolated or normal-mapped normal then shades as the other glTF
// renderers draw it instead of black. Twin: SurfaceFrame::facing.
fn facing_frame(frame: SurfaceFrame, wo: vec3<f32>) -> SurfaceFrame {
    let c = dot(frame.n, wo);
    if c >= FACING_COS_MIN {
        return frame;
    }
    return surface_frame(normalize(frame.n + (FACING_COS_MIN - c) * wo), frame.t);
}
#endif

// One-sided f_r: zero where N·I ≤ 0 or N·V ≤ 0 (Material::f_r in Rust).
fn f_r(m: Material, wi: vec3<f32>, wo: vec3<f32>, frame: SurfaceFrame) -> vec3<f32> {
    if dot(frame.n, wi) <= 0.0 || dot(frame.n, wo) <= 0.0 {
        return vec3<f32>(0.0);
    }
    return eval_brdf(m, wi, wo, frame);
}


#if vertex_colors
// The material under a vertex colour (glTF COLOR_0): k_a, k_d and
// base_color multiplied by its RGB, alpha by its A. Twin:
// Material::vertex_coloured.
fn vertex_coloured(m: Material, c: vec4<f32>) -> Material {
    var out = m;
    out.k_a *= c.rgb;
    out.k_d *= c.rgb;
    out.base_color *= c.rgb;
    out.alpha *= c.a;
    return out;
}
#endif
