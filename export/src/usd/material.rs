//! `UsdPreviewSurface` materials: a species' bark (tinted colour texture and normal map) and
//! leaf cards (tinted texture, alpha cut), the terrain (its vertex colours), and the PNG
//! images they read, written beside the USD file.

use std::path::Path;

use sylva_base::file::AtomicFile;
use sylva_forest::Species;

use super::text::{float, tuple};
use crate::error::ExportError;
use crate::texture::{Texture, card_alpha_cutoff};

/// Where a USD file's materials live.
pub(super) const MATERIALS: &str = "/Forest/Materials";

/// A species' two materials, by prim path, and the images they read, relative to the USD
/// file.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct SpeciesMaterials {
    pub(super) bark: String,
    pub(super) leaves: String,
    images: [String; 3],
}

impl SpeciesMaterials {
    /// The materials of `species`, named after `prim` (its name as an identifier), reading
    /// images from the folder `images` beside the USD file.
    pub(super) fn new(prim: &str, images: &str) -> SpeciesMaterials {
        SpeciesMaterials {
            bark: format!("{MATERIALS}/{prim}_bark"),
            leaves: format!("{MATERIALS}/{prim}_leaves"),
            images: [
                format!("{images}/{prim}_bark.png"),
                format!("{images}/{prim}_bark_normal.png"),
                format!("{images}/{prim}_leaves.png"),
            ],
        }
    }

    /// Writes the images of `species` under `folder` (the USD file's own folder), each whole
    /// or not at all; returns how many.
    pub(super) fn write_images(
        &self,
        species: &Species,
        folder: &Path,
    ) -> Result<usize, ExportError> {
        let pngs = [
            Texture::bark(species.bark_pattern).tinted(species.bark),
            Texture::bark_normal(species.bark_pattern),
            Texture::leaf(species.leaf_shape).tinted(species.leaf),
        ];
        for (relative, texture) in self.images.iter().zip(pngs) {
            let path = folder.join(relative);
            if let Some(parent) = path.parent() {
                std::fs::create_dir_all(parent).map_err(sylva_base::file::FileError::at(parent))?;
            }
            let mut file = AtomicFile::create(&path)?;
            file.put(&texture.png())?;
            file.commit()?;
        }
        Ok(self.images.len())
    }

    /// Appends both materials' prims at `indent` (inside the materials scope).
    pub(super) fn write(&self, out: &mut String, species: &Species, roughness: f32) {
        let [bark, normal, leaves] = &self.images;
        write_material(
            out,
            &self.bark,
            Surface {
                colour: Colour::Texture(bark, "repeat"),
                normal: Some(normal),
                cutoff: None,
                roughness,
                phenology: None,
            },
        );
        write_material(
            out,
            &self.leaves,
            Surface {
                colour: Colour::Texture(leaves, "clamp"),
                normal: None,
                cutoff: Some(card_alpha_cutoff(species.leaf_shape)),
                roughness,
                phenology: Some(species),
            },
        );
    }
}

/// Where a surface's colour comes from.
#[derive(Debug, Clone, Copy)]
enum Colour<'a> {
    /// An sRGB image (its alpha the opacity) and how it wraps (`repeat` for bark, `clamp` for
    /// leaf cards).
    Texture(&'a str, &'static str),
    /// The mesh's `displayColor` primvar.
    Vertices,
}

/// What a `UsdPreviewSurface` is given.
#[derive(Debug, Clone, Copy)]
struct Surface<'a> {
    colour: Colour<'a>,
    /// A tangent-space normal map (OpenGL's convention, as glTF's and USD's).
    normal: Option<&'a str>,
    /// Opacity below which the surface is cut away (leaf cards).
    cutoff: Option<f32>,
    roughness: f32,
    /// The species whose year a leaf material names in its `customData`.
    phenology: Option<&'a Species>,
}

/// The terrain's material at `path`: its vertices' colours (a preview surface has no colour
/// factor, so the terrain's tint is multiplied into them).
pub(super) fn write_terrain_material(out: &mut String, path: &str, roughness: f32) {
    write_material(
        out,
        path,
        Surface {
            colour: Colour::Vertices,
            normal: None,
            cutoff: None,
            roughness,
            phenology: None,
        },
    );
}

/// The texture-coordinate reader every texture of a material shares.
fn write_st_reader(out: &mut String, material: &str) -> String {
    out.push_str(concat!(
        "        def Shader \"Coordinates\"\n        {\n",
        "            uniform token info:id = \"UsdPrimvarReader_float2\"\n",
        "            string inputs:varname = \"st\"\n",
        "            float2 outputs:result\n        }\n",
    ));
    format!("{material}/Coordinates.outputs:result")
}

