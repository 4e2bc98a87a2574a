//! Rectangular boxes: periodic or hard walls, chosen per axis.
//!
//! The box spans [0, L_x) × [0, L_y). A periodic axis wraps positions and uses the
//! minimum-image convention; a walled axis confines disc centres to [a, L − a] and
//! reflects the normal velocity with the wall's own restitution.

use glam::DVec2;

/// A Cartesian axis of the box.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Axis {
    /// The x axis (index 0).
    X = 0,
    /// The y axis (index 1).
    Y = 1,
}

impl Axis {
    /// Both axes, x first.
    pub const BOTH: [Axis; 2] = [Axis::X, Axis::Y];

    /// The axis index, 0 for x and 1 for y.
    pub fn index(self) -> usize {
        self as usize
    }
}

/// Which wall of an axis: the one at 0 (`Low`) or the one at L (`High`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum WallSide {
    /// The wall at coordinate 0.
    Low,
    /// The wall at coordinate L.
    High,
}

/// The boundary condition of one axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Boundary {
    /// Periodic: a disc leaving at L re-enters at 0; distances use the minimum image.
    Periodic,
    /// Hard walls at 0 and L with restitution `restitution` ∈ [0, 1]: a disc hitting a
    /// wall leaves with its normal velocity reversed and multiplied by it.
    Walls {
        /// Wall restitution coefficient e_w (1 = elastic).
        restitution: f64,
    },
}

impl Boundary {
    /// True for [`Boundary::Periodic`].
    pub fn is_periodic(&self) -> bool {
        matches!(self, Boundary::Periodic)
    }
}

/// A rectangular simulation box [0, L_x) × [0, L_y) with a boundary per axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SimBox {
    /// Edge lengths (L_x, L_y) (length).
    pub size: DVec2,
    /// Boundary conditions of the x and y axes.
    pub boundary: [Boundary; 2],
}

impl SimBox {
    /// A box periodic on both axes.
    pub fn periodic(lx: f64, ly: f64) -> Self {
        SimBox {
            size: DVec2::new(lx, ly),
            boundary: [Boundary::Periodic; 2],
        }
    }

    /// A box with hard walls of restitution `e` on both axes.
    pub fn walled(lx: f64, ly: f64, e: f64) -> Self {
        SimBox {
            size: DVec2::new(lx, ly),
            boundary: [Boundary::Walls { restitution: e }; 2],
        }
    }

    /// Area L_x L_y (length²).
    pub fn area(&self) -> f64 {
        self.size.x * self.size.y
    }

    /// The boundary of `axis`.
    pub fn boundary(&self, axis: Axis) -> Boundary {
        self.boundary[axis.index()]
    }

    /// The edge length along `axis` (length).
    pub fn length(&self, axis: Axis) -> f64 {
        self.size[axis.index()]
    }

    /// Number of momentum components the dynamics conserve: one per periodic axis
    /// (physics.md §5: 2 fully periodic, 1 for a channel, 0 with walls on both axes).
    pub fn conserved_momentum_components(&self) -> usize {
        self.boundary.iter().filter(|b| b.is_periodic()).count()
    }

    /// Minimum-image separation: each periodic component of `d` is mapped into
    /// [−L/2, L/2]; walled components are returned unchanged.
    #[inline]
    pub fn minimum_image(&self, mut d: DVec2) -> DVec2 {
        for axis in Axis::BOTH {
            if self.boundary(axis).is_periodic() {
                let l = self.length(axis);
                let k = axis.index();
                d[k] -= l * (d[k] / l).round();
            }
        }
        d
    }

    /// Wrap a position into the box along periodic axes ([0, L)); walled components
    /// are returned unchanged.
    #[inline]
    pub fn wrap(&self, mut r: DVec2) -> DVec2 {
        for axis in Axis::BOTH {
            if self.boundary(axis).is_periodic() {
                let l = self.length(axis);
                let k = axis.index();
                if (0.0..l).contains(&r[k]) {
                    // Already inside, where rem_euclid (a libm fmod call) returns
                    // it unchanged.
                    continue;
                }
                r[k] = r[k].rem_euclid(l);
                if r[k] >= l {
                    // rem_euclid of a tiny negative number rounds up to l.
                    r[k] = 0.0;
                }
            }
        }
        r
    }
}

/// Time from now until a disc of radius `a` at coordinate `x` with velocity `v` along
/// a walled axis of length `l` touches a wall, and which wall (time ≥ 0).
///
/// The centre reaches the wall at a (low side) or l − a (high side). A disc that
/// rounding left beyond its wall while moving outwards hits it now (t = 0); a disc at
/// rest never does (`None`).
#[inline]
pub fn wall_time(x: f64, v: f64, a: f64, l: f64) -> Option<(f64, WallSide)> {
    if v > 0.0 {
        Some((((l - a - x) / v).max(0.0), WallSide::High))
    } else if v < 0.0 {
        Some((((a - x) / v).max(0.0), WallSide::Low))
    } else {
        None
    }
}

/// Momentum a wall of restitution e_w gives a disc of mass `m` whose normal
/// velocity is `v`: Δp = −(1 + e_w) m v (physics.md §4b applied to an infinitely
/// heavy wall), so that v + Δp/m ([`crate::collision::apply_wall_impulse`]) is
/// −e_w v. Taken as ((−(1 + e_w) v) m), so that Δp/m gives back −(1 + e_w) v in
/// nearly every case and an elastic wall reverses v exactly.
#[inline]
pub fn wall_impulse(v: f64, m: f64, restitution: f64) -> f64 {
    -(1.0 + restitution) * v * m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn minimum_image_maps_into_half_box() {
        let b = SimBox::periodic(10.0, 4.0);
        let d = b.minimum_image(DVec2::new(9.0, -3.0));
        assert_eq!(d, DVec2::new(-1.0, 1.0));
    }

    #[test]
    fn channel_keeps_wall_axis_unchanged() {
        let b = SimBox {
            size: DVec2::new(10.0, 4.0),
            boundary: [Boundary::Periodic, Boundary::Walls { restitution: 1.0 }],
        };
        assert_eq!(b.minimum_image(DVec2::new(9.0, 3.0)), DVec2::new(-1.0, 3.0));
        assert_eq!(b.conserved_momentum_components(), 1);
    }

    #[test]
    fn wrap_never_returns_l() {
        let b = SimBox::periodic(1.0, 1.0);
        let r = b.wrap(DVec2::new(-1e-300, 1.0));
        assert!(r.x < 1.0 && r.y < 1.0 && r.x >= 0.0);
    }

    #[test]
    fn wall_time_reaches_contact() {
        assert_eq!(wall_time(5.0, 2.0, 0.5, 10.0), Some((2.25, WallSide::High)));
        assert_eq!(wall_time(5.0, -1.0, 0.5, 10.0), Some((4.5, WallSide::Low)));
        assert_eq!(wall_time(5.0, 0.0, 0.5, 10.0), None);
    }
}
