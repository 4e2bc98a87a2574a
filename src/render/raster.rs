//! Discs rasterised with anti-aliasing, at their exact sub-pixel centres and
//! radii (the bitmap backends of plotters round both to whole pixels, which at a
//! few pixels per disc merges a dense fluid into one blob). A pixel whose centre
//! lies at distance d from a disc's centre is covered by
//!
//! c = clamp(R − d + ½, 0, 1),   R = a·s (the radius in pixels),
//!
//! and a rim of width w = min(0.8, R/4) pixels takes a darker shade, so touching
//! discs stay apart: pixel ← pixel (1 − c) + fill · c_in + rim · (c − c_in),
//! with c_in the coverage of the disc of radius R − w.

use plotters::style::RGBColor;

use super::layout::Layout;

/// An RGB image, 3 bytes per pixel, rows from the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Raster {
    /// Width and height (pixels).
    pub size: (u32, u32),
    /// The pixels.
    pub rgb: Vec<u8>,
}

/// The rim's shade of a fill colour.
fn rim(c: RGBColor) -> [f64; 3] {
    [
        0.55 * f64::from(c.0),
        0.55 * f64::from(c.1),
        0.55 * f64::from(c.2),
    ]
}

impl Raster {
    /// An image of `layout`'s size filled with `background`.
    pub fn new(layout: &Layout, background: RGBColor) -> Raster {
        let (w, h) = layout.size;
        let mut rgb = Vec::with_capacity(3 * w as usize * h as usize);
        for _ in 0..(w as usize * h as usize) {
            rgb.extend_from_slice(&[background.0, background.1, background.2]);
        }
        Raster { size: (w, h), rgb }
    }

    /// Paint a disc of radius `r` (pixels) centred at pixel point (`cx`, `cy`).
    pub fn disc(&mut self, cx: f64, cy: f64, r: f64, fill: RGBColor) {
        let (w, h) = (f64::from(self.size.0), f64::from(self.size.1));
        let x0 = (cx - r - 1.0).floor().max(0.0);
        let x1 = (cx + r + 1.0).ceil().min(w);
        let y0 = (cy - r - 1.0).floor().max(0.0);
        let y1 = (cy + r + 1.0).ceil().min(h);
        if x0 >= x1 || y0 >= y1 {
            return;
        }
        let band = (r / 4.0).min(0.8);
        let f = [f64::from(fill.0), f64::from(fill.1), f64::from(fill.2)];
        let e = rim(fill);
        let stride = self.size.0 as usize;
        for py in y0 as usize..y1 as usize {
            let dy = py as f64 + 0.5 - cy;
            for px in x0 as usize..x1 as usize {
                let dx = px as f64 + 0.5 - cx;
                let d = (dx * dx + dy * dy).sqrt();
                let cover = (r - d + 0.5).clamp(0.0, 1.0);
                if cover == 0.0 {
                    continue;
                }
                let inner = (r - band - d + 0.5).clamp(0.0, 1.0);
                let k = 3 * (py * stride + px);
                for c in 0..3 {
                    let old = f64::from(self.rgb[k + c]);
                    let v = old * (1.0 - cover) + f[c] * inner + e[c] * (cover - inner);
                    self.rgb[k + c] = v.round().clamp(0.0, 255.0) as u8;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom_core::DVec2;

    #[test]
    fn a_disc_covers_its_area_with_its_colour_inside_and_nothing_outside() {
        let layout = Layout::new(200, DVec2::new(10.0, 10.0), false);
        let mut r = Raster::new(&layout, RGBColor(255, 255, 255));
        let fill = RGBColor(31, 119, 180);
        r.disc(100.25, 80.5, 10.0, fill);
        let at = |x: usize, y: usize| {
            let k = 3 * (y * r.size.0 as usize + x);
            [r.rgb[k], r.rgb[k + 1], r.rgb[k + 2]]
        };
        assert_eq!(at(100, 80), [31, 119, 180]);
        assert_eq!(at(100, 72), [31, 119, 180]);
        assert_eq!(at(112, 80), [255, 255, 255]);
        assert_eq!(at(100, 92), [255, 255, 255]);
        // The painted area (coverage-weighted) is π R² to within the rim's shading.
        let covered: f64 = r
            .rgb
            .chunks(3)
            .map(|p| (255.0 - f64::from(p[0])) / (255.0 - 31.0))
            .sum();
        let area = std::f64::consts::PI * 100.0;
        assert!((covered - area).abs() < 0.1 * area, "{covered} vs {area}");
    }
}
