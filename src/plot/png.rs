//! PNG encoding of the figures' bitmaps (8-bit RGB): every row Paeth-filtered, the filtered
//! rows deflated by `fdeflate` (the png crate's `Compression::Fast`), one `IHDR`, one `IDAT`,
//! `IEND` (W3C, *Portable Network Graphics (PNG) Specification*, 3rd ed., §5 chunks, §9.4
//! the Paeth filter, §11.2.1 IHDR). The files are byte for byte those the png crate writes
//! with `Compression::Fast` and `FilterType::Paeth` (tested below); what differs is the
//! filter's cost. A figure is mostly white: where 16 bytes of a row, the 16 before them
//! (one pixel back) and the same two spans of the row above are all equal, Paeth's predictor
//! is that value (a = b = c = x) and the filtered bytes are zero — one comparison of 16-byte
//! blocks instead of the predictor per byte (the paper case's figures: 68–83 % of the blocks).

use std::io::{self, Write};

/// The PNG signature (specification §5.2).
const SIGNATURE: [u8; 8] = [137, 80, 78, 71, 13, 10, 26, 10];

/// The longest chunk the png crate writes (`u32::MAX >> 1`): a longer `IDAT` is split.
const MAX_CHUNK: usize = (u32::MAX >> 1) as usize;

/// Bytes per block of the uniform-run test.
const BLOCK: usize = 16;

/// Write `rgb` (rows of `w` pixels, 3 bytes each, `h` rows) to `out` as a PNG file.
pub(crate) fn write_png(out: &mut impl Write, rgb: &[u8], w: u32, h: u32) -> io::Result<()> {
    let row = w as usize * 3;
    if w == 0 || h == 0 || rgb.len() != row * h as usize {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "a {w} × {h} RGB image needs {} bytes, not {}",
                row * h as usize,
                rgb.len()
            ),
        ));
    }
    let raw = (row + 1) * h as usize;
    let mut z = fdeflate::Compressor::new(io::Cursor::new(Vec::with_capacity(raw / 16)))?;
    let mut line = vec![0u8; row + 1];
    line[0] = 4; // Paeth
    let zero = vec![0u8; row];
    let mut prev: &[u8] = &zero;
    for cur in rgb.chunks_exact(row) {
        paeth_row(prev, cur, &mut line[1..]);
        z.write_data(&line)?;
        prev = cur;
    }
    let mut data = z.finish()?.into_inner();
    if data.len() > fdeflate::StoredOnlyCompressor::<()>::compressed_size(raw) {
        // (as the png crate: stored blocks of the unfiltered rows when deflate does not pay)
        let mut s = fdeflate::StoredOnlyCompressor::new(io::Cursor::new(Vec::new()))?;
        for cur in rgb.chunks_exact(row) {
            s.write_data(&[0])?;
            s.write_data(cur)?;
        }
        data = s.finish()?.into_inner();
    }
    out.write_all(&SIGNATURE)?;
    let mut ihdr = [0u8; 13];
    ihdr[..4].copy_from_slice(&w.to_be_bytes());
    ihdr[4..8].copy_from_slice(&h.to_be_bytes());
    // bit depth 8, colour type 2 (RGB), deflate, adaptive filtering, no interlace
    ihdr[8..].copy_from_slice(&[8, 2, 0, 0, 0]);
    chunk(out, b"IHDR", &ihdr)?;
    for part in data.chunks(MAX_CHUNK) {
        chunk(out, b"IDAT", part)?;
    }
    chunk(out, b"IEND", &[])?;
    out.flush()
}

/// One chunk: length, type, data, CRC-32 of type and data (specification §5.3).
fn chunk(out: &mut impl Write, kind: &[u8; 4], data: &[u8]) -> io::Result<()> {
    out.write_all(&(data.len() as u32).to_be_bytes())?;
    out.write_all(kind)?;
    out.write_all(data)?;
    let mut crc = crc32fast::Hasher::new();
    crc.update(kind);
    crc.update(data);
    out.write_all(&crc.finalize().to_be_bytes())
}

