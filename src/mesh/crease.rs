//! Crease angles as Q1.14 cosines.

/// cos(d°) in Q1.14 for d = 0..=90, each entry correctly rounded (within
/// 0.5 ulp; no entry is within 0.0005 ulp of a rounding tie).
const COS_DEG_Q14: [i16; 91] = [
    16384, 16382, 16374, 16362, 16344, 16322, 16294, 16262, 16225, 16182, // 0..9
    16135, 16083, 16026, 15964, 15897, 15826, 15749, 15668, 15582, 15491, // 10..19
    15396, 15296, 15191, 15082, 14968, 14849, 14726, 14598, 14466, 14330, // 20..29
    14189, 14044, 13894, 13741, 13583, 13421, 13255, 13085, 12911, 12733, // 30..39
    12551, 12365, 12176, 11982, 11786, 11585, 11381, 11174, 10963, 10749, // 40..49
    10531, 10311, 10087, 9860, 9630, 9397, 9162, 8923, 8682, 8438, // 50..59
    8192, 7943, 7692, 7438, 7182, 6924, 6664, 6402, 6138, 5872, // 60..69
    5604, 5334, 5063, 4790, 4516, 4240, 3964, 3686, 3406, 3126, // 70..79
    2845, 2563, 2280, 1997, 1713, 1428, 1143, 857, 572, 286, // 80..89
    0,
];

/// The largest angle between two face normals that still lets the faces
/// share a smoothed vertex normal, stored as its cosine in Q1.14.
///
/// Two faces meeting at a vertex are smoothed together only if
/// `dot(n1, n2) >= cos(crease)`. Two values are special: 0° ([`FLAT`])
/// shares with no other face, and 180° ([`SMOOTH`]) shares with every face,
/// whatever the rounding of the dot product.
///
/// [`FLAT`]: Crease::FLAT
/// [`SMOOTH`]: Crease::SMOOTH
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Crease {
    cos_q14: i16,
}

impl Crease {
    /// 0°: every corner gets its own face normal.
    pub const FLAT: Crease = Crease { cos_q14: 16384 };
    /// 180°: fully smooth, every face at a vertex counts.
    pub const SMOOTH: Crease = Crease { cos_q14: -16384 };

    /// The crease whose cosine is `cos_q14` / 16384, clamped to [-1, 1].
    pub const fn from_cos_q14(cos_q14: i16) -> Self {
        let cos_q14 = if cos_q14 > 16384 {
            16384
        } else if cos_q14 < -16384 {
            -16384
        } else {
            cos_q14
        };
        Crease { cos_q14 }
    }

    /// The crease of `degrees` whole degrees, clamped to 180, from an
    /// integer table: the cosine is correctly rounded to Q1.14 (error at
    /// most 0.5 ulp = 2⁻¹⁵), using cos(180° - d) = -cos(d).
    pub const fn from_degrees(degrees: u32) -> Self {
        let d = if degrees > 180 { 180 } else { degrees as usize };
        let cos_q14 = if d <= 90 {
            COS_DEG_Q14[d]
        } else {
            -COS_DEG_Q14[180 - d]
        };
        Crease { cos_q14 }
    }

    /// The cosine of the crease angle, Q1.14.
    pub const fn cos_q14(self) -> i16 {
        self.cos_q14
    }

    /// Whether two faces with Q1.30 unit normals `a` and `b` may share a
    /// normal; the dot product is exact in i64 (|dot| <= 3 · 2^60).
    pub(crate) const fn allows(self, a: [i32; 3], b: [i32; 3]) -> bool {
        if self.cos_q14 <= -16384 {
            return true;
        }
        if self.cos_q14 >= 16384 {
            return false;
        }
        let dot = a[0] as i64 * b[0] as i64 + a[1] as i64 * b[1] as i64 + a[2] as i64 * b[2] as i64;
        dot >= (self.cos_q14 as i64) << 46
    }
}

impl Default for Crease {
    /// [`Crease::SMOOTH`].
    fn default() -> Self {
        Crease::SMOOTH
    }
}
