//! Light through surfaces in the f64 reference (docs/transmission.md),
//! against closed forms: Beer–Lambert through a slab, a glass sphere's
//! image position (the ball lens), the angular spread of a dispersive
//! prism per wavelength (Snell's law), and the thin-wall furnace.

mod transmission_scenes;

use glam::DVec3;
use gonio::material::brdf::gltf_layers::transmission::dispersion_ior;
use gonio::reference::{refracted_path, render_reporting};
use gonio::scene::Rgb;
use gonio::scene::camera::Ray;
use gonio::scene::primitives::uv_sphere;
use transmission_scenes::{cuboid, emitter, glass, pixel, polyhedron, quad, scene};

/// Beer–Lambert through a slab of thickness `d` (a closed box, `z` from
/// `−d/2` to `d/2`) in front of an emitter of radiance `L`:
///
/// * index 1 (no interface): every pixel sees
///   `L · c^(d / (cos θ · D))` per channel, the true path length of its
///   oblique ray through the slab;
/// * index 1.5, the middle pixel (on the axis, normal incidence), a
///   smooth slab: `L (1 − F)² a / (1 − F² a²)`, `a = c^(d/D)`,
///   `F = 0.04`, the sum of the light passing straight and after `2k`
///   internal reflections.
///
/// The glass is smooth (roughness 0: one refracted ray, though the
/// pixel's roughness floor, α = 1.9·10⁻², widens its highlights beyond
/// `thin::STRAIGHT_ALPHA`; `thin::spreads`); at index 1 there is no
/// interface, which the reference follows straight on at any
/// roughness.
///
/// Tolerance: the pixels are `f32` (relative 2⁻²⁴ = 6·10⁻⁸ of the value,
/// 10⁻⁷ with the f64 arithmetic's rounding), plus, for the reflections,
/// the light the renderer reports untraced (`lost`, per unit radiance
/// behind, times `L`).
#[test]
fn beer_lambert_through_a_slab_is_the_closed_form() {
    let (d, distance) = (0.8, 0.5);
    let c = Rgb::new(0.9, 0.5, 0.2);
    let l = Rgb::new(2.0, 3.0, 4.0);
    for ior in [1.0, 1.5] {
        let mut slab = glass(ior, d);
        slab.layers.attenuation_distance = distance;
        slab.layers.attenuation_color = c;
        let meshes = vec![
            cuboid(
                DVec3::new(-3.0, -3.0, -d / 2.0),
                DVec3::new(3.0, 3.0, d / 2.0),
                0,
            ),
            quad(-3.0, 50.0, 1),
        ];
        let s = scene(9, meshes, vec![slab, emitter(l)]);
        let (frame, lost) = render_reporting(&s);
        let a = |path: f64| {
            Rgb::new(
                c.x.powf(path / distance),
                c.y.powf(path / distance),
                c.z.powf(path / distance),
            )
        };
        let close = |got: Rgb, want: Rgb, what: &str| {
            let tol = 1e-7 * want.max_element() + lost * l.max_element();
            let err = (got - want).abs().max_element();
            assert!(
                err <= tol,
                "{what}: {got} vs {want} (err {err:e}, tol {tol:e})"
            );
        };
        if ior == 1.0 {
            assert_eq!(lost, 0.0);
            for (i, j) in [(4, 4), (0, 0), (2, 7), (8, 3)] {
                let ray = s.camera.ray(j as f64 + 0.5, i as f64 + 0.5, 9, 9);
                let cos = -ray.direction.z;
                close(pixel(&frame, i, j), l * a(d / cos), &format!("({i}, {j})"));
            }
        } else {
            let f = ((ior - 1.0) / (ior + 1.0)).powi(2);
            let a = a(d);
            let want = l * a * (1.0 - f) * (1.0 - f) / (Rgb::ONE - a * a * (f * f));
            close(pixel(&frame, 4, 4), want, "normal incidence");
            assert!(lost < 1e-4, "{lost}");
        }
    }
}

/// A unit-speed ray's closest approach to the line `s·u` (through the
/// origin): the parameter `s` of the point on the line. For a ray in a
/// plane with the line it is where the two cross.
fn crossing_on_axis(ray: &Ray, u: DVec3) -> f64 {
    let (o, d) = (ray.origin, ray.direction);
    let b = d.dot(u);
    let (e, f) = (d.dot(o), u.dot(o));
    // Minimize |o + t d − s u|²: t = (b f − e)/(1 − b²), s = f + b t.
    let t = (b * f - e) / (1.0 - b * b);
    f + b * t
}

