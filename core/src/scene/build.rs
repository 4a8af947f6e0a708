//! Building scene descriptions by hand: a [`Scene`] constructor with
//! defaults, and mesh quantizing that runs at compile time.

use super::{CameraSpec, Color, Light, ProjectionSpec, Scene, SceneObject, SceneSphere};

impl Light {
    /// Light from above-right-front, `(0.4, 1.0, 0.6)`, with ambient 0.2
    /// and diffuse 0.8 (the host simulator's scene-file default).
    pub const DEFAULT: Self = Self {
        direction: [0.4, 1.0, 0.6],
        ambient: 0.2,
        diffuse: 0.8,
    };
}

impl<'a> Scene<'a> {
    /// A scene of `objects` seen by `camera`, with the defaults of a scene
    /// file: a 60° horizontal field of view, depth range 0.1 to 100,
    /// [`Light::DEFAULT`], a black background, no spheres and no name.
    /// Change a part with the `with_*` methods (all `const`, so a firmware
    /// scene can be a `static`).
    ///
    /// ```
    /// # #[cfg(feature = "demo")] {
    /// use sightline::scene::{CameraSpec, Color, Light, Scene, builtin};
    ///
    /// static SCENE: Scene<'static> = Scene::new(
    ///     CameraSpec::LookAt { eye: [3.0, 2.0, -4.0], target: [0.0; 3], up: [0.0, 1.0, 0.0] },
    ///     builtin::CUBE.objects,
    /// )
    /// .with_background(Color::new(4, 8, 12));
    /// assert_eq!(SCENE.light, Light::DEFAULT);
    /// assert!(SCENE.validate().is_ok());
    /// # }
    /// ```
    #[must_use]
    pub const fn new(camera: CameraSpec, objects: &'a [SceneObject<'a>]) -> Self {
        Self {
            name: "",
            description: "",
            camera,
            projection: ProjectionSpec::Perspective {
                fov_x: core::f32::consts::FRAC_PI_3,
            },
            near: 0.1,
            far: 100.0,
            light: Light::DEFAULT,
            background: Color::new(0, 0, 0),
            objects,
            spheres: &[],
        }
    }

    /// The same scene with a name and a one-line description.
    #[must_use]
    pub const fn with_name(mut self, name: &'a str, description: &'a str) -> Self {
        self.name = name;
        self.description = description;
        self
    }

    /// The same scene with `projection`.
    #[must_use]
    pub const fn with_projection(mut self, projection: ProjectionSpec) -> Self {
        self.projection = projection;
        self
    }

    /// The same scene with depth range `near..far` (view z; checked when
    /// rendering: `0 < near < far`, both finite).
    #[must_use]
    pub const fn with_depth_range(mut self, near: f32, far: f32) -> Self {
        self.near = near;
        self.far = far;
        self
    }

    /// The same scene lit by `light`.
    #[must_use]
    pub const fn with_light(mut self, light: Light) -> Self {
        self.light = light;
        self
    }

    /// The same scene with `background` where nothing is drawn.
    #[must_use]
    pub const fn with_background(mut self, background: Color) -> Self {
        self.background = background;
        self
    }

    /// The same scene with `spheres` (drawn by the ray path only).
    #[must_use]
    pub const fn with_spheres(mut self, spheres: &'a [SceneSphere]) -> Self {
        self.spheres = spheres;
        self
    }
}

/// Mesh positions quantized to `i16` steps of one power-of-two
/// [`scale`](Self::scale), the form [`MeshData`](super::MeshData) stores.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuantizedPositions<const N: usize> {
    /// Position `k` is `positions[k] · scale`.
    pub positions: [[i16; 3]; N],
    /// World units per step: the smallest power of two (down to 2⁻⁶⁰) for
    /// which the largest coordinate magnitude fits in ±32767 steps.
    pub scale: f32,
}

