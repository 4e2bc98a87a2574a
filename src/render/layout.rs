//! Where things go in a picture of the box: a title band on top, the box drawn to
//! scale below it with a margin, and (colouring by speed) a colour bar on the
//! right. A point (x, y) of the box [0, L_x) × [0, L_y) maps to the pixel
//!
//! (p_x, p_y) = (x₀ + s x, y₀ + s (L_y − y)),   s = (W − 2m − b) / L_x,
//!
//! y pointing up as in the box, with W the image width, m the margin and b the
//! colour bar's width. The image height follows from the box's aspect ratio.

use carom_core::DVec2;

/// Height of the title band (pixels).
pub const TITLE: u32 = 58;
/// Margin around the box (pixels).
pub const MARGIN: u32 = 16;
/// Width taken by the colour bar and its labels (pixels).
pub const BAR: u32 = 110;

/// The geometry of one picture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layout {
    /// Image width and height (pixels).
    pub size: (u32, u32),
    /// Pixel of the box's corner (0, L_y) (top left).
    pub origin: (f64, f64),
    /// Pixels per unit length.
    pub scale: f64,
    /// Box edge lengths (length).
    pub box_size: DVec2,
    /// The colour bar's rectangle (x, y, width, height in pixels), if any.
    pub bar: Option<(i32, i32, i32, i32)>,
}

impl Layout {
    /// The layout of an image `width` pixels wide for a box of `box_size`, with a
    /// colour bar if `bar`. The height is at most 4 × `width` (a very tall box is
    /// scaled down to fit).
    pub fn new(width: u32, box_size: DVec2, bar: bool) -> Layout {
        let b = if bar { BAR } else { 0 };
        let inner_w = f64::from(width.saturating_sub(2 * MARGIN + b).max(16));
        let max_h = f64::from(4 * width);
        let scale = (inner_w / box_size.x).min(max_h / box_size.y);
        let box_w = (scale * box_size.x).ceil() as u32;
        let box_h = (scale * box_size.y).ceil() as u32;
        let height = TITLE + 2 * MARGIN + box_h;
        let width = width.max(box_w + 2 * MARGIN + b);
        let bar = bar.then(|| {
            let x = (MARGIN + box_w + 24) as i32;
            (x, (TITLE + MARGIN) as i32, 18, box_h as i32)
        });
        Layout {
            size: (width, height),
            origin: (f64::from(MARGIN), f64::from(TITLE + MARGIN)),
            scale,
            box_size,
            bar,
        }
    }

    /// The pixel of the box point (x, y) (fractional).
    pub fn pixel(&self, x: f64, y: f64) -> (f64, f64) {
        (
            self.origin.0 + self.scale * x,
            self.origin.1 + self.scale * (self.box_size.y - y),
        )
    }

    /// The box's pixel rectangle: top-left and bottom-right corners.
    pub fn box_pixels(&self) -> ((i32, i32), (i32, i32)) {
        let (x0, y0) = self.pixel(0.0, self.box_size.y);
        let (x1, y1) = self.pixel(self.box_size.x, 0.0);
        (
            (x0.round() as i32, y0.round() as i32),
            (x1.round() as i32, y1.round() as i32),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_box_keeps_its_aspect_and_y_points_up() {
        let l = Layout::new(800, DVec2::new(20.0, 10.0), false);
        let ((x0, y0), (x1, y1)) = l.box_pixels();
        assert_eq!(x1 - x0, 2 * (y1 - y0));
        assert_eq!(x0, MARGIN as i32);
        assert_eq!(l.size.0, 800);
        assert_eq!(l.size.1, TITLE + 2 * MARGIN + (y1 - y0) as u32);
        // y = L_y is the top of the box, y = 0 its bottom.
        assert!(l.pixel(1.0, 9.0).1 < l.pixel(1.0, 1.0).1);
        let with_bar = Layout::new(800, DVec2::new(20.0, 10.0), true);
        assert!(with_bar.scale < l.scale);
        let (bx, _, _, _) = with_bar.bar.unwrap();
        assert!(bx > with_bar.box_pixels().1 .0);
    }
}
