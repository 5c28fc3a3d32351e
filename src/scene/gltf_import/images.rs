//! glTF textures: the images (a buffer view, a base64 `data:` URI, or a
//! file inside the glTF's folder, under the same rules as buffers), the
//! samplers (glTF's default when a texture has none), `texCoord` and
//! `KHR_texture_transform`, as a [`MaterialTexture`] for a parameter.
//! Images are decoded once per encoding, within the limits
//! (`scene::texture::store`).

use super::buffers::{confine, decode_base64_uri, has_scheme, percent_decode, relative_path};
use crate::material::texture::{MaterialTexture, Sampler, TextureTarget, UvTransform};
use crate::scene::limits::read_regular_file;
use crate::scene::texture::{Encoding, store::ImageStore};
use glam::DVec2;
use std::borrow::Cow;
use std::path::Path;

/// A glTF `textureInfo` as an extension's raw JSON holds it (glTF 2.0,
/// 5.22 textureInfo; `normalTextureInfo`'s `scale` too). Unknown members (`extras`) are allowed, as glTF allows
/// them.
#[derive(Clone, Debug, serde::Deserialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct RawTextureInfo {
    pub index: usize,
    #[serde(default)]
    pub tex_coord: u32,
    /// `normalTextureInfo.scale` (default 1), for a coat's normal map.
    #[serde(default = "one")]
    pub scale: f64,
    #[serde(default)]
    pub extensions: Option<serde_json::Map<String, serde_json::Value>>,
}

fn one() -> f64 {
    1.0
}

/// An image computed from a file's image texel by texel, in linear
/// values before the mip chain (`ImageStore::load_bytes_mapped`), where a
/// glTF texture means something other than a factor of the parameter it
/// sets (`1 − A`, `mix(min, max, G)`); `label` names the derivation (the
/// store keeps the file's image and each derivation apart).
pub(super) struct Derived<'f> {
    pub label: String,
    pub map: &'f dyn Fn(&mut [f32; 4]),
}

/// Where the images of one file come from and go to.
pub(super) struct ImageSource<'a> {
    pub buffers: &'a [Cow<'a, [u8]>],
    pub folder: &'a Path,
    pub store: ImageStore,
}

impl<'a> ImageSource<'a> {
    /// The texture of `info` on parameter `key`, its image read as
    /// `encoding`, reading channel `channel` when the parameter is a
    /// scalar. Errors name the texture and the image.
    pub fn texture(
        &mut self,
        info: &gltf::texture::Info,
        key: &'static str,
        encoding: Encoding,
        channel: usize,
    ) -> Result<MaterialTexture, String> {
        let mut t = self.texture_of(
            &info.texture(),
            info.tex_coord(),
            TextureTarget::Param(key),
            encoding,
        )?;
        t.channel = channel;
        if let Some(transform) = info.texture_transform() {
            let at = format!("texture {}", info.texture().index());
            let [ox, oy] = transform.offset();
            let [sx, sy] = transform.scale();
            t.transform = UvTransform {
                offset: DVec2::new(ox.into(), oy.into()),
                rotation: transform.rotation().into(),
                scale: DVec2::new(sx.into(), sy.into()),
            };
            if let Some(set) = transform.tex_coord() {
                t.tex_coord = set as usize;
            }
            let finite = t.transform.offset.is_finite()
                && t.transform.scale.is_finite()
                && t.transform.rotation.is_finite();
            if !finite || t.tex_coord > 1 {
                return Err(format!(
                    "{at}: KHR_texture_transform is not finite or reads a set past TEXCOORD_1"
                ));
            }
        }
        Ok(t)
    }

    /// The texture a raw `textureInfo` object names (one inside a
    /// material extension the `gltf` crate does not parse): its `index`
    /// checked against the file's textures, its `texCoord` and its
    /// `KHR_texture_transform`, read as [`Self::texture_with_raw_transform`]
    /// reads them; the image as `derived` computes it from the file's, if
    /// given.
    pub fn raw_texture(
        &mut self,
        document: &gltf::Document,
        info: &RawTextureInfo,
        target: TextureTarget,
        encoding: Encoding,
        derived: Option<Derived>,
    ) -> Result<MaterialTexture, String> {
        let count = document.textures().len();
        let texture = document.textures().nth(info.index).ok_or_else(|| {
            format!(
                "texture {} does not exist (the file has {count})",
                info.index
            )
        })?;
        let transform = info
            .extensions
            .as_ref()
            .and_then(|e| e.get("KHR_texture_transform"));
        self.transformed(
            &texture,
            info.tex_coord,
            target,
            encoding,
            transform,
            derived,
        )
    }