/// Quantizes f32 positions for a [`MeshData`](super::MeshData), at compile
/// time when called in a `const` or `static`: the step is a power of two,
/// so `positions[k] · scale` is exact in f32, and every coordinate is
/// rounded to the nearest step (ties away from zero), an error of at most
/// half a step.
///
/// A non-finite coordinate is a compile error in a `const` (a panic when
/// called at run time). A mesh whose triangles collapse at this step (one
/// far outlier makes the step coarse) is refused later by
/// [`Scene::prepare`](super::Scene::prepare) or
/// [`PreparedMesh::new`](super::PreparedMesh::new) only if it becomes
/// degenerate; check the step yourself for very uneven meshes.
///
/// ```
/// use sightline::scene::{MeshData, QuantizedPositions, quantize_positions};
///
/// const Q: QuantizedPositions<3> =
///     quantize_positions([[0.0, 0.0, 0.0], [1.5, 0.0, 0.0], [0.0, -0.75, 2.0]]);
/// static TRIANGLE: MeshData<'static> = MeshData {
///     closed: false,
///     positions: &Q.positions,
///     scale: Q.scale,
///     triangles: &[[0, 1, 2]],
///     normals: None,
///     uvs: None,
/// };
/// // The largest magnitude, 2.0, gets a step of 2⁻¹³: 16384 steps (at
/// // 2⁻¹⁴ it would be 32768, one more than an i16 holds).
/// assert_eq!(Q.scale, 1.0 / 8192.0);
/// assert_eq!(TRIANGLE.positions[2], [0, -6144, 16384]);
/// ```
#[must_use]
pub const fn quantize_positions<const N: usize>(positions: [[f32; 3]; N]) -> QuantizedPositions<N> {
    let mut max = 0.0f32;
    let mut i = 0;
    while i < N {
        let mut a = 0;
        while a < 3 {
            let v = positions[i][a];
            assert!(
                v.is_finite(),
                "quantize_positions: a coordinate is not finite"
            );
            let m = v.abs();
            if m > max {
                max = m;
            }
            a += 1;
        }
        i += 1;
    }
    // The smallest power-of-two step with max / step ≤ 32767.
    let mut scale = 1.0f32;
    while max / scale > 32767.0 {
        scale *= 2.0;
    }
    let mut k = 0;
    while k < 60 && max / (scale * 0.5) <= 32767.0 {
        scale *= 0.5;
        k += 1;
    }
    let mut out = [[0i16; 3]; N];
    let mut i = 0;
    while i < N {
        let mut a = 0;
        while a < 3 {
            // Division by a power of two is exact, and so is adding ½ in
            // f64 (|q| ≤ 32767.5 with 24 significant bits; in f32 it could
            // round 0.5 − 2⁻²⁵ up). The cast truncates toward zero, so ±½
            // first rounds half away.
            let q = positions[i][a] as f64 / scale as f64;
            let r = if q < 0.0 { q - 0.5 } else { q + 0.5 };
            out[i][a] = r as i16;
            a += 1;
        }
        i += 1;
    }
    QuantizedPositions {
        positions: out,
        scale,
    }
}

