//! Textures kept from one offscreen render to the next on the same
//! device: the radiance and depth targets and the shadow-map array.
//!
//! Why: lavapipe (and any CPU device) backs a texture with fresh host
//! memory, and the kernel hands out that memory a 4 KiB page at a time,
//! zeroed, on first touch. A render that allocates its textures anew pays
//! that first touch inside its passes: the shadow passes' clears fault in
//! 16 MiB per 2048² layer, the scene pass 41 MiB of 1080p targets. In
//! `gonio bench`, which renders the same scene many times, that was about
//! half of the four-shadowed-light frame (measured: 392 ms whole frame
//! with fresh textures, 202 ms with the process's freed memory reused,
//! 2026-12-03, docs/bench/report.md). Reusing the textures costs no
//! image: every pass that uses them clears what it reads (the scene pass
//! both targets, each drawn shadow layer its first pass; a skipped layer
//! is never read, see [`super::shadow_maps::ShadowMaps`]).
//!
//! The pool holds at most one texture per role (its label), so it never
//! holds more than one render's textures: a request that does not match
//! the held texture of its role drops it before making the new one, and
//! a render empties the pool of what it did not take before its passes
//! (a multisampled target after an MSAA render, shadow maps after a
//! shadowed one), so what is held never adds to a render's peak.
//! Only one-shot renders give their textures back
//! ([`super::offscreen`]); the viewer keeps its own across frames.

use std::collections::HashMap;
use std::sync::Mutex;

/// One device's textures between renders, one per role.
#[derive(Default)]
pub struct TexturePool {
    held: Mutex<HashMap<&'static str, wgpu::Texture>>,
}

impl TexturePool {
    /// A texture as `desc` describes it (its label is its role): the one
    /// held for that role if it matches, else a new one (the held one is
    /// dropped first, so its memory is free before the new is made).
    pub fn take(&self, device: &wgpu::Device, desc: &TextureRequest<'_>) -> wgpu::Texture {
        let held = self.lock().remove(desc.role);
        match held {
            Some(texture) if desc.matches(&texture) => texture,
            stale => {
                drop(stale);
                device.create_texture(&desc.descriptor())
            }
        }
    }

    /// Keeps `texture` for the next request of `role`, in place of any
    /// texture held for it.
    pub fn give(&self, role: &'static str, texture: wgpu::Texture) {
        self.lock().insert(role, texture);
    }

    /// How many textures are held (one per role at most).
    pub fn len(&self) -> usize {
        self.lock().len()
    }

    /// Whether no texture is held.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The texture held for `role`, if any (it stays held).
    pub fn held(&self, role: &str) -> Option<wgpu::Texture> {
        self.lock().get(role).cloned()
    }

    /// Drops every held texture (their memory goes back to the device).
    pub fn clear(&self) {
        self.lock().clear();
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, HashMap<&'static str, wgpu::Texture>> {
        // A panic while the map was held cannot leave it half-changed
        // (insert and remove are whole), so a poisoned lock is usable.
        self.held.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// What a render asks of the pool: a 2D texture (array) of one role.
#[derive(Clone, Copy, Debug)]
pub struct TextureRequest<'a> {
    /// The texture's label and its slot in the pool.
    pub role: &'static str,
    pub size: wgpu::Extent3d,
    pub format: wgpu::TextureFormat,
    pub usage: wgpu::TextureUsages,
    pub sample_count: u32,
    pub view_formats: &'a [wgpu::TextureFormat],
}

impl TextureRequest<'_> {
    fn descriptor(&self) -> wgpu::TextureDescriptor<'_> {
        wgpu::TextureDescriptor {
            label: Some(self.role),
            size: self.size,
            mip_level_count: 1,
            sample_count: self.sample_count,
            dimension: wgpu::TextureDimension::D2,
            format: self.format,
            usage: self.usage,
            view_formats: self.view_formats,
        }
    }

    /// Whether `texture` is what this request would make.
    fn matches(&self, texture: &wgpu::Texture) -> bool {
        texture.size() == self.size
            && texture.format() == self.format
            && texture.usage() == self.usage
            && texture.sample_count() == self.sample_count
            && texture.mip_level_count() == 1
            && texture.dimension() == wgpu::TextureDimension::D2
            && self.view_formats.is_empty()
    }
}