    /// [`Self::texture_of`] with the `KHR_texture_transform` found in the
    /// texture reference's raw `extensions` (`extension`: the normal and
    /// occlusion textures', which the `gltf` crate does not parse; the
    /// same fields and checks as [`Self::texture`]'s).
    pub fn texture_with_raw_transform(
        &mut self,
        texture: &gltf::Texture,
        tex_coord: u32,
        target: TextureTarget,
        encoding: Encoding,
        extension: Option<&serde_json::Value>,
    ) -> Result<MaterialTexture, String> {
        self.transformed(texture, tex_coord, target, encoding, extension, None)
    }

    fn transformed(
        &mut self,
        texture: &gltf::Texture,
        tex_coord: u32,
        target: TextureTarget,
        encoding: Encoding,
        extension: Option<&serde_json::Value>,
        derived: Option<Derived>,
    ) -> Result<MaterialTexture, String> {
        let mut t = self.texture_derived(texture, tex_coord, target, encoding, derived)?;
        let Some(value) = extension else {
            return Ok(t);
        };
        let at = format!("texture {}: KHR_texture_transform", texture.index());
        let pair = |key: &str, default: [f64; 2]| -> Result<DVec2, String> {
            match value.get(key) {
                None => Ok(DVec2::from(default)),
                Some(v) => {
                    let a = v
                        .as_array()
                        .filter(|a| a.len() == 2)
                        .and_then(|a| Some([a[0].as_f64()?, a[1].as_f64()?]))
                        .ok_or_else(|| format!("{at}: `{key}` is not two numbers"))?;
                    Ok(DVec2::from(a))
                }
            }
        };
        let rotation = match value.get("rotation") {
            None => 0.0,
            Some(v) => v
                .as_f64()
                .ok_or_else(|| format!("{at}: `rotation` is not a number"))?,
        };
        t.transform = UvTransform {
            offset: pair("offset", [0.0, 0.0])?,
            rotation,
            scale: pair("scale", [1.0, 1.0])?,
        };
        if let Some(set) = value.get("texCoord") {
            t.tex_coord = set
                .as_u64()
                .ok_or_else(|| format!("{at}: `texCoord` is not an index"))?
                as usize;
        }
        let finite = t.transform.offset.is_finite()
            && t.transform.scale.is_finite()
            && t.transform.rotation.is_finite();
        if !finite || t.tex_coord > 1 {
            return Err(format!("{at} is not finite or reads a set past TEXCOORD_1"));
        }
        Ok(t)
    }

    /// glTF texture `texture` read from `TEXCOORD_{tex_coord}` for
    /// `target`, without a UV transform.
    pub fn texture_of(
        &mut self,
        texture: &gltf::Texture,
        tex_coord: u32,
        target: TextureTarget,
        encoding: Encoding,
    ) -> Result<MaterialTexture, String> {
        self.texture_derived(texture, tex_coord, target, encoding, None)
    }

    /// [`Self::texture_of`], its image derived from the file's by
    /// `derived` when given.
    pub fn texture_derived(
        &mut self,
        texture: &gltf::Texture,
        tex_coord: u32,
        target: TextureTarget,
        encoding: Encoding,
        derived: Option<Derived>,
    ) -> Result<MaterialTexture, String> {
        let at = format!("texture {}", texture.index());
        let tex_coord = tex_coord as usize;
        if tex_coord > 1 {
            return Err(format!(
                "{at} reads TEXCOORD_{tex_coord}; gonio reads TEXCOORD_0 and TEXCOORD_1"
            ));
        }
        let image = self
            .image(&texture.source(), encoding, derived)
            .map_err(|e| format!("{at}: {e}"))?;
        let s = texture.sampler();
        let sampler = Sampler::from_gltf(
            s.mag_filter().map(|f| f.as_gl_enum()),
            s.min_filter().map(|f| f.as_gl_enum()),
            s.wrap_s().as_gl_enum(),
            s.wrap_t().as_gl_enum(),
        )
        .map_err(|e| format!("{at}: sampler: {e}"))?;
        Ok(MaterialTexture {
            target,
            image,
            channel: 0,
            tex_coord,
            transform: UvTransform::default(),
            sampler,
        })
    }

