//! A rough volume's boundary in the f64 reference (docs/transmission.md):
//! the path spread by the rough dielectric BSDF of Walter et al. 2007 at
//! its first crossing and each of its paths at the second, measured in a
//! furnace against the BSDF's albedo, and its smooth limit.

mod transmission_scenes;

use glam::DVec3;
use gonio::material::Material;
use gonio::material::brdf::SurfaceFrame;
use gonio::material::brdf::gltf_layers::transmission::dispersion_ior;
use gonio::material::brdf::gltf_layers::volume_albedo::rough_dielectric_albedo;
use gonio::reference::render_reporting;
use gonio::reference::transmission::rough_boundary::{Boundary, samples_of};
use gonio::reference::transmission::thin::{STRAIGHT_ALPHA, spreads};
use gonio::reference::transmission::visible_normals::LOBE_SAMPLES;
use gonio::reference::transmission::{Crossing, Scenery, Traced, spectrum, through};
use gonio::scene::camera::Ray;
use gonio::scene::{Light, Rgb, Scene};
use std::borrow::Cow;
use transmission_scenes::{cuboid, emitter, glass, pixel, scene};

/// The flat boundary `z = 0` of a glass filling `z < 0`, in a uniform
/// radiance `L` from every direction on both sides: a furnace for the
/// interface alone (no other surface; the boundary's own reflection, the
/// reflection equation's term, left out).
struct Furnace {
    glass: Material,
    radiance: f64,
}

impl Scenery for Furnace {
    fn cross(&self, ray: &Ray, t_min: f64) -> Option<Crossing<'_>> {
        let t = -ray.origin.z / ray.direction.z;
        (t.is_finite() && t > t_min).then(|| Crossing {
            mesh: 0,
            ray: *ray,
            t,
            point: ray.origin + ray.direction * t,
            frame: SurfaceFrame::from_normal(DVec3::Z),
            face: DVec3::Z,
            material: Cow::Borrowed(&self.glass),
        })
    }
    fn surface_radiance(&self, _: &Crossing) -> Rgb {
        Rgb::ZERO
    }
    fn background(&self, _: DVec3) -> Rgb {
        Rgb::splat(self.radiance)
    }
    fn epsilon(&self) -> f64 {
        1e-9
    }
    fn roughness_floor(&self) -> f64 {
        0.0
    }
    fn lights(&self) -> &[Light] {
        &[]
    }
    fn light_visible(&self, _: usize, _: DVec3, _: DVec3) -> f64 {
        0.0
    }
}

impl Furnace {
    /// The light through the boundary seen from above (outside the glass)
    /// at `μ`.
    fn through(&self, mu: f64) -> Traced {
        let direction = -DVec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
        let ray = Ray {
            origin: -direction,
            direction,
        };
        let c = self.cross(&ray, 0.0).expect("the ray meets the boundary");
        through(self, &c)
    }
}

/// One pixel looking along −Z at a glass slab (index 1.5, roughness `r`)
/// turned by `acos μ` about Y, inside an emitter of radiance `L` that
/// surrounds everything (its faces seen from inside): from outside the
/// slab, or from inside it (`inside`: the camera in the glass). The view
/// is 0.001° wide, so the pixel's roughness floor (`8.7·10⁻⁶`) leaves α
/// within `4·10⁻⁵` of `r²`.
fn slab_in_a_furnace(r: f64, mu: f64, inside: bool, l: f64) -> Scene {
    let turn = glam::DMat4::from_rotation_y(mu.acos());
    let mut slab = if inside {
        // Wide enough that the far face (z = 20), not a side, meets
        // what the first crossing reflects down to 0.6° from the plane.
        cuboid(
            DVec3::new(-2000.0, -2000.0, -1.0),
            DVec3::new(2000.0, 2000.0, 20.0),
            0,
        )
    } else {
        cuboid(
            DVec3::new(-20.0, -20.0, -1.0),
            DVec3::new(20.0, 20.0, 0.0),
            0,
        )
    };
    slab.transform(turn);
    let around = cuboid(DVec3::splat(-5000.0), DVec3::splat(5000.0), 1);
    let mut g = glass(1.5, 1.0);
    g.roughness = r;
    let mut s = scene(1, vec![slab, around], vec![g, emitter(Rgb::splat(l))]);
    s.camera.fov_y_deg = 0.001;
    s
}

