//! CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320, initial value and
//! final xor 0xFFFFFFFF: `CRC_32_ISO_HDLC`, the checksum `crc32fast` and
//! zlib compute) from the `crc` crate, with its table built at compile time
//! (1 KiB of flash), fed from byte iterators.

use crc::{Crc, Digest, CRC_32_ISO_HDLC};

static CRC32: Crc<u32> = Crc::<u32>::new(&CRC_32_ISO_HDLC);

/// A running CRC-32.
#[derive(Clone)]
pub struct Crc32(Digest<'static, u32>);

impl core::fmt::Debug for Crc32 {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_tuple("Crc32").finish_non_exhaustive()
    }
}

impl Crc32 {
    /// An empty checksum.
    pub const fn new() -> Self {
        Self(CRC32.digest())
    }

    /// Adds bytes, in chunks of up to 64.
    pub fn update(&mut self, bytes: impl IntoIterator<Item = u8>) {
        let mut buf = [0u8; 64];
        let mut n = 0;
        for b in bytes {
            buf[n] = b;
            n += 1;
            if n == buf.len() {
                self.0.update(&buf);
                n = 0;
            }
        }
        self.0.update(&buf[..n]);
    }

    /// The checksum of the bytes so far.
    pub fn finish(&self) -> u32 {
        self.0.clone().finalize()
    }
}

impl Default for Crc32 {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::Crc32;

    #[test]
    fn check_value() {
        // The CRC-32 check value: the CRC of the ASCII digits "123456789".
        let mut c = Crc32::new();
        c.update(*b"123456789");
        assert_eq!(c.finish(), 0xCBF4_3926);
        assert_eq!(Crc32::new().finish(), 0);
        // Fed in pieces across the 64-byte chunks: the same checksum.
        let data: [u8; 200] = core::array::from_fn(|i| (i * 7 + 3) as u8);
        let mut whole = Crc32::new();
        whole.update(data);
        let mut parts = Crc32::new();
        parts.update(data[..63].iter().copied());
        parts.update(data[63..130].iter().copied());
        parts.update(data[130..].iter().copied());
        assert_eq!(whole.finish(), parts.finish());
    }
}