    /// The index of glTF image `image` decoded as `encoding`.
    fn image(
        &mut self,
        image: &gltf::Image,
        encoding: Encoding,
        derived: Option<Derived>,
    ) -> Result<usize, String> {
        let index = image.index();
        let name = image.name().map_or_else(
            || format!("image {index}"),
            |n| format!("image {index} (\"{n}\")"),
        );
        let bytes =
            image_bytes(self.buffers, self.folder, image).map_err(|e| format!("{name} {e}"))?;
        // A decoding error names the image file too, when there is one.
        let shown = match image.source() {
            gltf::image::Source::Uri { uri, .. }
                if !uri
                    .get(..5)
                    .is_some_and(|s| s.eq_ignore_ascii_case("data:")) =>
            {
                format!("{name} (uri \"{}\")", super::hostile::abbreviate(uri))
            }
            _ => name.clone(),
        };
        let stored = format!("{}:{name}", self.folder.display());
        match derived {
            None => self.store.load_bytes(stored, &bytes, encoding),
            Some(d) => self.store.load_bytes_mapped(
                format!("{stored} as {}", d.label),
                &bytes,
                encoding,
                d.map,
            ),
        }
        .map_err(|e| format!("{shown}: {e}"))
    }
}

/// Checks what the `gltf` crate unwraps when an image's source is asked
/// for: an image has a `uri` or a `bufferView`, and a `bufferView` comes
/// with a `mimeType` (glTF 2.0, 5.18 image). Without this,
/// `"images": [{}]` panicked inside the crate.
pub(super) fn check_sources(json: &gltf::json::Root) -> Result<(), String> {
    for (index, image) in json.images.iter().enumerate() {
        match (&image.uri, &image.buffer_view, &image.mime_type) {
            (None, None, _) => {
                return Err(format!(
                    "image {index} has neither a uri nor a bufferView; glTF requires exactly one (glTF 2.0, 5.18)"
                ));
            }
            (Some(_), Some(_), _) => {
                return Err(format!(
                    "image {index} has both a uri and a bufferView; glTF requires exactly one (glTF 2.0, 5.18)"
                ));
            }
            (None, Some(_), None) => {
                return Err(format!(
                    "image {index} has a bufferView but no mimeType, which glTF requires with a bufferView (glTF 2.0, 5.18)"
                ));
            }
            _ => {}
        }
    }
    Ok(())
}

/// An image's encoded bytes; errors follow "image N ...".
fn image_bytes<'a>(
    buffers: &'a [Cow<'a, [u8]>],
    folder: &Path,
    image: &gltf::Image,
) -> Result<Cow<'a, [u8]>, String> {
    match image.source() {
        gltf::image::Source::View { view, .. } => {
            let buffer = &buffers[view.buffer().index()];
            let (start, length) = (view.offset(), view.length());
            let end = start.checked_add(length).filter(|&e| e <= buffer.len());
            match end {
                Some(end) => Ok(Cow::Borrowed(&buffer[start..end])),
                None => Err(format!(
                    "has buffer view {} (bytes {start}.. +{length}) past the end of buffer {} ({} bytes)",
                    view.index(),
                    view.buffer().index(),
                    buffer.len()
                )),
            }
        }
        gltf::image::Source::Uri { uri, .. } => {
            let shown = super::hostile::abbreviate(uri);
            if uri
                .get(..5)
                .is_some_and(|s| s.eq_ignore_ascii_case("data:"))
            {
                return decode_base64_uri(uri)
                    .map(Cow::Owned)
                    .map_err(|e| format!("(uri \"{shown}\") {e}"));
            }
            if has_scheme(uri) {
                return Err(format!(
                    "(uri \"{shown}\") has a URI scheme; images must be relative file references, data: URIs or buffer views"
                ));
            }
            let reference = uri.split(['?', '#']).next().unwrap_or_default();
            let path = percent_decode(reference)
                .and_then(|p| relative_path(&p))
                .and_then(|rel| confine(folder, &rel))
                .map_err(|e| format!("(uri \"{shown}\") {e}"))?;
            read_regular_file(&path, 1 << 32)
                .map(Cow::Owned)
                .map_err(|e| format!("(uri \"{shown}\", {}) {e}", path.display()))
        }
    }
}
