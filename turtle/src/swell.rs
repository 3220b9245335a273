//! Where a tube swells beyond its frustum: the root flare at a tree's base and the collar
//! where a branch leaves its parent. Each is a profile, extra rings up a segment's first part
//! whose radii fade back to the frustum's, so the builder only draws rings.

use glam::Vec3;

use crate::sink::Segment;

/// Rings drawn up a flared trunk base.
pub(crate) const FLARE_RINGS: usize = 4;
/// How far up the trunk the flare's rings reach, in base radii.
pub(crate) const FLARE_REACH: f32 = 3.0;
/// The widest flare accepted (a base four times the trunk's radius).
pub(crate) const FLARE_MAX: f32 = 3.0;
/// The widest collar accepted (a branch's base twice its radius where it leaves the parent).
pub(crate) const COLLAR_MAX: f32 = 1.0;
/// How far past the parent's surface the collar fades, in the branch's radii.
const COLLAR_REACH: f32 = 2.5;

/// Extra rings of a segment's first part: `(height along the segment, radius)`, rising.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Profile {
    rings: [(f32, f32); FLARE_RINGS],
    len: usize,
}

impl Profile {
    /// The rings, from the segment's start up.
    pub(crate) fn rings(&self) -> &[(f32, f32)] {
        &self.rings[..self.len]
    }

    fn push(&mut self, height: f32, radius: f32) {
        self.rings[self.len] = (height, radius);
        self.len += 1;
    }
}

/// The frustum's radius `h` along `s`.
fn frustum(s: &Segment, h: f32) -> f32 {
    s.start_radius + (s.end_radius - s.start_radius) * (h / s.length)
}

/// A tree's base widened by `flare` (0 none, 0.6 a base 1.6 times the trunk's radius): the
/// radius of its first ring, and [`FLARE_RINGS`] rings within the segment's first
/// [`FLARE_REACH`] base radii (and its first 60%), the frustum's radius times
/// `1 + flare * e^(-h / (1.2 r))` at height `h`. `None` when there is nothing to widen.
pub(crate) fn flare(s: &Segment, flare: f32) -> Option<(f32, Profile)> {
    // Written as "all positive" so that NaNs fail too.
    let positive = [flare, s.length, s.start_radius].iter().all(|&x| x > 0.0);
    if !positive {
        return None;
    }
    let r0 = s.start_radius;
    let radius_at = |h: f32| frustum(s, h) * (1.0 + flare * (-h / (1.2 * r0)).exp());
    let reach = (FLARE_REACH * r0).min(0.6 * s.length);
    let mut profile = Profile::default();
    for k in 1..=FLARE_RINGS {
        let h = reach * k as f32 / FLARE_RINGS as f32;
        profile.push(h, radius_at(h));
    }
    Some((radius_at(0.0), profile))
}

/// The collar of a branch whose first segment `s` leaves a parent axis of heading `parent`
/// and radius `parent_radius` (at the branch point, on the parent's axis): the branch's
/// radius is `1 + collar` times the frustum's where its axis leaves the parent's surface
/// (never wider than the parent), and fades back to within a twentieth of it over
/// [`COLLAR_REACH`] radii. Two rings; `None` when the segment is too short to hold them, the
/// branch no thinner than its parent, or the collar 0.
pub(crate) fn collar(
    s: &Segment,
    parent: Vec3,
    parent_radius: f32,
    collar: f32,
) -> Option<Profile> {
    let r = s.start_radius;
    let positive = [collar, s.length, r].iter().all(|&x| x > 0.0);
    if !positive || parent_radius.partial_cmp(&r) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    // The branch's axis leaves the parent's cylinder `parent_radius / sin(angle)` along it;
    // branches nearly along their parent are treated as leaving at 15 degrees.
    let sine = s.frame.heading().cross(parent).length().max(0.26);
    let exit = parent_radius / sine;
    let fade = exit + COLLAR_REACH * r;
    if fade > 0.7 * s.length {
        return None;
    }
    let widest = (frustum(s, exit) * (1.0 + collar)).min(0.95 * parent_radius);
    let mut profile = Profile::default();
    profile.push(exit, widest.max(frustum(s, exit)));
    profile.push(fade, frustum(s, fade) * (1.0 + 0.05 * collar));
    Some(profile)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::Frame;

    /// A segment along +x (`sideways`) or +y.
    fn segment(sideways: bool, length: f32, radii: (f32, f32)) -> Segment {
        let mut frame = Frame::default();
        if sideways {
            frame.rotate_world(Vec3::Z, -std::f32::consts::FRAC_PI_2);
        }
        assert!(
            frame
                .heading()
                .abs_diff_eq(if sideways { Vec3::X } else { Vec3::Y }, 1e-6)
        );
        Segment {
            id: 1,
            parent: Some(0),
            continues_parent: false,
            frame,
            length,
            start_radius: radii.0,
            end_radius: radii.1,
            depth: 1,
        }
    }

    /// A collar is widest where the branch leaves its parent's surface, never wider than the
    /// parent, and back near the frustum a few radii on.
    #[test]
    fn a_collar_swells_where_the_branch_leaves_its_parent() {
        let s = segment(true, 2.0, (0.05, 0.04));
        let p = collar(&s, Vec3::Y, 0.2, 0.6).expect("a collar");
        let [(exit, widest), (fade, faded)] = [p.rings()[0], p.rings()[1]];
        assert!(
            (exit - 0.2).abs() < 1e-5,
            "a branch at right angles leaves at 0.2: {exit}"
        );
        assert!(widest > 1.5 * frustum(&s, exit) && widest < 0.2, "{widest}");
        assert!(
            fade > exit && faded < 1.06 * frustum(&s, fade),
            "{fade} {faded}"
        );
        // A branch nearly as thick as its parent is capped by the parent's radius.
        let thick = segment(true, 4.0, (0.18, 0.17));
        let p = collar(&thick, Vec3::Y, 0.2, 1.0).expect("a collar");
        assert!(p.rings()[0].1 <= 0.19 + 1e-6, "{:?}", p.rings());
        // No collar on twigs too short for it, on branches as thick as their parent, or
        // for bad settings.
        assert_eq!(
            collar(&segment(true, 0.3, (0.05, 0.04)), Vec3::Y, 0.2, 0.6),
            None
        );
        assert_eq!(collar(&s, Vec3::Y, 0.05, 0.6), None);
        assert_eq!(collar(&s, Vec3::Y, 0.2, f32::NAN), None);
        assert_eq!(collar(&s, Vec3::Y, 0.2, 0.0), None);
    }

    /// A flare's rings rise and narrow; a bad flare draws none.
    #[test]
    fn a_flare_narrows_up_the_trunk() {
        let s = segment(false, 4.0, (0.2, 0.15));
        let (base, p) = flare(&s, 0.6).expect("a flare");
        assert!((base - 0.32).abs() < 1e-5);
        let rings = p.rings();
        assert_eq!(rings.len(), FLARE_RINGS);
        assert!(rings.windows(2).all(|w| w[1].0 > w[0].0 && w[1].1 < w[0].1));
        assert_eq!(flare(&s, f32::NAN), None);
        assert_eq!(flare(&s, -1.0), None);
    }
}
