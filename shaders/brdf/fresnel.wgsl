// Fresnel reflectance of a smooth interface (lecture: "Electric
// Conductors (e.g. Metals)", "Dielectrics (e.g. Glass)"): exact conductor
// and dielectric, the lecture's conductor approximation, Schlick, F0.
// f64 twin: src/material/brdf/fresnel.rs (same names, same order).
// cos_i is measured from the (micro)facet normal (I·H) and clamped into
// [0, 1] everywhere: reflection from outside only; rounding can pass 1.

// Floor of the Fresnel quotients' denominators (each quotient is
// |x − y|² / |x + y|², numerator ≤ denominator): a denominator is 0 only
// for η = 1, κ = 0 at cos = 0 (no interface) or η = κ = 0, where the
// numerator is 0 too and the quotient becomes 0. A normal f32.
const FRESNEL_DENOM_FLOOR: f32 = 1e-30;

// Exact unpolarized conductor Fresnel for n = η + iκ (pbrt-v3 FrConductor /
// Mitsuba 3 fresnel_conductor), a + ib = sqrt(n² − sin²θ) taken the
// stable way, written as sums
// of squares so f32 never makes them negative:
// r_s = ((a − cos)² + b²) / ((a + cos)² + b²),
// r_p = r_s ((a cos − sin²)² + b² cos²) / ((a cos + sin²)² + b² cos²).
fn fresnel_conductor(cos_i: f32, eta: vec3<f32>, kappa: vec3<f32>) -> vec3<f32> {
    let cos_theta = clamp(cos_i, 0.0, 1.0);
    let cos2 = cos_theta * cos_theta;
    let sin2 = 1.0 - cos2;
    let eta2 = eta * eta;
    let kappa2 = kappa * kappa;
    // Re(n² − sin²θ) as (η² − 1) − κ² + cos²θ: exactly cos²θ for η = 1,
    // where η² − κ² − sin²θ would cancel near grazing.
    let t0 = eta2 - 1.0 - kappa2 + cos2;
    let a2pb2 = sqrt(t0 * t0 + 4.0 * eta2 * kappa2); // a² + b² = |n² − sin²θ|
    // a + ib = sqrt(n² − sin²θ), the stable way: the larger of a, b is
    // sqrt((|z| + |Re z|)/2), the other from ab = ηκ (no cancellation).
    // The floor: big = 0 only for ηκ = 0, then small = 0 / 1e-30 = 0.
    let big = sqrt(0.5 * (a2pb2 + abs(t0)));
    let small = eta * kappa / max(big, vec3<f32>(FRESNEL_DENOM_FLOOR));
    let t0_nonneg = t0 >= vec3<f32>(0.0);
    let a = select(small, big, t0_nonneg);
    let b = select(big, small, t0_nonneg);
    let b2 = b * b;
    let a_minus = a - cos_theta;
    let a_plus = a + cos_theta;
    let r_s = (a_minus * a_minus + b2) / max(a_plus * a_plus + b2, vec3<f32>(FRESNEL_DENOM_FLOOR));
    let p_minus = a * cos_theta - sin2;
    let p_plus = a * cos_theta + sin2;
    let r_p = r_s * (p_minus * p_minus + b2 * cos2)
        / max(p_plus * p_plus + b2 * cos2, vec3<f32>(FRESNEL_DENOM_FLOOR));
    return 0.5 * (r_s + r_p);
}

// The lecture's conductor Fresnel as printed: ½ (r∥² + r⊥²),
// r∥² = ((η²+κ²) cos² − 2η cos + 1) / ((η²+κ²) cos² + 2η cos + 1),
// r⊥² = ((η²+κ²) − 2η cos + cos²) / ((η²+κ²) + 2η cos + cos²),
// the polynomials regrouped as sums of squares (the same numbers; no
// cancellation below 0 in f32). First denominator ≥ 1; second floored
// (0 only for η = κ = cos = 0).
fn fresnel_conductor_lecture(cos_i: f32, eta: vec3<f32>, kappa: vec3<f32>) -> vec3<f32> {
    let cos_theta = clamp(cos_i, 0.0, 1.0);
    let cos2 = cos_theta * cos_theta;
    let kappa2 = kappa * kappa;
    let eta_cos = eta * cos_theta;
    let par_minus = eta_cos - 1.0; // (η²+κ²) cos² − 2η cos + 1 = (η cos − 1)² + κ² cos²
    let par_plus = eta_cos + 1.0;
    let r_par2 = (par_minus * par_minus + kappa2 * cos2) / (par_plus * par_plus + kappa2 * cos2);
    let perp_minus = eta - cos_theta; // (η²+κ²) − 2η cos + cos² = (η − cos)² + κ²
    let perp_plus = eta + cos_theta;
    let r_perp2 = (perp_minus * perp_minus + kappa2)
        / max(perp_plus * perp_plus + kappa2, vec3<f32>(FRESNEL_DENOM_FLOOR));
    return 0.5 * (r_par2 + r_perp2);
}

// Exact unpolarized dielectric Fresnel (lecture: "Dielectrics") with
// Snell's law. η_i = η_t: 0 (no interface, every angle); total internal
// reflection: 1; otherwise cos θ_t > 0 and both denominators are > 0.
// η_i = η_t is a select, not a branch on material values alone (see
// UNIFORM_BRANCHES in phong.wgsl); it discards the 0/0 at grazing incidence.
fn fresnel_dielectric(cos_i: f32, eta_i: f32, eta_t: f32) -> f32 {
    let no_interface = eta_i == eta_t;
    let cos_theta = clamp(cos_i, 0.0, 1.0);
    let eta = eta_i / eta_t;
    let sin2_t = eta * eta * (1.0 - cos_theta * cos_theta); // Snell: sin θ_t = η sin θ_i
    if sin2_t >= 1.0 {
        return select(1.0, 0.0, no_interface); // total internal reflection (and the critical angle)
    }
    let cos_t = sqrt(1.0 - sin2_t); // > 0 here
    let r_par = (eta_t * cos_theta - eta_i * cos_t) / (eta_t * cos_theta + eta_i * cos_t);
    let r_perp = (eta_i * cos_theta - eta_t * cos_t) / (eta_i * cos_theta + eta_t * cos_t);
    return select(0.5 * (r_par * r_par + r_perp * r_perp), 0.0, no_interface);
}

// Schlick 1994: F0 + (1 − F0)(1 − cos)^5, the fifth power by multiplication.
fn fresnel_schlick(cos_i: f32, f0: vec3<f32>) -> vec3<f32> {
    let cos_theta = clamp(cos_i, 0.0, 1.0);
    let m = 1.0 - cos_theta;
    let m2 = m * m;
    let m5 = m2 * m2 * m;
    return f0 + (1.0 - f0) * m5;
}

// Conductor reflectance at normal incidence: ((η − 1)² + κ²) / ((η + 1)² + κ²).
fn f0_conductor(eta: vec3<f32>, kappa: vec3<f32>) -> vec3<f32> {
    let kappa2 = kappa * kappa;
    let eta_minus = eta - 1.0;
    let eta_plus = eta + 1.0;
    return (eta_minus * eta_minus + kappa2) / (eta_plus * eta_plus + kappa2);
}

// Dielectric reflectance at normal incidence: ((η_t − η_i) / (η_t + η_i))².
fn f0_dielectric(eta_i: f32, eta_t: f32) -> f32 {
    let r = (eta_t - eta_i) / (eta_t + eta_i);
    return r * r;
}