/// What a clear slab in a uniform emitter passes, per unit radiance, of
/// one pixel's path at `μ` (from outside, or from inside the glass): its
/// first rough crossing (the 64-point set, a frame of normal +Z), each of
/// its paths that stays in the glass crossing the parallel far face with
/// that face's albedo `A` (the 4096-point set), each that leaves reaching
/// the emitter whole.
fn slab_passes(alpha: f64, mu: f64, inside: bool) -> f64 {
    let up = SurfaceFrame::from_normal(DVec3::Z);
    let down = SurfaceFrame::from_normal(-DVec3::Z);
    let wi = DVec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
    let first = Boundary {
        frame: &up,
        face: DVec3::Z,
        wi,
        alpha,
        etas: if inside { (1.5, 1.0) } else { (1.0, 1.5) },
        reflections: inside,
    };
    samples_of(LOBE_SAMPLES, &first)
        .iter()
        .map(|s| {
            if inside && s.refracted {
                return s.weight;
            }
            // The far face's normal towards the path's origin.
            let (frame, face) = if s.direction.z < 0.0 {
                (&up, DVec3::Z)
            } else {
                (&down, -DVec3::Z)
            };
            let far = Boundary {
                frame,
                face,
                wi: -s.direction,
                alpha,
                etas: (1.5, 1.0),
                reflections: true,
            };
            let albedo: f64 = samples_of(4096, &far).iter().map(|t| t.weight).sum();
            s.weight * albedo
        })
        .sum()
}

/// The white furnace of a rough volume through the renderer: a clear,
/// non-absorbing slab in a uniform emitter. All the light a path carries
/// into the slab leaves it into the emitter, or is cut (reported as
/// `lost`, per unit radiance: here the light that the smooth crossings
/// after the second trap by total internal reflection between the slab's
/// parallel faces), so `pixel / L + lost` is what the two rough crossings
/// pass ([`slab_passes`]): the first crossing's paths, each through the
/// far face along the one normal of its stratum. Seen from outside, the
/// reflection off the outside is the surface's own term, which reflects
/// no emitter; seen from inside, the first crossing's reflected paths
/// meet the far face too.
///
/// Tolerance: the second crossing's 64 paths against the far face's
/// albedo, the unit test `the_second_crossing_integrates_the_far_face`
/// (3·10⁻² plus the 4096-point rule's 8.1·10⁻⁴), plus the first
/// crossing's 64-point rule turned about the normal (the renderer's frame
/// is the mesh's, [`slab_passes`]' another: the rule's error, 3·10⁻³ into
/// the glass, 3·10⁻² out of it), plus the f32 pixel's 10⁻⁶.
#[test]
fn a_rough_volume_in_a_furnace_passes_both_crossings() {
    let l = 2.0;
    for r in [0.3, 0.5, 1.0] {
        for mu in [1.0, 0.7, 0.3] {
            for inside in [false, true] {
                let s = slab_in_a_furnace(r, mu, inside, l);
                let alpha = s.effective_materials()[0].roughness.powi(2);
                let (frame, lost) = render_reporting(&s);
                let got = pixel(&frame, 0, 0);
                assert!(got.x == got.y && got.y == got.z, "{got}");
                let passed = got.x / l + lost;
                let want = slab_passes(alpha, mu, inside);
                let first = if inside { 3e-2 } else { 3e-3 };
                let tol = 3e-2 + 8.1e-4 + first + 1e-6;
                let what = format!("r {r} μ {mu} inside {inside}");
                eprintln!(
                    "{what}: pixel/L {:.6} + lost {lost:.2e} = {passed:.6} vs {want:.6} ({:.1e})",
                    got.x / l,
                    passed - want
                );
                assert!((passed - want).abs() <= tol, "{what}: {passed} vs {want}");
                assert!(passed <= 1.0 + 1e-6, "{what}: {passed}");
            }
        }
    }
}

