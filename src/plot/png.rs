//! PNG encoding of the figures' bitmaps (8-bit RGB) by the png crate (through `image`, the
//! version plotters draws with): its fast deflate (`fdeflate`) and one fixed row filter, `Up`
//! (each byte minus the one above it).
//!
//! Why `Up`: a figure is mostly white, with axes, grid lines, text and curves; the rows above
//! and below a point of it are mostly alike, so `Up` leaves mostly zeros, which this deflate
//! codes as runs. `Paeth` leaves a few more zeros but costs a predictor per byte: measured on
//! the paper case's two figures (1200 × 900 and 1600 × 700), `Up` encodes them in 26 M
//! instructions against Paeth's 37.6 M (the filter alone 2.4 M against 18.3 M), in files of
//! 474 KB and 267 KB against 323 KB and 207 KB. The pixels are the same either way (lossless).
//! The level is the cheapest that compresses (`Fast`; `Default` would give 254 KB for both
//! files at 17× the encoding's instructions).

use std::io::{self, Write};

use image::ImageEncoder as _;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};

/// Write `rgb` (rows of `w` pixels, 3 bytes each, `h` rows) to `out` as a PNG file.
pub(crate) fn write_png(out: &mut impl Write, rgb: &[u8], w: u32, h: u32) -> io::Result<()> {
    let bytes = 3 * w as usize * h as usize;
    if w == 0 || h == 0 || rgb.len() != bytes {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "a {w} × {h} RGB image needs {bytes} bytes, not {}",
                rgb.len()
            ),
        ));
    }
    PngEncoder::new_with_quality(&mut *out, CompressionType::Fast, FilterType::Up)
        .write_image(rgb, w, h, image::ColorType::Rgb8)
        .map_err(io::Error::other)?;
    out.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The file decodes to the pixels: images of several widths with white areas, lines, a
    /// gradient and noise, and one of pure noise, which deflate cannot shrink (stored
    /// blocks); a buffer of the wrong size is refused.
    #[test]
    fn the_file_holds_the_pixels() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut noise = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 24) as u8
        };
        let mut cases = Vec::new();
        for (w, h) in [
            (1u32, 1u32),
            (2, 3),
            (6, 5),
            (7, 9),
            (40, 31),
            (123, 64),
            (301, 97),
        ] {
            let mut rgb = vec![255u8; (w * h * 3) as usize];
            for y in 0..h {
                for x in 0..w {
                    let i = ((y * w + x) * 3) as usize;
                    if x == w / 3 || y == h / 2 {
                        rgb[i..i + 3].copy_from_slice(&[30, 60, 200]);
                    } else if x > 2 * w / 3 {
                        rgb[i..i + 3].copy_from_slice(&[(x * 2) as u8, (y * 3) as u8, 128]);
                    } else if (x + y) % 17 == 0 {
                        rgb[i..i + 3].copy_from_slice(&[noise(), noise(), noise()]);
                    }
                }
            }
            cases.push((w, h, rgb));
        }
        let (w, h) = (64u32, 48u32);
        cases.push((w, h, (0..w * h * 3).map(|_| noise()).collect()));
        for (w, h, rgb) in cases {
            let mut file = Vec::new();
            write_png(&mut file, &rgb, w, h).unwrap();
            let back = image::load_from_memory(&file).unwrap().to_rgb8();
            assert_eq!(back.dimensions(), (w, h));
            assert!(back.as_raw() == &rgb, "{w} × {h}: pixels");
        }
        let mut out = Vec::new();
        assert!(write_png(&mut out, &[0; 5], 1, 2).is_err());
        assert!(write_png(&mut out, &[], 0, 0).is_err());
    }
}
