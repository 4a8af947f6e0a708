//! Shared input generators and oracle arithmetic for the fuzz targets.
//!
//! Every target includes this file with `mod common;`; not every target
//! uses every helper.
#![allow(dead_code)]

use arbitrary::Arbitrary;
use sightline::math::{Vec2, Vec3};
use sightline::scalar::Scalar;

/// A number from the fuzzer: small integers and halves (exact geometry,
/// many ties and degeneracies), values at a chosen binary scale (tiny,
/// huge, distant), or any f64 bit pattern (NaN, ±∞, subnormal).
#[derive(Arbitrary, Debug, Clone, Copy)]
pub enum Num {
    Small(i8),
    Scaled(i16, i8),
    Bits(u64),
}

impl Num {
    pub fn value(self) -> f64 {
        match self {
            Num::Small(k) => k as f64 / 2.0,
            Num::Scaled(m, e) => (m as f64 / 1024.0) * 2f64.powi(e as i32 / 2),
            Num::Bits(b) => f64::from_bits(b),
        }
    }
}

/// Which scalar type a run uses.
#[derive(Arbitrary, Debug, Clone, Copy)]
pub enum Kind {
    F32,
    F64,
    Fixed,
}

/// `x` in `T`, keeping NaN and ±∞ for floats (`Scalar::from_f64` turns
/// NaN into 0 and saturates ±∞, so it alone would never feed them in);
/// fixed point gets `from_f64`'s saturation.
pub fn conv<T: Scalar>(x: f64) -> T {
    if T::IS_FLOAT && x.is_nan() {
        // ∞·0.
        T::MAX * T::TWO * T::ZERO
    } else if T::IS_FLOAT && x.is_infinite() {
        let m = if x > 0.0 { T::MAX } else { T::MIN };
        m * T::TWO
    } else {
        T::from_f64(x)
    }
}

pub fn v3<T: Scalar>(n: [Num; 3]) -> Vec3<T> {
    Vec3::new(conv(n[0].value()), conv(n[1].value()), conv(n[2].value()))
}

pub fn vi3<T: Scalar>(p: [i64; 3]) -> Vec3<T> {
    Vec3::new(
        T::from_f64(p[0] as f64),
        T::from_f64(p[1] as f64),
        T::from_f64(p[2] as f64),
    )
}

pub fn vi2<T: Scalar>(p: [i64; 2]) -> Vec2<T> {
    Vec2::new(T::from_f64(p[0] as f64), T::from_f64(p[1] as f64))
}

pub fn f3<T: Scalar>(v: Vec3<T>) -> [f64; 3] {
    [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()]
}

/// The unit roundoff-like constant used in the bounds: `T::EPSILON` (the
/// ulp of 1 for floats, one raw step 2⁻¹⁶ for I16F16).
pub fn eps<T: Scalar>() -> f64 {
    T::EPSILON.to_f64()
}

/// Absolute error of one rounding besides the relative ε: one raw step
/// for fixed point; the smallest subnormal for floats (gradual underflow).
pub fn floor<T: Scalar>() -> f64 {
    if !T::IS_FLOAT {
        T::EPSILON.to_f64()
    } else if T::EPSILON.to_f64() > 1e-10 {
        f32::from_bits(1) as f64
    } else {
        f64::from_bits(1)
    }
}

// ---------------------------------------------------------------------
// Double-double arithmetic (≈ 106-bit significand): references for f64
// code paths. Error-free transformations (Knuth TwoSum, FMA TwoProd).

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dd {
    pub hi: f64,
    pub lo: f64,
}

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

