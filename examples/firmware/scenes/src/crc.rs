//! CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320, initial value and
//! final xor 0xFFFFFFFF): the checksum `crc32fast` and zlib compute.

/// The 256-entry table, computed at compile time (1 KiB of flash).
const TABLE: [u32; 256] = {
    let mut t = [0u32; 256];
    let mut i = 0;
    while i < 256 {
        let mut c = i as u32;
        let mut k = 0;
        while k < 8 {
            c = if c & 1 != 0 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
            k += 1;
        }
        t[i] = c;
        i += 1;
    }
    t
};

/// A running CRC-32.
#[derive(Clone, Copy, Debug)]
pub struct Crc32(u32);

impl Crc32 {
    /// An empty checksum.
    pub const fn new() -> Self {
        Self(!0)
    }

    /// Adds bytes.
    pub fn update(&mut self, bytes: impl IntoIterator<Item = u8>) {
        let mut c = self.0;
        for b in bytes {
            c = TABLE[((c ^ b as u32) & 0xff) as usize] ^ (c >> 8);
        }
        self.0 = c;
    }

    /// The checksum of the bytes so far.
    pub const fn finish(&self) -> u32 {
        !self.0
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
    fn check_values() {
        // The standard check value of CRC-32/ISO-HDLC, and the empty input.
        let mut c = Crc32::new();
        c.update(*b"123456789");
        assert_eq!(c.finish(), 0xCBF4_3926);
        assert_eq!(Crc32::new().finish(), 0);
        // Split updates equal one update.
        let mut a = Crc32::new();
        a.update(*b"1234");
        a.update(*b"56789");
        assert_eq!(a.finish(), 0xCBF4_3926);
    }
}
