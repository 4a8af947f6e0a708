//! `ray_plane`: `Plane::new` and `Plane::intersect` in f32, f64 and I16F16
//! with arbitrary, parallel and in-plane rays.
//!
//! Oracle: construction fails exactly for non-finite input or a zero
//! normal; a returned `t` is finite and `> t_min`; a ray with `m·d = 0`
//! exactly for the normal m as given (parallel or in the plane; checked in
//! i128 on the dyadic values where they span at most 18 binades) is no
//! hit; and whenever the
//! double-double reference `t* = u·(P − Q) / u·d` (u = n/|n| from the
//! stored inputs) is well defined, the result agrees with it within the
//! error bound of the three operations involved (normalizing n, two dot
//! products of differences, one division):
//!
//! ```text
//! |t − t*| ≤ 8ε·(Σ|u_i||r_i| + |t*|·Σ|u_i||d_i|)/|u·d| + 8f·(3 + Σ|r_i| + |t*|(3 + Σ|d_i|))/|u·d| + 2ε|t*| + 2f
//! ```
//!
//! with r = P − Q, ε = `T::EPSILON` and f the absolute error of one
//! rounding: the fixed-point step, or for floats the smallest subnormal
//! (gradual underflow, e.g. a normal component below the range after
//! normalizing). A missing hit is allowed only where the bound cannot decide
//! (t* within the bound of t_min, |u·d| within its own error of 0) or an
//! intermediate leaves the range of the type (documented as no hit).
#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::{Dd, Kind, Num, dd3, ddot3, dsub3, eps, f3, floor};
use libfuzzer_sys::fuzz_target;
use sightline::math::Vec3;
use sightline::ray::{Plane, PlaneError, Ray};
use sightline::scalar::{I16F16, Scalar};

#[derive(Arbitrary, Debug)]
enum Dir {
    Free([Num; 3]),
    /// d = n × w: exactly parallel (for small inputs).
    Parallel([Num; 3]),
    /// Origin P + n × w1 and d = n × w2: in the plane.
    InPlane([Num; 3], [Num; 3]),
}

