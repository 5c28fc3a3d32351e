//! The paths light takes through transmissive surfaces, traced backwards
//! from the viewer: [`through`] is the radiance that arrives through a
//! surface the camera (or an earlier path) sees.
//!
//! * A thin wall (`thickness = 0`) passes light straight on, no
//!   refraction: along the directions and weights of [`super::thin`],
//!   plus the direct light of every light behind it, `f_t E |cos θ| V`.
//! * A volume's boundary (`thickness > 0` with `transmission > 0`, a
//!   closed mesh with outward normals) refracts by Snell's law at the
//!   shading normal, splits by the exact dielectric Fresnel reflectance
//!   `F` between the indices on both sides (`interface::Media`, nested
//!   volumes included), is tinted by `(1 − m) T b` at each crossing (the
//!   base colour acts "as if the object is covered with a coloured
//!   transparent foil", `KHR_materials_volume`), and attenuates by
//!   Beer–Lambert over the true length of each segment inside. Entering,
//!   the refracted ray is followed (the reflection off the outside is the
//!   surface's own `F·S` term, which the reflection equation already
//!   gives); leaving, both the refracted ray and the internal reflection
//!   (all of it at total internal reflection).
//! * A rough boundary (the material's own GGX `α = r²` at least
//!   [`super::thin::STRAIGHT_ALPHA`], [`super::thin::spreads`]) at a
//!   path's first crossing (`depth 0`: the surface the camera sees)
//!   spreads the path instead over the directions of
//!   [`super::rough_boundary`]: the rough dielectric BSDF of Walter et
//!   al. 2007, at the rendered `α` (the pixel's roughness floor
//!   included), at [`super::visible_normals::LOBE_SAMPLES`] visible
//!   normals, each split by its own `F` into the refracted and, leaving,
//!   the reflected ray (the media and the tint as above). Each of those
//!   paths crosses the next rough boundary it meets (a sphere's exit, a
//!   slab's far face) along one normal of its own
//!   ([`super::visible_normals::second_point`] of its stratum), split the
//!   same way; crossings after that are smooth, as a thin wall seen
//!   through another goes straight on. So a rough volume costs at most
//!   `LOBE_SAMPLES` paths (leaving: twice that), each as long as a smooth
//!   one. An interface between equal indices stays smooth at any
//!   roughness: there is no interface (`F = 0`, the ray straight on),
//!   where the microfacet model's masking would lose `1 − G2/G1` of light
//!   that no facet turns.
//! * A dispersive volume (`dispersion > 0`) splits the path where it is
//!   entered into the wavelengths of [`super::spectrum`], each traced with
//!   its own `n(λ)` through every medium after it.
//!
//! A path ends after [`MAX_DEPTH`] crossings, or where its weight falls
//! below [`MIN_WEIGHT`]; the weight it carried then is not traced and is
//! summed into [`Traced::lost`] (the share of a unit radiance behind that
//! may be missing, an upper bound of the error).
//!
//! Light reaches a surface directly only along unblocked shadow rays:
//! transmissive surfaces block shadow rays like opaque ones (no light
//! through glass onto what lies behind it, no caustics), as the GPU's
//! shadow maps do.

use super::interface::{Media, Medium, reflect};
use super::rough_boundary::{self, Boundary, rough_boundary_samples, second_crossing_samples};
use super::spectrum;
use super::thin::{spreads, thin_samples};
use crate::base::Rgb;
use crate::material::Material;
use crate::material::brdf::SurfaceFrame;
use crate::material::brdf::fresnel::fresnel_dielectric;
use crate::material::brdf::gltf_layers::transmission::gltf_transmitted;
use crate::material::brdf::gltf_layers::volume_btdf::refract;
use crate::scene::Light;
use crate::scene::camera::Ray;
use glam::DVec3;
use std::borrow::Cow;
use std::cell::Cell;

/// Crossings along one path before it is cut.
pub const MAX_DEPTH: u32 = 24;

/// A path whose weight (the largest channel of what it carries to the
/// pixel) falls below this is cut.
pub const MIN_WEIGHT: f64 = 1e-5;

/// Where a ray meets a surface.
pub struct Crossing<'a> {
    /// The mesh it belongs to.
    pub mesh: usize,
    /// The ray that found it, and its distance along it.
    pub ray: Ray,
    pub t: f64,
    pub point: DVec3,
    /// The shading frame (interpolated normal, normal map applied), its
    /// normal on the mesh's front side.
    pub frame: SurfaceFrame,
    /// The face's geometric normal (front side).
    pub face: DVec3,
    /// The material at the point (textures applied).
    pub material: Cow<'a, Material>,
}