/// Snell's law, written here independently of the library: `d` (unit,
/// towards the surface) refracted at unit normal `n` (facing `d`'s
/// origin), from index `n1` into `n2`.
fn snell(d: DVec3, n: DVec3, n1: f64, n2: f64) -> DVec3 {
    let cos_i = -d.dot(n);
    let eta = n1 / n2;
    let cos_t = (1.0 - eta * eta * (1.0 - cos_i * cos_i)).sqrt();
    eta * d + (eta * cos_i - cos_t) * n
}

/// The exact image of a ray parallel to axis `u` at distance `h` through
/// a perfect sphere of radius `r` and index `n` about the origin: where
/// the ray leaving the sphere crosses the axis (parameter along `u`).
fn ball_lens_exact(u: DVec3, side: DVec3, h: f64, r: f64, n: f64) -> f64 {
    let p1 = side * h - u * (r * r - h * h).sqrt();
    let d1 = snell(u, p1 / r, 1.0, n);
    let t = -2.0 * p1.dot(d1);
    let p2 = p1 + d1 * t;
    let d2 = snell(d1, -p2 / r, n, 1.0);
    crossing_on_axis(
        &Ray {
            origin: p2,
            direction: d2,
        },
        u,
    )
}

/// A glass sphere (a ball lens of radius R and index n) focuses a ray
/// parallel to its axis at `f = nR / (2(n − 1))` from its centre in the
/// paraxial limit (the ball lens formula; `EFL = nD / (4(n − 1))`).
///
/// 1. The exact trace through a perfect sphere (closed form, written
///    here) tends to it: Richardson's extrapolation of the heights h and
///    h/2 (h = 0.05 R), `(4 z(h/2) − z(h)) / 3`, removes the `h²` term of
///    the spherical aberration and leaves `O(h⁴)`: within 10⁻⁵ R.
/// 2. The reference renderer's refracted path through a tessellated
///    sphere (512 slices, 256 stacks, exact vertex normals) at h = 0.2 R,
///    0.5 R and 0.8 R crosses the axis where the exact trace does, within
///    the tessellation's error: a facet spans Δ = 2π/512, so the
///    interpolated normal and the hit point deviate from the sphere's by
///    at most about Δ²/8 = 1.9·10⁻⁵ (rad, and R), each refraction turns
///    a normal error into at most (n + 1)·Δ²/8 of direction, two of them
///    5Δ²/8 = 9.4·10⁻⁵ rad; seen from the exit point at distance ℓ from
///    the crossing, under the angle u to the axis, that moves the crossing
///    by ℓ·9.4·10⁻⁵/sin u along the axis (evaluated per ray).
#[test]
fn a_glass_sphere_focuses_where_the_ball_lens_formula_says() {
    let (r, n) = (1.0, 1.5);
    let f = n * r / (2.0 * (n - 1.0));
    // Not along a row or column of the sphere's vertices.
    let u = DVec3::new(0.1271f64.sin(), 0.0, 0.1271f64.cos());
    let side = (DVec3::Y + DVec3::Y.cross(u) * 0.3).normalize();
    let h = 0.05 * r;
    let z = |h: f64| ball_lens_exact(u, side, h, r, n);
    let paraxial = (4.0 * z(h / 2.0) - z(h)) / 3.0;
    assert!((paraxial - f).abs() < 1e-5 * r, "{paraxial} vs {f}");
    assert!(
        z(h) < f,
        "spherical aberration shortens the focus of a marginal ray"
    );

    let s = scene(
        1,
        vec![uv_sphere(DVec3::ZERO, r, 512, 0)],
        vec![glass(n, 1.0)],
    );
    let delta = std::f64::consts::TAU / 512.0;
    let angle_error = (n + 1.0) * 2.0 * delta * delta / 8.0;
    for h in [0.2, 0.5, 0.8] {
        let ray = Ray {
            origin: side * h - u * 10.0,
            direction: u,
        };
        let path = refracted_path(&s, ray, None);
        assert_eq!(path.len(), 3, "h {h}: in and out of the sphere");
        let exit = path[2];
        let got = crossing_on_axis(&exit, u);
        let want = z(h);
        let sin_u = exit.direction.cross(u).length();
        let ell = (exit.origin - u * want).length();
        let tol = ell * angle_error / sin_u;
        assert!(
            (got - want).abs() <= tol,
            "h {h}: crosses at {got}, exact {want} (tol {tol:e})"
        );
    }
}