/// Quantizes unit vertex normals to the `i16` units of 1/32767 that
/// [`MeshData::normals`](super::MeshData::normals) stores, at compile time
/// when called in a `const` or `static`. Components are rounded to the
/// nearest unit (ties away from zero) and clamped to ±32767; the vectors
/// are not renormalized (the renderer normalizes after transforming).
/// A non-finite component is a compile error in a `const`.
///
/// ```
/// use sightline::scene::quantize_normals;
///
/// const N: [[i16; 3]; 2] = quantize_normals([[0.0, 1.0, 0.0], [0.6, 0.0, -0.8]]);
/// assert_eq!(N, [[0, 32767, 0], [19660, 0, -26214]]);
/// ```
#[must_use]
pub const fn quantize_normals<const N: usize>(normals: [[f32; 3]; N]) -> [[i16; 3]; N] {
    let mut out = [[0i16; 3]; N];
    let mut i = 0;
    while i < N {
        let mut a = 0;
        while a < 3 {
            let v = normals[i][a];
            assert!(v.is_finite(), "quantize_normals: a component is not finite");
            // Exact in f64: 24 + 15 significant bits, then + ½.
            let q = v as f64 * 32767.0;
            let r = if q < 0.0 { q - 0.5 } else { q + 0.5 };
            let r = if r > 32767.0 {
                32767.0
            } else if r < -32767.0 {
                -32767.0
            } else {
                r
            };
            out[i][a] = r as i16;
            a += 1;
        }
        i += 1;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An independent oracle in f64: the step is the smallest power of two
    /// 2^e with max·2^−e ≤ 32767, and each coordinate rounds half away.
    fn oracle(p: &[[f32; 3]]) -> (f64, std::vec::Vec<[i16; 3]>) {
        let max = p
            .iter()
            .flatten()
            .fold(0.0f64, |m, &v| m.max(f64::from(v).abs()));
        let mut e = -60i32;
        while max / 2f64.powi(e) > 32767.0 {
            e += 1;
        }
        let s = 2f64.powi(e);
        let q = p
            .iter()
            .map(|v| v.map(|c| (f64::from(c) / s).round() as i16))
            .collect();
        (s, q)
    }

    #[test]
    fn positions_match_an_f64_oracle() {
        let cases: [[[f32; 3]; 4]; 4] = [
            [
                [0.0; 3],
                [1.0, -1.0, 0.5],
                [0.25, 0.125, -0.0625],
                [0.3, 0.7, -0.9],
            ],
            [
                [1e6, 0.0, 0.0],
                [-3.0, 2.5, 1.0],
                [0.0; 3],
                [7.25, -7.25, 1.0],
            ],
            [
                [1e-12, 0.0, 0.0],
                [0.0; 3],
                [-5e-13, 2.5e-13, 0.0],
                [0.0; 3],
            ],
            // 32767 fits with step 1; 32767.5 needs step 2.
            [
                [32767.0, 0.0, 0.0],
                [-32767.0, 1.5, 2.5],
                [0.0; 3],
                [1.0; 3],
            ],
        ];
        // Step 1, and a coordinate just below a half step (0.5 − 2⁻²⁵).
        let q = quantize_positions([[32767.0, 0.0, 0.0], [0.49999997, -0.49999997, 1.5]]);
        assert_eq!(q.scale, 1.0);
        assert_eq!(q.positions[1], [0, 0, 2]);
        for p in cases {
            let q = quantize_positions(p);
            let (s, o) = oracle(&p);
            assert_eq!(f64::from(q.scale), s, "{p:?}");
            assert_eq!(q.positions.as_slice(), o.as_slice(), "{p:?}");
            // Within half a step, exactly representable.
            for (a, b) in p.iter().zip(q.positions) {
                for k in 0..3 {
                    let back = f64::from(b[k]) * s;
                    assert!((back - f64::from(a[k])).abs() <= s / 2.0, "{a:?}");
                }
            }
        }
        let q = quantize_positions([[32767.5, 0.0, 0.0]]);
        assert_eq!((q.scale, q.positions[0][0]), (2.0, 16384));
        let q = quantize_positions([[0.0f32; 3]; 2]);
        assert_eq!(q.positions, [[0; 3]; 2]);
    }

    #[test]
    fn normals_round_and_clamp() {
        let n = quantize_normals([[1.0, -1.0, 0.5], [2.0, -2.0, 1e-9]]);
        assert_eq!(n, [[32767, -32767, 16384], [32767, -32767, 0]]);
        // Just below a half unit: 0.5 − 2⁻²⁵ units must round down (an f32
        // `q + 0.5` would round it up).
        let just_below = ((0.5f64 - 2f64.powi(-25)) / 32767.0) as f32;
        let q = f64::from(just_below) * 32767.0;
        assert!(q < 0.5);
        assert_eq!(
            quantize_normals([[just_below, -just_below, 0.0]]),
            [[0, 0, 0]]
        );
    }
}
