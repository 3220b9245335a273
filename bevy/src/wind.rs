//! The wind: a material extension of Bevy's `StandardMaterial` whose vertex stage (main pass
//! and shadows) sways branches and flutters leaf cards from the wind data sylva's meshes carry.

use bevy::mesh::{MeshVertexAttribute, MeshVertexBufferLayoutRef, VertexFormat};
use bevy::pbr::{
    ExtendedMaterial, MaterialExtension, MaterialExtensionKey, MaterialExtensionPipeline,
};
use bevy::prelude::*;
use bevy::render::render_resource::{
    AsBindGroup, RenderPipelineDescriptor, SpecializedMeshPipelineError,
};
use bevy::shader::ShaderRef;

/// The wind data of a vertex, as sylva's meshes carry it (`sylva::turtle::Vertex::wind`): the
/// pivot its branch sways about in xyz, its hierarchy depth plus a phase in w.
pub const ATTRIBUTE_WIND: MeshVertexAttribute =
    MeshVertexAttribute::new("Sylva_Wind", 0x5359_4c56_4100_0001, VertexFormat::Float32x4);

/// The shader location the wind attribute is read at: above every location Bevy's PBR
/// vertex stages use (main pass and prepass).
const WIND_LOCATION: u32 = 8;

/// A sylva material: Bevy's PBR with the wind's vertex stage.
pub type WindMaterial = ExtendedMaterial<StandardMaterial, Wind>;

/// The wind a material sways in: `direction.xz` times strength, and the time in seconds in
/// `w` (the plugin advances it every frame).
#[derive(Asset, AsBindGroup, Reflect, Debug, Clone, Default)]
pub struct Wind {
    /// xz: the wind's direction times its strength (1: a breeze); w: time in seconds.
    #[uniform(100)]
    pub wind: Vec4,
}

impl MaterialExtension for Wind {
    fn vertex_shader() -> ShaderRef {
        "embedded://sylva_bevy/shaders/wind.wgsl".into()
    }

    fn prepass_vertex_shader() -> ShaderRef {
        "embedded://sylva_bevy/shaders/wind_prepass.wgsl".into()
    }

    fn specialize(
        _pipeline: &MaterialExtensionPipeline,
        descriptor: &mut RenderPipelineDescriptor,
        layout: &MeshVertexBufferLayoutRef,
        _key: MaterialExtensionKey<Self>,
    ) -> Result<(), SpecializedMeshPipelineError> {
        // Appended to the layout Bevy built for the base material, so its locations hold.
        if layout.0.contains(ATTRIBUTE_WIND) {
            let extra = layout
                .0
                .get_layout(&[ATTRIBUTE_WIND.at_shader_location(WIND_LOCATION)])?;
            if let Some(buffer) = descriptor.vertex.buffers.first_mut() {
                buffer.attributes.extend(extra.attributes);
            }
            descriptor.vertex.shader_defs.push("SYLVA_WIND".into());
        }
        Ok(())
    }
}