impl Dd {
    pub const ZERO: Dd = Dd { hi: 0.0, lo: 0.0 };
    pub fn new(x: f64) -> Dd {
        Dd { hi: x, lo: 0.0 }
    }
    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }
    pub fn add(self, o: Dd) -> Dd {
        let (s, e) = two_sum(self.hi, o.hi);
        let (t, f) = two_sum(self.lo, o.lo);
        let (s, e) = two_sum(s, e + t);
        let (hi, lo) = two_sum(s, e + f);
        Dd { hi, lo }
    }
    pub fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
    pub fn sub(self, o: Dd) -> Dd {
        self.add(o.neg())
    }
    pub fn mul(self, o: Dd) -> Dd {
        let p = self.hi * o.hi;
        let e = self.hi.mul_add(o.hi, -p);
        let (hi, lo) = two_sum(p, e + (self.hi * o.lo + self.lo * o.hi));
        Dd { hi, lo }
    }
    pub fn div(self, o: Dd) -> Dd {
        let q1 = self.hi / o.hi;
        let r = self.sub(o.mul(Dd::new(q1)));
        let q2 = r.hi / o.hi;
        let r = r.sub(o.mul(Dd::new(q2)));
        let q3 = r.hi / o.hi;
        let (hi, lo) = two_sum(q1, q2);
        Dd { hi, lo }.add(Dd::new(q3))
    }
    pub fn sqrt(self) -> Dd {
        if self.hi <= 0.0 {
            return Dd::ZERO;
        }
        let x = self.hi.sqrt();
        // One Newton step: x + (a − x²)/(2x).
        let xx = Dd::new(x).mul(Dd::new(x));
        let corr = self.sub(xx).hi / (2.0 * x);
        let (hi, lo) = two_sum(x, corr);
        Dd { hi, lo }
    }
    pub fn abs(self) -> Dd {
        if self.hi < 0.0 { self.neg() } else { self }
    }
}

pub fn dd3(v: [f64; 3]) -> [Dd; 3] {
    v.map(Dd::new)
}
pub fn dsub3(a: [Dd; 3], b: [Dd; 3]) -> [Dd; 3] {
    [a[0].sub(b[0]), a[1].sub(b[1]), a[2].sub(b[2])]
}
pub fn ddot3(a: [Dd; 3], b: [Dd; 3]) -> Dd {
    a[0].mul(b[0]).add(a[1].mul(b[1])).add(a[2].mul(b[2]))
}
pub fn dcross(a: [Dd; 3], b: [Dd; 3]) -> [Dd; 3] {
    [
        a[1].mul(b[2]).sub(a[2].mul(b[1])),
        a[2].mul(b[0]).sub(a[0].mul(b[2])),
        a[0].mul(b[1]).sub(a[1].mul(b[0])),
    ]
}
pub fn dnorm(a: [Dd; 3]) -> Dd {
    ddot3(a, a).sqrt()
}

pub fn norm1(v: [f64; 3]) -> f64 {
    v[0].abs() + v[1].abs() + v[2].abs()
}
pub fn norm2(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

// ---------------------------------------------------------------------
// Exact integer geometry.

pub fn isub3(a: [i128; 3], b: [i128; 3]) -> [i128; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub fn icross(a: [i128; 3], b: [i128; 3]) -> [i128; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub fn idot(a: [i128; 3], b: [i128; 3]) -> i128 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
/// Twice the signed area of (a, b, p) in 2D: > 0 when p is left of a→b.
pub fn orient2(a: [i128; 2], b: [i128; 2], p: [i128; 2]) -> i128 {
    (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
}

/// Winding number of the closed polyline `poly` around `p` (exact; `p`
/// must not lie on the polyline): signed crossings of the ray from `p`
/// towards +x, upward edges +1 and downward −1 (Sunday's formulation).
pub fn winding(poly: &[[i128; 2]], p: [i128; 2]) -> i32 {
    let n = poly.len();
    let mut w = 0;
    for i in 0..n {
        let a = poly[i];
        let b = poly[(i + 1) % n];
        if a[1] <= p[1] {
            if b[1] > p[1] && orient2(a, b, p) > 0 {
                w += 1;
            }
        } else if b[1] <= p[1] && orient2(a, b, p) < 0 {
            w -= 1;
        }
    }
    w
}

/// Convex hull (counter-clockwise, y up, no collinear points) of integer
/// points, by Andrew's monotone chain.
pub fn convex_hull(pts: &[[i64; 2]]) -> Vec<[i64; 2]> {
    let mut p: Vec<[i64; 2]> = pts.to_vec();
    p.sort();
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: [i64; 2], a: [i64; 2], b: [i64; 2]| {
        (a[0] - o[0]) as i128 * (b[1] - o[1]) as i128
            - (a[1] - o[1]) as i128 * (b[0] - o[0]) as i128
    };
    let mut h: Vec<[i64; 2]> = Vec::new();
    for &q in &p {
        while h.len() >= 2 && cross(h[h.len() - 2], h[h.len() - 1], q) <= 0 {
            h.pop();
        }
        h.push(q);
    }
    let lower = h.len() + 1;
    for &q in p.iter().rev().skip(1) {
        while h.len() >= lower && cross(h[h.len() - 2], h[h.len() - 1], q) <= 0 {
            h.pop();
        }
        h.push(q);
    }
    h.pop();
    h
}