/// A dispersive rough boundary (dispersion 1, `V_d = 20`) entered in the
/// furnace of a flat interface (nothing else in the scene, so nothing is
/// cut): each of the 41 wavelengths is sampled with its own `n(λ)`, so
/// the pixel is `L Σ_k c_k T(μ, n(λ_k))` (`spectrum::weights`), each `T`
/// by quadrature. Tolerance: the 64-point rule's 3·10⁻³ per wavelength,
/// times `Σ_k |c_k|` per channel (the weights of a channel sum to 1, but
/// red's are negative near 500 nm), plus the quadrature's 10⁻⁵ at 1000 ×
/// 256 cells for α = 0.25 (`e_q` in the unit test).
#[test]
fn a_dispersive_rough_boundary_passes_each_wavelengths_albedo() {
    let l = 2.0;
    let mut g = glass(1.5, 1.0);
    g.roughness = 0.5;
    g.layers.dispersion = 1.0;
    let furnace = Furnace {
        glass: g,
        radiance: l,
    };
    let weights = spectrum::weights();
    let spread = weights.iter().fold(Rgb::ZERO, |s, &(_, c)| s + c.abs());
    for mu in [0.7, 0.3] {
        let got = furnace.through(mu);
        assert_eq!(got.lost, 0.0);
        let want = weights.iter().fold(Rgb::ZERO, |s, &(lambda, c)| {
            let n = dispersion_ior(1.5, 1.0, lambda);
            s + c * rough_dielectric_albedo(0.25, mu, (1.0, n), (1000, 256))[1]
        });
        let tol = spread * 3e-3 + Rgb::splat(1e-5);
        let err = (got.radiance / l - want).abs();
        assert!(
            err.cmple(tol).all(),
            "μ {mu}: {} vs {want} (err {err}, tol {tol})",
            got.radiance / l
        );
        // The channels differ: blue sees the larger index, so more Fresnel
        // reflection.
        assert!(want.z < want.x, "μ {mu}: {want}");
    }
}

/// Where the roughness crosses `thin::STRAIGHT_ALPHA` the reference
/// switches from the smooth boundary to the sampled one, and the picture
/// does not jump: the furnace slab's `pixel / L + lost` at α 1 % above
/// the threshold (rough) and 1 % below (smooth: `1 − F(μ)` from outside,
/// 1 from inside) agree within the rough split's distance from Fresnel's
/// at the threshold, 10⁻⁴ (the unit test
/// `the_rough_split_is_the_smooth_one_at_the_threshold`), plus the f32
/// pixel's 10⁻⁶.
#[test]
fn a_rough_volume_at_the_threshold_renders_as_the_smooth_one() {
    let l = 2.0;
    for mu in [1.0, 0.7, 0.3] {
        for inside in [false, true] {
            let passed = |alpha: f64| {
                let s = slab_in_a_furnace(alpha.sqrt(), mu, inside, l);
                let effective = s.effective_materials()[0].roughness.powi(2);
                assert_eq!(
                    spreads(effective, s.roughness_floor()),
                    alpha >= STRAIGHT_ALPHA,
                    "{effective}"
                );
                let (frame, lost) = render_reporting(&s);
                pixel(&frame, 0, 0).x / l + lost
            };
            let rough = passed(STRAIGHT_ALPHA * 1.01);
            let smooth = passed(STRAIGHT_ALPHA * 0.99);
            assert!(
                (rough - smooth).abs() <= 1e-4 + 1e-6,
                "μ {mu} inside {inside}: rough {rough} smooth {smooth}"
            );
        }
    }
}