/// A prism of apex angle A and index `n(λ)` (KHR_materials_dispersion:
/// n_d = 1.5, dispersion 0.5, V_d = 40) deviates a ray entering at θ₁ by
/// `δ(λ) = θ₁ + asin(n sin(A − asin(sin θ₁ / n))) − A` (Snell's law at
/// both faces). The reference's refracted path through the prism mesh
/// (flat faces, exact normals) gives the same deviation at every traced
/// wavelength and the same angular spread `δ(F) − δ(C)` between the
/// Fraunhofer F (486.13 nm) and C (656.27 nm) lines, within 10⁻¹² rad
/// (f64 rounding of a few dot products and normalizations).
#[test]
fn a_prism_spreads_the_wavelengths_as_snells_law_says() {
    let (nd, dispersion) = (1.5, 0.5);
    let apex = 40f64.to_radians();
    // Cross-section in the xz-plane: apex at the top (+x), base below;
    // extruded along y.
    let half = apex / 2.0;
    let (height, y) = (2.0, 3.0);
    let top = DVec3::new(1.0, 0.0, 0.0);
    let left = top + DVec3::new(-height, 0.0, -height * half.tan());
    let right = top + DVec3::new(-height, 0.0, height * half.tan());
    let at = |p: DVec3, s: f64| p + DVec3::Y * (s * y);
    let faces = vec![
        // The two refracting faces, the base, and the two ends.
        vec![at(top, -1.0), at(top, 1.0), at(right, 1.0), at(right, -1.0)],
        vec![at(left, -1.0), at(left, 1.0), at(top, 1.0), at(top, -1.0)],
        vec![
            at(right, -1.0),
            at(right, 1.0),
            at(left, 1.0),
            at(left, -1.0),
        ],
        vec![at(top, 1.0), at(left, 1.0), at(right, 1.0)],
        vec![at(top, -1.0), at(right, -1.0), at(left, -1.0)],
    ];
    let mut prism = glass(nd, 1.0);
    prism.layers.dispersion = dispersion;
    let s = scene(1, vec![polyhedron(&faces, 0)], vec![prism]);
    // The entry face (left–top) and its outward normal.
    let centroid = (top + left + right) / 3.0;
    let n_in = (top - left).cross(DVec3::Y).normalize();
    let n_in = if n_in.dot(left - centroid) > 0.0 {
        n_in
    } else {
        -n_in
    };
    let theta1 = 50f64.to_radians();
    // The ray arrives against the normal, turned by θ₁ towards the apex
    // (the textbook prism: it leaves through the other face, bent
    // towards the base).
    let towards_apex = (top - left).normalize();
    let direction = -n_in * theta1.cos() + towards_apex * theta1.sin();
    let entry = left + (top - left) * 0.6;
    let ray = Ray {
        origin: entry - direction * 5.0,
        direction,
    };
    let deviation = |lambda: f64| {
        let path = refracted_path(&s, ray, Some(lambda));
        assert_eq!(path.len(), 3, "λ {lambda}: in and out of the prism");
        let out = path[2].direction;
        let (sin, cos) = (direction.cross(out).length(), direction.dot(out));
        sin.atan2(cos)
    };
    let snell = |lambda: f64| {
        let n = dispersion_ior(nd, dispersion, lambda);
        let inner = (theta1.sin() / n).asin();
        theta1 + (n * (apex - inner).sin()).asin() - apex
    };
    for lambda in [400.0, 486.13, 550.0, 587.56, 656.27, 700.0] {
        let (got, want) = (deviation(lambda), snell(lambda));
        assert!((got - want).abs() < 1e-12, "λ {lambda}: {got} vs {want}");
    }
    let spread = deviation(486.13) - deviation(656.27);
    let want = snell(486.13) - snell(656.27);
    assert!((spread - want).abs() < 1e-12, "{spread} vs {want}");
    // Blue bends more than red, by about (n_F − n_C) = (n_d − 1)/V_d
    // times the prism's dδ/dn (here about 1.5): a visible spread.
    assert!(spread > 0.005, "{spread}");
}

