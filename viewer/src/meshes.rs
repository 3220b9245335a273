//! The world's meshes on the GPU, uploaded once when a scene is shown: each species variant's
//! and proxy's vertices, per-vertex materials and bark and leaf indices, and the terrain with
//! the one placement it is drawn at.

use sylva::turtle::Vertex;

use crate::geometry::InstanceRaw;
use crate::gpu::{buffer, index_buffer};
use crate::materials::Materials;
use crate::scene::Scene;

/// One variant's (or proxy's) mesh: a vertex buffer shared by its bark and leaf draws.
pub(crate) struct VariantBuffers {
    pub(crate) vertices: wgpu::Buffer,
    /// Each vertex's material (an index into the material array): its variant's bark or
    /// leaf material.
    pub(crate) materials: wgpu::Buffer,
    /// Its bark triangles; none when it has no bark.
    pub(crate) bark: Option<wgpu::Buffer>,
    /// Its leaf triangles; none when it has no leaves.
    pub(crate) leaves: Option<wgpu::Buffer>,
}

impl VariantBuffers {
    /// Uploads a mesh whose `bark` indices take `bark_material` and every other vertex
    /// `leaf_material`.
    fn new(
        device: &wgpu::Device,
        vertices: &[Vertex],
        (bark, leaves): (&[u32], &[u32]),
        (bark_material, leaf_material): (u32, u32),
    ) -> VariantBuffers {
        let mut of_vertex = vec![leaf_material; vertices.len()];
        for &i in bark {
            of_vertex[i as usize] = bark_material;
        }
        VariantBuffers {
            vertices: buffer(
                device,
                "variant vertices",
                bytemuck::cast_slice(vertices),
                wgpu::BufferUsages::VERTEX,
            ),
            materials: buffer(
                device,
                "variant materials",
                bytemuck::cast_slice(&of_vertex),
                wgpu::BufferUsages::VERTEX,
            ),
            bark: index_buffer(device, "bark indices", bark),
            leaves: index_buffer(device, "leaf indices", leaves),
        }
    }
}

/// The terrain's mesh, in the trees' vertex layout, and the placement it is drawn at.
pub(crate) struct TerrainBuffers {
    pub(crate) vertices: wgpu::Buffer,
    /// Material 0 (the terrain) for each vertex.
    pub(crate) materials: wgpu::Buffer,
    pub(crate) indices: wgpu::Buffer,
    /// How many indices `indices` holds.
    pub(crate) count: u32,
    /// One placement that leaves the mesh where it is, whole and untinted.
    pub(crate) identity: wgpu::Buffer,
}

impl TerrainBuffers {
    /// Uploads `scene`'s terrain mesh, every vertex of it material 0.
    fn new(device: &wgpu::Device, scene: &Scene) -> TerrainBuffers {
        // The trees' vertex layout, with no wind: the shader leaves the terrain material
        // still.
        let vertices: Vec<Vertex> = scene
            .terrain_vertices
            .iter()
            .map(|t| Vertex {
                position: t.position,
                normal: t.normal,
                uv: t.uv,
                wind: [0.0; 4],
            })
            .collect();
        let identity = InstanceRaw {
            rotation: [0.0, 0.0, 0.0, 1.0],
            translation_scale: [0.0, 0.0, 0.0, 1.0],
            // Tint w is the fade between levels of detail: 0, whole.
            tint: [1.0, 1.0, 1.0, 0.0],
            tree: [0.0; 4],
        };
        TerrainBuffers {
            vertices: buffer(
                device,
                "terrain vertices",
                bytemuck::cast_slice(&vertices),
                wgpu::BufferUsages::VERTEX,
            ),
            materials: buffer(
                device,
                "terrain materials",
                bytemuck::cast_slice(&vec![0u32; vertices.len()]),
                wgpu::BufferUsages::VERTEX,
            ),
            indices: buffer(
                device,
                "terrain indices",
                bytemuck::cast_slice(&scene.terrain_indices),
                wgpu::BufferUsages::INDEX,
            ),
            count: scene.terrain_indices.len() as u32,
            identity: buffer(
                device,
                "identity instance",
                bytemuck::bytes_of(&identity),
                wgpu::BufferUsages::VERTEX,
            ),
        }
    }
}

/// Every mesh a frame may draw.
pub(crate) struct Meshes {
    /// The variants' meshes in the world's order, then the proxies' (the impostor cards):
    /// a draw's variant number indexes it.
    pub(crate) variants: Vec<VariantBuffers>,
    pub(crate) terrain: TerrainBuffers,
}

impl Meshes {
    /// Uploads `scene`'s meshes, each vertex naming its material in `materials`.
    pub(crate) fn new(device: &wgpu::Device, scene: &Scene, materials: &Materials) -> Meshes {
        let world = &scene.world;
        let variants = world
            .variants
            .iter()
            .zip(&materials.variants)
            .map(|(v, &m)| VariantBuffers::new(device, &v.vertices, (&v.bark, &v.leaves), m))
            .chain(world.proxies.iter().zip(&materials.proxies).map(|(p, &m)| {
                // An impostor card's vertices name its bark material (for the id mode).
                let vertices: Vec<Vertex> = p
                    .vertices
                    .iter()
                    .map(|v| Vertex {
                        wind: [v.wind[0], v.wind[1], v.wind[2], m.0 as f32],
                        ..*v
                    })
                    .collect();
                VariantBuffers::new(device, &vertices, (&p.bark, &p.leaves), m)
            }))
            .collect();
        Meshes {
            variants,
            terrain: TerrainBuffers::new(device, scene),
        }
    }
}