#[derive(Arbitrary, Debug)]
struct Input {
    kind: Kind,
    point: [Num; 3],
    normal: [Num; 3],
    origin: [Num; 3],
    dir: Dir,
    t_min: Num,
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn conv<T: Scalar>(v: [f64; 3]) -> Vec3<T> {
    Vec3::new(T::from_f64(v[0]), T::from_f64(v[1]), T::from_f64(v[2]))
}

fn run<T: Scalar>(input: &Input) {
    let p: Vec3<T> = common::v3(input.point);
    let n: Vec3<T> = common::v3(input.normal);
    let plane = Plane::new(p, n);
    let (pf, nf) = (f3(p), f3(n));
    let finite = pf.iter().chain(&nf).all(|v| v.is_finite());
    let plane = match plane {
        Ok(pl) => {
            assert!(
                finite && nf.iter().any(|&c| c != 0.0),
                "{}: plane accepted {pf:?} {nf:?}",
                T::NAME
            );
            pl
        }
        Err(PlaneError::NonFinite) => {
            assert!(!finite, "{}: NonFinite for finite input", T::NAME);
            return;
        }
        Err(e) => {
            assert!(
                finite && nf.iter().all(|&c| c == 0.0),
                "{}: {e:?} for {nf:?}",
                T::NAME
            );
            return;
        }
    };
    let (q, d): (Vec3<T>, Vec3<T>) = match &input.dir {
        Dir::Free(d) => (common::v3(input.origin), common::v3(*d)),
        Dir::Parallel(w) => (
            common::v3(input.origin),
            conv(cross(nf, f3(common::v3::<T>(*w)))),
        ),
        Dir::InPlane(w1, w2) => {
            let a = cross(nf, f3(common::v3::<T>(*w1)));
            (
                conv([pf[0] + a[0], pf[1] + a[1], pf[2] + a[2]]),
                conv(cross(nf, f3(common::v3::<T>(*w2)))),
            )
        }
    };
    let Ok(ray) = Ray::new(q, d) else {
        return;
    };
    let t_min: T = common::conv(input.t_min.value());
    if !t_min.is_finite() {
        return;
    }
    let got = plane.intersect(&ray, t_min);
    if let Some(t) = got {
        assert!(
            t.is_finite() && t > t_min,
            "{}: t = {t:?}, t_min = {t_min:?}",
            T::NAME
        );
    }
    // Exactly parallel or in the plane (m·d = 0 for the normal as given,
    // decided in i128 where the six values span few enough binades): no hit.
    if exact_dot_is_zero(nf, f3(d)) == Some(true) {
        assert!(
            got.is_none(),
            "{}: m·d = 0 exactly for m {nf:?}, d {:?}, but t = {got:?}",
            T::NAME,
            f3(d)
        );
    }
    // Double-double reference with u = n/|n| (scaled by a power of two
    // first so nothing overflows).
    let (qf, df) = (f3(q), f3(d));
    let nmax = nf.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let k = 2f64.powi(-(nmax.log2().floor() as i32));
    let ns = dd3([nf[0] * k, nf[1] * k, nf[2] * k]);
    let nl = ddot3(ns, ns).sqrt();
    let u = ns.map(|c| c.div(nl));
    let r = dsub3(dd3(pf), dd3(qf));
    let num = ddot3(u, r).to_f64();
    let den = ddot3(u, dd3(df)).to_f64();
    if !(num.is_finite() && den.is_finite()) {
        return;
    }
    let uf = u.map(|c| c.to_f64());
    let rf = r.map(|c| c.to_f64());
    let (e, fl) = (eps::<T>(), floor::<T>());
    let ur: f64 = (0..3).map(|i| uf[i].abs() * rf[i].abs()).sum();
    let ud: f64 = (0..3).map(|i| uf[i].abs() * df[i].abs()).sum();
    let r1: f64 = rf.iter().map(|v| v.abs()).sum();
    let d1: f64 = df.iter().map(|v| v.abs()).sum();
    let den_err = 8.0 * e * ud + 8.0 * fl * (3.0 + d1);
    if den.abs() <= 2.0 * den_err {
        // Parallel to within rounding: only finiteness (checked above).
        return;
    }
    let t_ref = num / den;
    let bound = (8.0 * e * (ur + t_ref.abs() * ud)
        + 8.0 * fl * (3.0 + r1 + t_ref.abs() * (3.0 + d1)))
        / den.abs()
        + 2.0 * e * t_ref.abs()
        + 2.0 * fl;
    if !(bound.is_finite() && t_ref.is_finite()) {
        return;
    }
    let tm = t_min.to_f64();
    match got {
        Some(t) => {
            let t = t.to_f64();
            assert!(
                (t - t_ref).abs() <= bound,
                "{}: t = {t}, reference {t_ref}, |diff| {} > bound {bound}",
                T::NAME,
                (t - t_ref).abs()
            );
        }
        None => {
            let max = T::MAX.to_f64();
            // Range: the difference, the numerator or the quotient may
            // leave the type (documented as no hit).
            let out_of_range = rf.iter().any(|v| v.abs() >= max * 0.99)
                || ur >= max * 0.99
                || ud >= max * 0.99
                || t_ref.abs() + bound >= max * 0.99;
            assert!(
                t_ref <= tm + bound || out_of_range,
                "{}: no hit, reference t = {t_ref} (t_min {tm}, bound {bound})",
                T::NAME
            );
        }
    }
    let _ = Dd::ZERO;
}

/// Whether `a·b = 0` exactly, for finite dyadic inputs: each product is
/// `m·2^e` with `m < 2^106`; shifted to the smallest exponent the three fit
/// an i128 when the exponents span at most 18 bits. `None` otherwise.
fn exact_dot_is_zero(a: [f64; 3], b: [f64; 3]) -> Option<bool> {
    fn parts(x: f64) -> Option<(i128, i32)> {
        if !x.is_finite() {
            return None;
        }
        if x == 0.0 {
            return Some((0, 0));
        }
        // x = m·2^e with |m| < 2^53: scale by powers of two (exact).
        let mut e = 0;
        let mut y = x;
        while y.fract() != 0.0 {
            y *= 2.0;
            e -= 1;
        }
        while y.abs() >= 9007199254740992.0 {
            y /= 2.0;
            e += 1;
        }
        Some((y as i128, e))
    }
    let mut terms = Vec::new();
    for i in 0..3 {
        let (ma, ea) = parts(a[i])?;
        let (mb, eb) = parts(b[i])?;
        if ma != 0 && mb != 0 {
            terms.push((ma * mb, ea + eb));
        }
    }
    let Some(lo) = terms.iter().map(|t| t.1).min() else {
        return Some(true);
    };
    if terms.iter().any(|t| t.1 - lo > 18) {
        return None;
    }
    Some(terms.iter().map(|t| t.0 << (t.1 - lo)).sum::<i128>() == 0)
}

fuzz_target!(|input: Input| {
    match input.kind {
        Kind::F32 => run::<f32>(&input),
        Kind::F64 => run::<f64>(&input),
        Kind::Fixed => run::<I16F16>(&input),
    }
});
