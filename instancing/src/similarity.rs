//! Similarity transforms (rotation, translation, uniform scale): glTF's TRS with equal scales.

use bytemuck::{Pod, Zeroable};
use glam::{Affine3A, Quat, Vec3};
use sylva_turtle::Frame;

/// `x -> translation + scale * (rotation * x)`. 32 bytes, `Pod`, directly usable as glTF
/// EXT_mesh_gpu_instancing TRANSLATION, ROTATION and SCALE.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct Similarity {
    /// Unit quaternion (x, y, z, w).
    pub rotation: Quat,
    /// Translation.
    pub translation: Vec3,
    /// Uniform scale.
    pub scale: f32,
}

impl Default for Similarity {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Similarity {
    /// The identity.
    pub const IDENTITY: Similarity = Similarity {
        rotation: Quat::IDENTITY,
        translation: Vec3::ZERO,
        scale: 1.0,
    };

    /// A rigid transform from a turtle frame.
    pub fn from_frame(frame: &Frame) -> Self {
        Similarity {
            rotation: frame.rotation,
            translation: frame.position,
            scale: 1.0,
        }
    }

    /// `self * other`: apply `other` first. The product of unit quaternions stays unit to
    /// within float rounding over the few levels a tree nests, so it is not renormalised here
    /// (exporters normalise once at the end).
    #[inline]
    #[must_use]
    pub fn mul(&self, other: &Similarity) -> Similarity {
        Similarity {
            rotation: self.rotation * other.rotation,
            translation: self.translation + self.scale * (self.rotation * other.translation),
            scale: self.scale * other.scale,
        }
    }

    /// The inverse transform.
    #[must_use]
    pub fn inverse(&self) -> Similarity {
        let r = self.rotation.conjugate();
        let s = 1.0 / self.scale;
        Similarity {
            rotation: r,
            translation: -(r * self.translation) * s,
            scale: s,
        }
    }

    /// Transforms a point.
    #[inline]
    pub fn transform_point(&self, p: Vec3) -> Vec3 {
        self.translation + self.scale * (self.rotation * p)
    }

    /// Whether all components are finite.
    pub fn is_finite(&self) -> bool {
        self.rotation.is_finite() && self.translation.is_finite() && self.scale.is_finite()
    }

    /// As an affine matrix.
    pub fn to_affine(&self) -> Affine3A {
        Affine3A::from_scale_rotation_translation(
            Vec3::splat(self.scale),
            self.rotation,
            self.translation,
        )
    }
}
