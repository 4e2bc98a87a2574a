//! The box (`carom_core::boundary`): what a periodic axis and a wall do to a disc.
//!
//! * Minimum image: a separation within half a box is its own image; one several
//!   boxes long maps to the same image as its remainder.
//! * Wrapping: a position any number of boxes outside lands at the same place
//!   modulo L, in [0, L); a walled axis is left alone.
//! * Wall time: after the predicted time a disc's centre is at a (low wall) or
//!   L − a (high wall), whatever its speed.
//! * Wall impulse (physics.md §4b with an infinitely heavy wall): an elastic wall
//!   reverses the normal velocity exactly, a wall of restitution e_w leaves −e_w v,
//!   and the impulse is the disc's change of momentum.
//!
//! Found missing by mutation testing (docs/testing.md): the earlier examples used
//! image shifts of ±1 and speeds of ±1, where `×` and `÷` agree.

use carom_core::boundary::{wall_impulse, wall_time};
use carom_core::collision::apply_wall_impulse;
use carom_core::{Boundary, DVec2, SimBox, WallSide};

#[test]
fn a_separation_within_half_a_box_is_its_own_image() {
    let b = SimBox::periodic(10.0, 4.0);
    for d in [DVec2::new(1.0, 1.5), DVec2::new(-4.5, -0.25), DVec2::ZERO] {
        assert_eq!(b.minimum_image(d), d);
    }
}

#[test]
fn a_separation_several_boxes_long_has_the_image_of_its_remainder() {
    let b = SimBox::periodic(10.0, 4.0);
    // 23 = 2·10 + 3 and −9 = −2·4 − 1.
    assert_eq!(
        b.minimum_image(DVec2::new(23.0, -9.0)),
        DVec2::new(3.0, -1.0)
    );
    assert_eq!(
        b.minimum_image(DVec2::new(-37.0, 13.0)),
        DVec2::new(3.0, 1.0)
    );
}

#[test]
fn wrapping_moves_by_whole_boxes_into_the_box() {
    let b = SimBox::periodic(10.0, 4.0);
    assert_eq!(b.wrap(DVec2::new(23.5, -1.5)), DVec2::new(3.5, 2.5));
    assert_eq!(b.wrap(DVec2::new(-17.0, 9.0)), DVec2::new(3.0, 1.0));
    assert_eq!(b.wrap(DVec2::new(2.5, 3.0)), DVec2::new(2.5, 3.0));
    // A channel: the walled y is not the wrap's business.
    let channel = SimBox {
        size: DVec2::new(10.0, 4.0),
        boundary: [Boundary::Periodic, Boundary::Walls { restitution: 1.0 }],
    };
    assert_eq!(channel.wrap(DVec2::new(12.0, 5.0)), DVec2::new(2.0, 5.0));
}

#[test]
fn after_the_wall_time_the_centre_touches_the_wall() {
    let (a, l) = (0.5, 10.0);
    for (x, v) in [(5.0, 2.0), (5.0, -2.0), (1.25, -0.5), (9.0, 4.0)] {
        let (t, side) = wall_time(x, v, a, l).unwrap();
        let contact = if v > 0.0 { l - a } else { a };
        assert_eq!(side == WallSide::High, v > 0.0);
        assert!((x + v * t - contact).abs() < 1e-12, "x {x}, v {v}: t {t}");
    }
    // Already beyond the wall and still moving out: now.
    assert_eq!(wall_time(0.25, -3.0, a, l), Some((0.0, WallSide::Low)));
}

#[test]
fn a_wall_reflects_the_normal_velocity_scaled_by_its_restitution() {
    let m = 2.5;
    for v in [1.75, -3.0, 0.3] {
        // Elastic: exactly reversed, and the impulse is the change of momentum 2 m |v|.
        let dp = wall_impulse(v, m, 1.0);
        assert_eq!(apply_wall_impulse(v, m, dp), -v);
        assert_eq!(dp, -2.0 * m * v);
        for e in [0.0, 0.5, 0.875] {
            let dp = wall_impulse(v, m, e);
            let after = apply_wall_impulse(v, m, dp);
            assert!((after + e * v).abs() < 1e-15, "v {v}, e {e}: {after}");
            assert!((dp - m * (after - v)).abs() < 1e-14);
            // Energy lost ½ m v² (1 − e²).
            let lost = 0.5 * m * (v * v - after * after);
            assert!((lost - 0.5 * m * v * v * (1.0 - e * e)).abs() < 1e-14);
        }
    }
}
