//! The sun's shadow map: a depth texture rendered from the sun over a box around the view,
//! and the bind group through which the main pass compares against it.

use sylva::terrain::glam::camera::rh::{proj::directx, view};
use sylva::terrain::glam::{Mat4, Vec3};

use crate::textures::sampled_texture;

/// Side of the shadow map in texels.
pub(crate) const SHADOW_SIZE: u32 = 2048;
/// Half the side of the box the shadow map covers, in metres: shadows reach this far around
/// the point the camera looks at.
const HALF_EXTENT: f32 = 100.0;
/// Metres per shadow-map texel.
pub(crate) const SHADOW_TEXEL: f32 = 2.0 * HALF_EXTENT / SHADOW_SIZE as f32;
/// How far the sun's camera stands back from the box's centre; the depth range is twice it.
const STAND_OFF: f32 = 400.0;

/// The shadow map and what reads it.
pub(crate) struct ShadowMap {
    pub(crate) view: wgpu::TextureView,
    pub(crate) layout: wgpu::BindGroupLayout,
    pub(crate) group: wgpu::BindGroup,
}

impl ShadowMap {
    pub(crate) fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> ShadowMap {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("shadow map"),
            size: wgpu::Extent3d {
                width: SHADOW_SIZE,
                height: SHADOW_SIZE,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        // Linear filtering of the comparison gives smooth edges between the PCF taps.
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("shadow sampler"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            compare: Some(wgpu::CompareFunction::LessEqual),
            ..Default::default()
        });
        let (layout, group) = sampled_texture(
            device,
            "shadow",
            &view,
            &sampler,
            (
                wgpu::TextureSampleType::Depth,
                wgpu::TextureViewDimension::D2,
                wgpu::SamplerBindingType::Comparison,
            ),
        );
        ShadowMap {
            view,
            layout,
            group,
        }
    }
}

/// The sun's view and orthographic projection over a box around what the camera at `eye`
/// looks at along `forward`; `sun` points towards the sun.
pub(crate) fn light_view_proj(eye: Vec3, forward: Vec3, sun: Vec3) -> Mat4 {
    let centre = eye + forward.normalize_or(Vec3::X) * (0.6 * HALF_EXTENT);
    let sun = sun.normalize_or(Vec3::Y);
    let up = if sun.y.abs() > 0.99 { Vec3::Z } else { Vec3::Y };
    let view = view::look_at_mat4(centre + sun * STAND_OFF, centre, up);
    let proj = directx::orthographic(
        -HALF_EXTENT,
        HALF_EXTENT,
        -HALF_EXTENT,
        HALF_EXTENT,
        1.0,
        2.0 * STAND_OFF,
    );
    proj * view
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_box_centre_maps_to_the_middle_of_the_map_and_depth_grows_away_from_the_sun() {
        let sun = Vec3::new(0.4, 0.8, 0.3).normalize();
        let (eye, forward) = (Vec3::new(10.0, 2.0, 5.0), Vec3::X);
        let m = light_view_proj(eye, forward, sun);
        let centre = eye + forward * (0.6 * HALF_EXTENT);
        let c = m.project_point3(centre);
        assert!(c.x.abs() < 1e-4 && c.y.abs() < 1e-4 && (0.0..1.0).contains(&c.z));
        let nearer_sun = m.project_point3(centre + sun * 10.0);
        assert!(nearer_sun.z < c.z);
        // A point at the box's edge across the sun's direction lands at the map's edge.
        let across = sun.cross(Vec3::Y).normalize();
        let edge = m.project_point3(centre + across * HALF_EXTENT);
        assert!(
            (edge.x.abs().max(edge.y.abs()) - 1.0).abs() < 1e-3,
            "{edge}"
        );
    }
}