/// A `UsdUVTexture` shader `name` reading `file`; normal maps (`raw`) are scaled and biased
/// from [0, 1] to [-1, 1] as `UsdPreviewSurface` expects.
fn write_texture(out: &mut String, name: &str, file: &str, (wrap, raw): (&str, bool), st: &str) {
    out.push_str(&format!(
        "        def Shader \"{name}\"\n        {{\n            uniform token info:id = \"UsdUVTexture\"\n            asset inputs:file = @{file}@\n            float2 inputs:st.connect = <{st}>\n            token inputs:wrapS = \"{wrap}\"\n            token inputs:wrapT = \"{wrap}\"\n"
    ));
    if raw {
        out.push_str(concat!(
            "            token inputs:sourceColorSpace = \"raw\"\n",
            "            float4 inputs:scale = (2, 2, 2, 1)\n",
            "            float4 inputs:bias = (-1, -1, -1, 0)\n",
            "            float3 outputs:rgb\n        }\n",
        ));
    } else {
        out.push_str(concat!(
            "            token inputs:sourceColorSpace = \"sRGB\"\n",
            "            float outputs:a\n",
            "            float3 outputs:rgb\n        }\n",
        ));
    }
}

/// A material prim at `path` (under [`MATERIALS`]) with a `UsdPreviewSurface` and the
/// shaders feeding it.
fn write_material(out: &mut String, path: &str, surface: Surface) {
    let name = path.rsplit('/').next().unwrap_or(path);
    out.push_str(&format!("    def Material \"{name}\""));
    if let Some(species) = surface.phenology {
        write_phenology(out, species);
    }
    out.push_str(&format!(
        "\n    {{\n        token outputs:surface.connect = <{path}/Surface.outputs:surface>\n"
    ));
    let mut inputs = String::new();
    match surface.colour {
        Colour::Texture(file, wrap) => {
            let st = write_st_reader(out, path);
            write_texture(out, "Colour", file, (wrap, false), &st);
            inputs.push_str(&format!(
                "            color3f inputs:diffuseColor.connect = <{path}/Colour.outputs:rgb>\n"
            ));
            if let Some(normal) = surface.normal {
                write_texture(out, "Normal", normal, (wrap, true), &st);
                inputs.push_str(&format!(
                    "            normal3f inputs:normal.connect = <{path}/Normal.outputs:rgb>\n"
                ));
            }
            if let Some(cutoff) = surface.cutoff {
                inputs.push_str(&format!(
                    "            float inputs:opacity.connect = <{path}/Colour.outputs:a>\n            float inputs:opacityThreshold = "
                ));
                float(&mut inputs, cutoff);
                inputs.push('\n');
            }
        }
        Colour::Vertices => {
            out.push_str(concat!(
                "        def Shader \"Colour\"\n        {\n",
                "            uniform token info:id = \"UsdPrimvarReader_float3\"\n",
                "            string inputs:varname = \"displayColor\"\n",
                "            float3 inputs:fallback = (1, 1, 1)\n",
                "            float3 outputs:result\n        }\n",
            ));
            inputs.push_str(&format!(
                "            color3f inputs:diffuseColor.connect = <{path}/Colour.outputs:result>\n"
            ));
        }
    }
    out.push_str("        def Shader \"Surface\"\n        {\n            uniform token info:id = \"UsdPreviewSurface\"\n");
    out.push_str(&inputs);
    out.push_str("            float inputs:metallic = 0\n            float inputs:roughness = ");
    float(out, surface.roughness);
    out.push_str("\n            token outputs:surface\n        }\n    }\n");
}

/// A leaf material's metadata naming its species' year ([`crate::phenology::entries`], as
/// glTF's `sylva_phenology` extras; `primvars:sylva:phenology` holds each vertex's card order
/// and snow catch).
fn write_phenology(out: &mut String, species: &Species) {
    use crate::phenology::Value;
    out.push_str(" (\n        customData = {\n            dictionary sylva_phenology = {\n");
    for (name, value) in crate::phenology::entries(species) {
        out.push_str("                ");
        match value {
            Value::Flag(flag) => out.push_str(&format!("bool {name} = {}", u8::from(flag))),
            Value::Number(number) => {
                out.push_str(&format!("float {name} = "));
                float(out, number);
            }
            Value::Colour(colour) => {
                out.push_str(&format!("float3 {name} = "));
                tuple(out, &colour);
            }
        }
        out.push('\n');
    }
    out.push_str("            }\n        }\n    )");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn leaf_cards_are_cut_at_their_texture_s_cutoff_and_bark_has_a_normal_map() {
        let oak = Species::from_preset("sylva-oak", 2).unwrap();
        let m = SpeciesMaterials::new("oak", "forest_textures");
        let mut out = String::new();
        m.write(&mut out, &oak, 0.9);
        assert!(out.contains("def Material \"oak_bark\""));
        assert!(out.contains("def Material \"oak_leaves\""));
        assert!(out.contains("asset inputs:file = @forest_textures/oak_leaves.png@"));
        assert!(out.contains(
            "normal3f inputs:normal.connect = </Forest/Materials/oak_bark/Normal.outputs:rgb>"
        ));
        let cutoff = card_alpha_cutoff(oak.leaf_shape);
        let mut expected = String::from("float inputs:opacityThreshold = ");
        float(&mut expected, cutoff);
        assert!(out.contains(&expected), "{expected}");
        // Braces balance: every prim is closed.
        assert_eq!(out.matches('{').count(), out.matches('}').count());
    }
}
