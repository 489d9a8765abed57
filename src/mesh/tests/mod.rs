//! Unit tests of the mesh module (no std: fixed buffers, libm for f64).

// Reinterpreting random bits as signed values is the point here.
#![allow(clippy::cast_possible_wrap)]

mod exact;
mod generate;
mod mesh;

/// A small xorshift generator for reproducible pseudo-random inputs.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// A pseudo-random i16 (any value).
    fn i16(&mut self) -> i16 {
        (self.next() >> 48) as u16 as i16
    }
}

/// Largest per-component difference, in Q1.14 ulps, between `n` and the
/// exact unit vector along `v`, computed in f64.
fn error_ulps(n: [i16; 3], v: [f64; 3]) -> f64 {
    let len = libm::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    (0..3)
        .map(|k| libm::fabs(f64::from(n[k]) - 16384.0 * v[k] / len))
        .fold(0.0, f64::max)
}

/// A built-in mesh's shape: its positions merged by value (a vertex per
/// distinct position, in order of first appearance) and its triangles
/// renumbered, without normals: what normal generation works on.
struct Shape {
    pos: [[i16; 3]; 64],
    n: usize,
    tris: [[u16; 3]; 64],
    t: usize,
}

impl Shape {
    fn of(m: &crate::mesh::Mesh<'_>) -> Self {
        let mut s = Self {
            pos: [[0; 3]; 64],
            n: 0,
            tris: [[0; 3]; 64],
            t: m.triangle_count(),
        };
        let mut map = [0u16; 64];
        for (i, p) in m.positions().iter().enumerate() {
            let k = s.pos[..s.n].iter().position(|q| q == p).unwrap_or_else(|| {
                s.pos[s.n] = *p;
                s.n += 1;
                s.n - 1
            });
            map[i] = k as u16;
        }
        for (d, t) in s.tris.iter_mut().zip(m.triangles()) {
            *d = t.map(|v| map[usize::from(v)]);
        }
        s
    }

    fn mesh(&self) -> crate::mesh::Mesh<'_> {
        crate::mesh::Mesh::new(&self.pos[..self.n], &self.tris[..self.t], None).unwrap()
    }
}
