//! `shading.transmission`, `shading.transmission_layers`,
//! `shading.transmission_exit` and `shading.transmission_exit_ray`: how the GPU
//! draws light through surfaces (`KHR_materials_transmission`), its
//! knobs. The reference traces the light through and ignores both
//! (docs/transmission.md).

use crate::base::named_enum;

named_enum!(
    /// How the GPU draws a transmissive `gltf-pbr` material
    /// (src/gpu/transmission.rs).
    #[derive(Default)]
    TransmissionMode, "transmission" {
        /// In screen space, the Khronos glTF Sample Renderer's method: the
        /// opaque scene drawn first into an image with a mip chain, read
        /// where the refracted view ray leaves the volume, blurred by the
        /// roughness. The default.
        #[default]
        Screen = "screen",
        /// Not at all: the material is drawn as if opaque (its diffuse
        /// part whole), and `gonio render` warns.
        Off = "off",
    }
);

named_enum!(
    /// Where the GPU reads what a volume's refracted ray sees past the
    /// volume (shaders/transmission.wgsl, shaders/transmission_traced.wgsl).
    #[derive(Default)]
    TransmissionExitRay, "transmission exit ray" {
        /// At the projection of the point `thickness` along the ray
        /// refracted in: the Khronos glTF Sample Renderer's
        /// (getVolumeTransmissionRay). The default.
        #[default]
        Thickness = "thickness",
        /// Traced in screen space: the refracted ray marched against the
        /// volumes' back faces to its exit point, refracted out at the
        /// back face's normal and marched against the opaque scene's
        /// depth to what it meets (Wyman 2005's two interfaces;
        /// src/gpu/transmission_back_faces.rs).
        Traced = "traced",
    }
);

/// The most transmission layers a scene may ask for: each costs a
/// full-size image with its mip chain and a pass over the transmissive
/// objects behind.
pub const MAX_TRANSMISSION_LAYERS: u32 = 8;

/// The GPU's transmission knobs of a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TransmissionSettings {
    pub mode: TransmissionMode,
    /// Images of what lies behind, `1..=MAX_TRANSMISSION_LAYERS`: the
    /// transmissive objects sorted back to front, the `k`-th (from 0)
    /// reads the image of layer `min(k, layers − 1)`, which holds the
    /// opaque scene and every transmissive object of the layers before.
    /// 1 (the default): one image of the opaque scene, so glass behind
    /// glass is not seen; `layers ≥` the number of transmissive objects:
    /// each sees all those behind it (in the order of their centres).
    pub layers: u32,
    /// Whether the light leaving a volume (`thickness > 0`) crosses its
    /// second interface, weighted once more by `1 − max₃ F(μ_o)`: the
    /// exit's transmittance equals the entry's for a slab (parallel
    /// faces) and a sphere (the exit angle inside is the entry's
    /// refracted one), by the reciprocity of Fresnel transmission.
    /// `false`: one interface, as the Khronos glTF Sample Renderer.
    pub exit: bool,
    /// Where a volume's refracted ray is read past the volume.
    pub exit_ray: TransmissionExitRay,
}

impl Default for TransmissionSettings {
    fn default() -> Self {
        TransmissionSettings {
            mode: TransmissionMode::Screen,
            layers: 1,
            exit: true,
            exit_ray: TransmissionExitRay::Thickness,
        }
    }
}

impl TransmissionSettings {
    /// The layer the transmissive object at `rank` (0: the farthest)
    /// reads.
    pub fn layer_of(&self, rank: usize) -> usize {
        rank.min(self.layers.max(1) as usize - 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_nearest_objects_share_the_last_layer() {
        let s = TransmissionSettings {
            layers: 3,
            ..Default::default()
        };
        let layers: Vec<_> = (0..5).map(|r| s.layer_of(r)).collect();
        assert_eq!(layers, [0, 1, 2, 2, 2]);
        assert_eq!(TransmissionSettings::default().layer_of(4), 0);
        assert_eq!("off".parse::<TransmissionMode>(), Ok(TransmissionMode::Off));
        assert!("ssr".parse::<TransmissionMode>().is_err());
        assert_eq!(
            "traced".parse::<TransmissionExitRay>(),
            Ok(TransmissionExitRay::Traced)
        );
        assert_eq!(
            TransmissionSettings::default().exit_ray,
            TransmissionExitRay::Thickness
        );
    }
}
