//! A contact sheet of a figure directory: every PNG in DIR, shrunk by half and
//! tiled three to a row under its file name, in one PNG (for looking at all the
//! figures of one run at once; not part of carom itself).
//!
//! cargo run --release --example contact_sheet -- DIR OUT.png

use plotters::prelude::*;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (dir, out) = match args.as_slice() {
        [_, dir, out] => (dir, out),
        _ => {
            eprintln!("usage: contact_sheet DIR OUT.png");
            std::process::exit(2);
        }
    };
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .expect("a readable directory")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "png"))
        .collect();
    files.sort();
    let tiles: Vec<(String, image::RgbImage)> = files
        .iter()
        .map(|p| {
            let img = image::open(p).expect("a PNG").to_rgb8();
            let (w, h) = (img.width() / 2, img.height() / 2);
            let small = image::imageops::resize(&img, w, h, image::imageops::FilterType::Triangle);
            (p.file_name().unwrap().to_string_lossy().into_owned(), small)
        })
        .collect();
    let cols = 3u32;
    let rows = (tiles.len() as u32).div_ceil(cols).max(1);
    let (tw, th) = tiles
        .first()
        .map_or((450, 300), |t| (t.1.width(), t.1.height()));
    let label = 24u32;
    let (w, h) = (cols * (tw + 10) + 10, rows * (th + label + 10) + 10);
    let mut buf = vec![255u8; (w * h * 3) as usize];
    for (k, (_, img)) in tiles.iter().enumerate() {
        let (cx, cy) = (k as u32 % cols, k as u32 / cols);
        let (x0, y0) = (10 + cx * (tw + 10), 10 + cy * (th + label + 10) + label);
        for (x, y, p) in img.enumerate_pixels() {
            let i = (((y0 + y) * w + x0 + x) * 3) as usize;
            buf[i..i + 3].copy_from_slice(&p.0);
        }
    }
    // The labels' font: DejaVu Sans, the one `carom`'s own figures use.
    let _ =
        plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular());
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        for (k, (name, img)) in tiles.iter().enumerate() {
            let (cx, cy) = (k as u32 % cols, k as u32 / cols);
            let (x0, y0) = (10 + cx * (tw + 10), 10 + cy * (th + label + 10));
            root.draw(&Text::new(
                name.clone(),
                (x0 as i32 + 4, y0 as i32 + 2),
                ("sans-serif", 18).into_font().color(&BLACK),
            ))
            .expect("text");
            root.draw(&Rectangle::new(
                [
                    (x0 as i32 - 1, (y0 + label) as i32 - 1),
                    (
                        (x0 + img.width()) as i32,
                        (y0 + label + img.height()) as i32,
                    ),
                ],
                BLACK.mix(0.3),
            ))
            .expect("frame");
        }
        root.present().expect("drawn");
    }
    image::RgbImage::from_raw(w, h, buf)
        .expect("the buffer's size")
        .save(out)
        .expect("written");
    eprintln!("{} figures of {dir} in {out}", tiles.len());
}