/// The thin-wall furnace through the renderer: a white thin wall of
/// transmission 1 (index 1.5), turned by `tilt` about the vertical, before
/// an emitter of radiance 1 that fills everything behind it, shows
/// `T(μ_o)`, the wall's transmitted albedo, and `R + T ≤ 1` with `R` its
/// reflected albedo.
///
/// * Smooth (the material's own α below `thin::STRAIGHT_ALPHA`,
///   `thin::spreads`: one ray straight on): `T = 1 − F(μ_o)` with
///   Schlick's F of the base, `0.04 + 0.96 (1 − μ_o)⁵`, to the f32
///   pixel's 10⁻⁷ (tolerance 10⁻⁶), though the pixel's roughness floor
///   (9 pixels over 20°: α = 1.9·10⁻²) is far above the threshold.
/// * Rough (r = 0.5, `visible_normals::LOBE_SAMPLES` = 64 Hammersley
///   points on the visible normals): `T` is the lobe's albedo
///   `∫ (1 − F) D Vis |cos|`, by `dfg::integrate` (2¹⁶ samples)
///   `T = E − R`, `E = A + B`,
///   `R = F0 A + B` at F0 = 0.04, at the effective α. The tolerance
///   4·10⁻³ is the 64-point rule's error on this lobe: measured on
///   2026-12-05 at these nine views, 1.1·10⁻⁵ to 9.5·10⁻⁴ for μ ≥ 0.64
///   and up to 3.1·10⁻³ at the grazing μ = 0.26 (256 points: at most
///   4.4·10⁻⁴ at every view).
#[test]
fn thin_wall_furnace_through_the_renderer() {
    use gonio::material::brdf::dfg;
    use gonio::reference::transmission::thin::spreads;
    for (r, tilt_deg) in [
        (0.01, 0.0),
        (0.01, 60.0),
        (0.01, 80.0),
        (0.5, 0.0),
        (0.5, 50.0),
        (0.5, 75.0),
    ] {
        let tilt = f64::to_radians(tilt_deg);
        let turn = glam::DMat4::from_rotation_y(tilt);
        let mut wall_mesh = quad(0.0, 100.0, 0);
        wall_mesh.transform(turn);
        let mut light = quad(-0.5, 1000.0, 1);
        light.transform(turn);
        let mut wall = glass(1.5, 0.0);
        wall.roughness = r;
        let s = scene(9, vec![wall_mesh, light], vec![wall, emitter(Rgb::ONE)]);
        let alpha = s.effective_materials()[0].roughness.powi(2);
        let (frame, lost) = render_reporting(&s);
        assert_eq!(lost, 0.0);
        let normal = turn.transform_vector3(DVec3::Z);
        for (i, j) in [(4, 4), (0, 0), (8, 2)] {
            let ray = s.camera.ray(j as f64 + 0.5, i as f64 + 0.5, 9, 9);
            let mu = -ray.direction.dot(normal);
            let t = pixel(&frame, i, j);
            let what = format!("r {r} tilt {tilt_deg}° ({i}, {j}), μ {mu:.4}");
            assert!(t.x == t.y && t.y == t.z, "{what}: {t}");
            let [a, b] = dfg::integrate(mu, alpha, 1 << 16);
            let reflected = 0.04 * a + b;
            if !spreads(alpha, s.roughness_floor()) {
                let f = 0.04 + 0.96 * (1.0 - mu).powi(5);
                assert!((t.x - (1.0 - f)).abs() < 1e-6, "{what}: {t} vs {}", 1.0 - f);
                assert!(t.x + f <= 1.0 + 1e-6, "{what}");
            } else {
                let want = a + b - reflected;
                eprintln!(
                    "{what}: T {:.6} vs {want:.6}, error {:.2e}",
                    t.x,
                    (t.x - want).abs()
                );
                assert!((t.x - want).abs() < 4e-3, "{what}: {} vs {want}", t.x);
                assert!(
                    t.x + reflected <= 1.0 + 1e-6,
                    "{what}: T {} R {reflected}",
                    t.x
                );
            }
        }
    }
}