/// What the paths need to know about the scene (the reference renderer
/// provides it).
pub trait Scenery {
    /// The closest surface along `ray` beyond `t_min`, both faces of a
    /// volume's boundary, what alpha MASK cuts out passed through.
    fn cross(&self, ray: &Ray, t_min: f64) -> Option<Crossing<'_>>;
    /// The radiance the surface at `c` reflects and emits back along
    /// `c.ray` (the reflection equation; 0 seen from inside a volume).
    fn surface_radiance(&self, c: &Crossing) -> Rgb;
    /// What a ray that leaves the scene sees.
    fn background(&self, direction: DVec3) -> Rgb;
    /// The scene's ray offset (`reference::shadow_epsilon`): a path's
    /// next ray starts at the crossing itself and ignores hits closer
    /// than it, so segment lengths (Beer–Lambert's path) are exact.
    fn epsilon(&self) -> f64;
    /// The view's roughness floor (`Scene::roughness_floor`), which the
    /// crossings' materials include: a lobe is sampled where the
    /// material's own width, without it, [`spreads`].
    fn roughness_floor(&self) -> f64;
    fn lights(&self) -> &[Light];
    /// `V_l` of light `l` at `x` (the shadow ray leaves on the light's
    /// side of `face`).
    fn light_visible(&self, l: usize, x: DVec3, face: DVec3) -> f64;
}

/// The light through a surface and how much of it was not traced.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Traced {
    pub radiance: Rgb,
    /// The summed weight of the paths cut (bounce limit or negligible
    /// weight): the largest radiance that may be missing, per unit
    /// radiance behind.
    pub lost: f64,
}

/// The light that arrives through the surface at `c` towards `c.ray`'s
/// origin (not its own reflection), from outside every volume.
pub fn through<S: Scenery>(scenery: &S, c: &Crossing) -> Traced {
    through_in(scenery, c, &Media::default())
}

/// [`through`] for a ray travelling in `media`.
pub fn through_in<S: Scenery>(scenery: &S, c: &Crossing, media: &Media) -> Traced {
    let tracer = Tracer {
        scenery,
        lost: Cell::new(0.0),
    };
    let path = Path {
        weight: 1.0,
        depth: 0,
        lambda: None,
        stratum: None,
    };
    let radiance = tracer.through(c, media, path);
    Traced {
        radiance,
        lost: tracer.lost.get(),
    }
}

/// What the path so far carries, how deep it is, its wavelength (`None`
/// until a dispersive medium splits it), and the stratum of the first
/// rough crossing that spread it, until its second rough crossing takes
/// that stratum's point (`None` before the first and after the second).
#[derive(Clone, Copy, Debug)]
struct Path {
    weight: f64,
    depth: u32,
    lambda: Option<f64>,
    stratum: Option<u32>,
}

impl Path {
    fn next(self, weight: f64) -> Path {
        Path {
            weight: self.weight * weight,
            depth: self.depth + 1,
            ..self
        }
    }
}

struct Tracer<'s, S: Scenery> {
    scenery: &'s S,
    lost: Cell<f64>,
}