/// Paeth's predictor of x from a (left), b (above), c (above left) (specification §9.4), in
/// the form on unsigned bytes that vectorises (L. Versari's, as the png crate has it): pa =
/// |b − c|, pb = |a − c|, and pc = |pa − pb| where c lies between a and b (else pc exceeds both
/// and does not matter); ties go to a, then b.
#[inline(always)]
fn paeth(a: u8, b: u8, c: u8) -> u8 {
    let pa = b.max(c) - c.min(b);
    let pb = a.max(c) - c.min(a);
    let pc = if (a < c) == (c < b) {
        pa.max(pb) - pa.min(pb)
    } else {
        255
    };
    if pa <= pb && pa <= pc {
        a
    } else if pb <= pc {
        b
    } else {
        c
    }
}

/// The Paeth-filtered `cur` (row above: `prev`, zeros for the first row) into `out`.
fn paeth_row(prev: &[u8], cur: &[u8], out: &mut [u8]) {
    let n = cur.len().min(prev.len()).min(out.len());
    let (prev, cur, out) = (&prev[..n], &cur[..n], &mut out[..n]);
    // the first pixel: no left neighbour (a = c = 0)
    for i in 0..n.min(3) {
        out[i] = cur[i].wrapping_sub(paeth(0, prev[i], 0));
    }
    if n <= 3 {
        return;
    }
    let body = n - 3;
    let blocks = body / BLOCK;
    let block =
        |s: &[u8], at: usize| -> [u8; BLOCK] { s[at..at + BLOCK].try_into().expect("a block") };
    for k in 0..blocks {
        let i = 3 + k * BLOCK;
        let (x, a) = (block(cur, i), block(cur, i - 3));
        let (b, c) = (block(prev, i), block(prev, i - 3));
        let o = &mut out[i..i + BLOCK];
        if x == a && x == b && x == c {
            o.fill(0);
        } else {
            for j in 0..BLOCK {
                o[j] = x[j].wrapping_sub(paeth(a[j], b[j], c[j]));
            }
        }
    }
    for i in 3 + blocks * BLOCK..n {
        out[i] = cur[i].wrapping_sub(paeth(cur[i - 3], prev[i], prev[i - 3]));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Paeth's predictor against the specification's own definition (§9.4: p = a + b − c, the
    /// nearest of a, b, c to p, ties in the order a, b, c) for every (a, b, c).
    #[test]
    fn paeth_is_the_specifications() {
        for a in 0..=255u8 {
            for b in 0..=255u8 {
                for c in 0..=255u8 {
                    let p = i16::from(a) + i16::from(b) - i16::from(c);
                    let (pa, pb, pc) = (
                        (p - i16::from(a)).abs(),
                        (p - i16::from(b)).abs(),
                        (p - i16::from(c)).abs(),
                    );
                    let want = if pa <= pb && pa <= pc {
                        a
                    } else if pb <= pc {
                        b
                    } else {
                        c
                    };
                    assert_eq!(paeth(a, b, c), want, "{a} {b} {c}");
                }
            }
        }
    }

    /// The file is byte for byte the png crate's with `Compression::Fast` and `FilterType::Paeth`
    /// (through the image crate, as the figures were written before), and decodes to the
    /// pixels: images of several widths (every remainder of the 16-byte blocks) with white
    /// areas, lines, a gradient and noise, so that both the uniform blocks and the predictor
    /// are exercised; and one of pure noise, which deflate cannot shrink (stored blocks).
    #[test]
    fn the_file_is_the_png_crates() {
        use image::ImageEncoder as _;
        use image::codecs::png::{CompressionType, FilterType, PngEncoder};
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
            let mut ours = Vec::new();
            write_png(&mut ours, &rgb, w, h).unwrap();
            let mut theirs = Vec::new();
            PngEncoder::new_with_quality(&mut theirs, CompressionType::Fast, FilterType::Paeth)
                .write_image(&rgb, w, h, image::ColorType::Rgb8)
                .unwrap();
            assert!(ours == theirs, "{w} × {h}: the files differ");
            let back = image::load_from_memory(&ours).unwrap().to_rgb8();
            assert_eq!(back.dimensions(), (w, h));
            assert!(back.as_raw() == &rgb, "{w} × {h}: pixels");
        }
        let mut out = Vec::new();
        assert!(write_png(&mut out, &[0; 5], 1, 2).is_err());
        assert!(write_png(&mut out, &[], 0, 0).is_err());
    }
}
