//! The turtle's position and orientation.

use glam::{Affine3A, Mat3, Quat, Vec3};

/// A position and an orthonormal heading/left/up frame, stored as a rotation.
///
/// The rotation maps the turtle's local axes to world space: local +Y is the heading H, local
/// -X the left vector L and local +Z the up vector U, so that H x L = U as in ABOP. The initial
/// frame heads up the world +Y axis.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Frame {
    /// Where the turtle is.
    pub position: Vec3,
    /// Local-to-world rotation (unit quaternion).
    pub rotation: Quat,
}

impl Default for Frame {
    fn default() -> Self {
        Frame::IDENTITY
    }
}

impl Frame {
    /// At the origin, heading up +Y, left -X, up +Z.
    pub const IDENTITY: Frame = Frame {
        position: Vec3::ZERO,
        rotation: Quat::IDENTITY,
    };

    /// The heading vector H.
    pub fn heading(&self) -> Vec3 {
        self.rotation * Vec3::Y
    }

    /// The left vector L.
    pub fn left(&self) -> Vec3 {
        self.rotation * Vec3::NEG_X
    }

    /// The up vector U.
    pub fn up(&self) -> Vec3 {
        self.rotation * Vec3::Z
    }

    /// The corners of a leaf card of `size` (length along the heading, width along the left
    /// vector) at this frame: from the frame's position along the heading, centred across,
    /// counter-clockwise seen from the up vector (the card's normal). The mesher draws cards
    /// on these corners; whatever measures cards takes the same.
    ///
    /// ```
    /// use sylva_turtle::Frame;
    /// let [a, b, c, d] = Frame::IDENTITY.card_corners([2.0, 1.0]);
    /// assert_eq!((c - b).length(), 2.0); // as long as the card
    /// assert_eq!((a - b).length(), 1.0); // as wide
    /// assert_eq!(a + b, sylva_turtle::glam::Vec3::ZERO); // the base centred on the frame
    /// # let _ = d;
    /// ```
    pub fn card_corners(&self, size: [f32; 2]) -> [Vec3; 4] {
        let (h, l) = (self.heading() * size[0], self.left() * (size[1] * 0.5));
        let p = self.position;
        [p + l, p - l, p - l + h, p + l + h]
    }

    /// The frame as an affine transform from turtle-local to world coordinates.
    pub fn to_affine(&self) -> Affine3A {
        Affine3A::from_rotation_translation(self.rotation, self.position)
    }

    /// Rotates about the local up vector: positive turns left (ABOP `+`).
    pub fn yaw(&mut self, radians: f32) {
        self.rotate_local(Quat::from_rotation_z(radians));
    }

    /// Rotates about the local left vector: positive pitches down (ABOP `&`).
    pub fn pitch(&mut self, radians: f32) {
        self.rotate_local(Quat::from_rotation_x(-radians));
    }

    /// Rotates about the heading: positive rolls right (ABOP `/`).
    pub fn roll(&mut self, radians: f32) {
        self.rotate_local(Quat::from_rotation_y(radians));
    }

    /// This frame rolled about its heading by `amount` (0 to 1) of the way towards the roll
    /// whose up vector points most nearly at the sky (+Y) or away from it, whichever is the
    /// smaller turn: a card in the heading-left plane then lies as flat as its heading allows.
    /// A vertical heading has no such roll and keeps its frame.
    ///
    /// ```
    /// use sylva_turtle::Frame;
    /// let mut f = Frame::IDENTITY;
    /// f.pitch(60f32.to_radians()); // heading tilted, up vector no longer vertical
    /// f.roll(0.7);
    /// let flat = f.facing_sky(1.0);
    /// assert!((flat.heading() - f.heading()).length() < 1e-5);
    /// assert!(flat.left().y.abs() < 1e-5); // the left vector is level: the card faces up
    /// ```
    #[must_use]
    pub fn facing_sky(&self, amount: f32) -> Frame {
        let amount = amount.clamp(0.0, 1.0);
        let h = self.heading();
        let sky = Vec3::Y - h * h.y;
        if amount == 0.0 || sky.length_squared() < 1e-8 {
            return *self;
        }
        let (up, left) = (self.up(), self.left());
        let mut target = sky.normalize();
        if target.dot(up) < 0.0 {
            target = -target;
        }
        // Rolling by r turns U into cos(r) U - sin(r) L.
        let r = (-left.dot(target)).atan2(up.dot(target));
        let mut out = *self;
        out.roll(r * amount);
        out
    }

    fn rotate_local(&mut self, q: Quat) {
        self.rotation = (self.rotation * q).normalize();
    }

    /// Rotates in world space about `axis` (unit) by `radians`.
    pub fn rotate_world(&mut self, axis: Vec3, radians: f32) {
        self.rotation = (Quat::from_axis_angle(axis, radians) * self.rotation).normalize();
    }

    /// ABOP `$`: rolls about the heading so that the left vector is horizontal (perpendicular
    /// to world up). Does nothing when heading straight up or down.
    pub fn roll_to_horizontal(&mut self) {
        let h = self.heading();
        let l = Vec3::Y.cross(h);
        if l.length_squared() < 1e-12 {
            return;
        }
        let l = l.normalize();
        let u = h.cross(l);
        self.rotation = Quat::from_mat3(&Mat3::from_cols(-l, h, u)).normalize();
    }

    /// Turns the heading towards `direction` by `e * |H x T|` radians (the thesis's tropism).
    pub fn bend_towards(&mut self, direction: Vec3, susceptibility: f32) {
        let axis = self.heading().cross(direction);
        let len = axis.length();
        if len > 1e-7 && susceptibility != 0.0 {
            self.rotate_world(axis / len, susceptibility * len);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identity_frame_is_right_handed_hlu() {
        let f = Frame::IDENTITY;
        assert_eq!(f.heading().cross(f.left()), f.up());
    }

    #[test]
    fn yaw_turns_heading_towards_left() {
        let mut f = Frame::IDENTITY;
        f.yaw(0.1);
        assert!(f.heading().dot(Frame::IDENTITY.left()) > 0.0);
        let mut g = Frame::IDENTITY;
        g.pitch(0.1);
        assert!(
            g.heading().dot(Frame::IDENTITY.up()) < 0.0,
            "pitch down moves H away from U"
        );
    }

    #[test]
    fn roll_to_horizontal_levels_left_vector() {
        let mut f = Frame::IDENTITY;
        f.pitch(0.7);
        f.roll(0.5);
        f.roll_to_horizontal();
        assert!(f.left().y.abs() < 1e-5);
    }
}