impl<S: Scenery> Tracer<'_, S> {
    /// The radiance seen along `ray` travelling in `media`: the surface it
    /// meets (its reflection, unless seen from inside its volume, and what
    /// comes through it) or the background, attenuated over the segment.
    fn seen(&self, ray: Ray, media: &Media, path: Path) -> Rgb {
        let s = self.scenery;
        let Some(c) = s.cross(&ray, s.epsilon()) else {
            let kept = media
                .current()
                .map_or(Rgb::ONE, |m| m.transmittance(f64::INFINITY));
            return kept * s.background(ray.direction);
        };
        let kept = media.current().map_or(Rgb::ONE, |m| m.transmittance(c.t));
        let path = Path {
            weight: path.weight * kept.max_element(),
            ..path
        };
        let inside = c.material.layers.is_volume() && leaves(&c);
        let own = if inside {
            Rgb::ZERO
        } else {
            s.surface_radiance(&c)
        };
        kept * (own + self.through(&c, media, path))
    }

    /// The light through the surface at `c` (module doc).
    fn through(&self, c: &Crossing, media: &Media, path: Path) -> Rgb {
        let layers = &c.material.layers;
        if !layers.transmits() {
            return Rgb::ZERO;
        }
        if path.depth >= MAX_DEPTH || path.weight < MIN_WEIGHT {
            self.lost.set(self.lost.get() + path.weight);
            return Rgb::ZERO;
        }
        if layers.is_volume() {
            let entering = !leaves(c);
            let dispersive = layers.dispersion > 0.0;
            if entering && dispersive && path.lambda.is_none() {
                let weights = spectrum::weights();
                let share = 1.0 / weights.len() as f64;
                let sum = weights.iter().fold(Rgb::ZERO, |sum, &(lambda, w)| {
                    let p = Path {
                        weight: path.weight * share,
                        lambda: Some(lambda),
                        ..path
                    };
                    sum + w * self.boundary(c, media, p)
                });
                return sum.max(Rgb::ZERO);
            }
            self.boundary(c, media, path)
        } else {
            self.thin(c, media, path)
        }
    }

    /// A thin wall: straight on along the lobes' samples, plus the lights
    /// behind it.
    fn thin(&self, c: &Crossing, media: &Media, path: Path) -> Rgb {
        let s = self.scenery;
        let m = &c.material;
        let wo = -c.ray.direction;
        let frame = facing(&c.frame, wo);
        let mut sum = Rgb::ZERO;
        let floor = s.roughness_floor();
        for sample in thin_samples(m, &frame, wo, path.depth == 0, floor) {
            let ray = Ray {
                origin: c.point,
                direction: sample.direction,
            };
            let w = sample.weight.max_element();
            if w > 0.0 {
                sum += sample.weight * self.seen(ray, media, path.next(w));
            }
        }
        for (l, light) in s.lights().iter().enumerate() {
            let incidence = light.incidence(c.point);
            let cos = frame.n.dot(incidence.wi);
            if cos >= 0.0 {
                continue;
            }
            let f_t = gltf_transmitted(
                m.base_color,
                m.metallic,
                m.roughness,
                &m.layers,
                0.0,
                0.0,
                frame.n,
                incidence.wi,
                wo,
            );
            if f_t == Rgb::ZERO {
                continue;
            }
            let v = s.light_visible(l, c.point, c.face);
            sum += f_t * incidence.irradiance * (-cos * v);
        }
        sum
    }

    /// A volume's boundary: refraction and internal reflection, sampled
    /// by the rough BSDF where the module doc says, smooth elsewhere.
    fn boundary(&self, c: &Crossing, media: &Media, path: Path) -> Rgb {
        let m = &c.material;
        let medium = Medium::of(m, c.mesh);
        let leaving = leaves(c);
        let (eta_i, after) = if leaving {
            let after = media.left(c.mesh);
            (medium.ior_at(path.lambda), after)
        } else {
            (media.ior_at(path.lambda), media.entered(medium))
        };
        let eta_t = if leaving {
            after.ior_at(path.lambda)
        } else {
            medium.ior_at(path.lambda)
        };
        let wi = -c.ray.direction;
        // The shading normal on the incoming side; the face's where the
        // interpolated normal points the other way.
        let face_in = if c.face.dot(wi) < 0.0 {
            -c.face
        } else {
            c.face
        };
        let mut n = if c.frame.n.dot(wi) < 0.0 {
            -c.frame.n
        } else {
            c.frame.n
        };
        if n.dot(face_in) <= 0.0 || n.dot(wi) <= 0.0 {
            n = face_in;
        }
        let tint = m.base_color * (m.layers.transmission * (1.0 - m.metallic));
        let alpha = m.roughness * m.roughness;
        let floor = self.scenery.roughness_floor();
        let rough = spreads(alpha, floor) && eta_i != eta_t;
        if rough && (path.depth == 0 || path.stratum.is_some()) {
            let frame = SurfaceFrame::new(n, c.frame.t);
            let b = Boundary {
                frame: &frame,
                face: face_in,
                wi,
                alpha,
                etas: (eta_i, eta_t),
                reflections: leaving,
            };
            let samples = match path.stratum {
                Some(k) => second_crossing_samples(&b, k),
                None => rough_boundary_samples(&b),
            };
            return self.rough(c, &samples, tint, (media, &after), path);
        }
        let cos_i = n.dot(wi);
        let refracted = refract(wi, n, eta_i, eta_t).filter(|d| d.dot(face_in) < 0.0);
        let f = match refracted {
            Some(_) => fresnel_dielectric(cos_i, eta_i, eta_t),
            None => 1.0,
        };
        let mut sum = Rgb::ZERO;
        if let Some(d) = refracted {
            let w = tint * (1.0 - f);
            if w.max_element() > 0.0 {
                let ray = Ray {
                    origin: c.point,
                    direction: d,
                };
                sum += w * self.seen(ray, &after, path.next(w.max_element()));
            }
        }
        if leaving && f > 0.0 {
            let r = reflect(wi, n);
            let r = if r.dot(face_in) > 0.0 {
                r
            } else {
                reflect(wi, face_in)
            };
            let ray = Ray {
                origin: c.point,
                direction: r,
            };
            sum += f * self.seen(ray, media, path.next(f));
        }
        sum
    }

    /// A rough boundary's sampled directions (`super::rough_boundary`):
    /// the refracted ones into `after` tinted as at the smooth boundary,
    /// the reflected ones back into `before`. After a path's first rough
    /// crossing each of its paths keeps its sample's stratum for its
    /// second; after the second (`path` carried a stratum), none.
    fn rough(
        &self,
        c: &Crossing,
        samples: &[rough_boundary::Sample],
        tint: Rgb,
        (before, after): (&Media, &Media),
        path: Path,
    ) -> Rgb {
        let mut sum = Rgb::ZERO;
        for s in samples {
            let (w, media) = if s.refracted {
                (tint * s.weight, after)
            } else {
                (Rgb::splat(s.weight), before)
            };
            if w.max_element() > 0.0 {
                let ray = Ray {
                    origin: c.point,
                    direction: s.direction,
                };
                let next = Path {
                    stratum: match path.stratum {
                        Some(_) => None,
                        None => Some(s.stratum),
                    },
                    ..path.next(w.max_element())
                };
                sum += w * self.seen(ray, media, next);
            }
        }
        sum
    }
}

