//! FNV-1a, a small stable 64-bit hash (the same value on every platform and build): what
//! identifies a sweep's inputs (its files and records) in its journal. Not for security.

/// FNV-1a, 64 bit: the sweep's identity in its journal (not cryptographic; it only tells
/// sweeps apart).
pub fn fnv1a(parts: &[&[u8]]) -> u64 {
    let mut h = Fnv1a::new();
    for p in parts {
        h.part(p);
    }
    h.finish()
}

/// [`fnv1a`] fed piece by piece, files streamed in blocks (no file is held in memory).
#[derive(Debug, Clone, Copy)]
pub struct Fnv1a(u64);

impl Fnv1a {
    /// The empty hash.
    pub fn new() -> Fnv1a {
        Fnv1a(0xcbf2_9ce4_8422_2325)
    }

    fn bytes(&mut self, b: &[u8]) {
        for &x in b {
            self.0 ^= u64::from(x);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    /// Ends a part (a separator, so that ("ab", "c") and ("a", "bc") differ).
    pub fn end_part(&mut self) {
        self.0 ^= 0xff;
        self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
    }

    /// One whole part.
    pub fn part(&mut self, b: &[u8]) {
        self.bytes(b);
        self.end_part();
    }

    /// A file's bytes, read in 64 KiB blocks (up to [`crate::model::ground_motion::record::MAX_RECORD_BYTES`]);
    /// a read error ends the stream (the case's own validation reports it).
    pub fn stream(&mut self, mut r: impl std::io::Read) {
        let mut buf = vec![0u8; 1 << 16];
        let mut left = crate::model::ground_motion::record::MAX_RECORD_BYTES;
        while left > 0 {
            match r.read(&mut buf) {
                Ok(0) | Err(_) => break,
                Ok(n) => {
                    self.bytes(&buf[..n]);
                    left = left.saturating_sub(n as u64);
                }
            }
        }
    }

    /// The hash.
    pub fn finish(self) -> u64 {
        self.0
    }
}

impl Default for Fnv1a {
    fn default() -> Fnv1a {
        Fnv1a::new()
    }
}