/// Whether the ray at `c` leaves the closed mesh (meets a face from its
/// back).
fn leaves(c: &Crossing) -> bool {
    c.ray.direction.dot(c.face) > 0.0
}

/// `frame` turned so that its normal faces `w`.
fn facing(frame: &SurfaceFrame, w: DVec3) -> SurfaceFrame {
    if frame.n.dot(w) >= 0.0 {
        *frame
    } else {
        SurfaceFrame::new(-frame.n, -frame.t)
    }
}

/// The refracted path of `ray` alone (no internal reflections): the ray
/// of every segment, from `ray` itself to the one that leaves the last
/// volume, for wavelength `lambda` (`None`: each medium's `n_d`); the
/// path stops at total internal reflection, after [`MAX_DEPTH`]
/// crossings, or where a segment meets an opaque surface or nothing.
/// What the tests of refraction (a ball lens, a prism) measure.
pub fn refracted_path<S: Scenery>(scenery: &S, ray: Ray, lambda: Option<f64>) -> Vec<Ray> {
    let mut rays = vec![ray];
    let mut media = Media::default();
    let mut ray = ray;
    for _ in 0..MAX_DEPTH {
        let Some(c) = scenery.cross(
            &ray,
            if rays.len() == 1 {
                0.0
            } else {
                scenery.epsilon()
            },
        ) else {
            break;
        };
        let layers = &c.material.layers;
        if !layers.is_volume() {
            break;
        }
        let medium = Medium::of(&c.material, c.mesh);
        let leaving = leaves(&c);
        let after = if leaving {
            media.left(c.mesh)
        } else {
            media.entered(medium)
        };
        let (eta_i, eta_t) = if leaving {
            (medium.ior_at(lambda), after.ior_at(lambda))
        } else {
            (media.ior_at(lambda), medium.ior_at(lambda))
        };
        let wi = -ray.direction;
        let face_in = if c.face.dot(wi) < 0.0 {
            -c.face
        } else {
            c.face
        };
        let n = if c.frame.n.dot(face_in) > 0.0 {
            c.frame.n
        } else {
            -c.frame.n
        };
        let n = if n.dot(wi) > 0.0 { n } else { face_in };
        let Some(d) = refract(wi, n, eta_i, eta_t).filter(|d| d.dot(face_in) < 0.0) else {
            break;
        };
        ray = Ray {
            origin: c.point,
            direction: d,
        };
        rays.push(ray);
        media = after;
        if media.current().is_none() {
            break;
        }
    }
    rays
}
