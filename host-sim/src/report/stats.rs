//! Error and timing summaries.

/// Maximum and mean of per-input errors.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrStats {
    /// Largest error.
    pub max: f64,
    /// Mean error.
    pub mean: f64,
    /// How many inputs were measured.
    pub count: usize,
}

impl ErrStats {
    /// The summary of `errors`; `None` if there are none. A non-finite
    /// error makes the maximum infinite (it is reported, not hidden).
    pub fn of(errors: &[f64]) -> Option<Self> {
        if errors.is_empty() {
            return None;
        }
        let mut max = 0.0f64;
        let mut sum = 0.0;
        for &e in errors {
            let e = if e.is_finite() { e } else { f64::INFINITY };
            max = max.max(e);
            sum += e;
        }
        Some(Self {
            max,
            mean: sum / errors.len() as f64,
            count: errors.len(),
        })
    }
}

/// Host time per operation over repeated passes, in nanoseconds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timing {
    /// Median pass.
    pub median: f64,
    /// 25th percentile.
    pub q1: f64,
    /// 75th percentile.
    pub q3: f64,
    /// Fastest pass.
    pub min: f64,
    /// Slowest pass.
    pub max: f64,
}

impl Timing {
    /// Zeros, until [`super::finish`] runs the benchmark.
    pub const PENDING: Self = Self {
        median: 0.0,
        q1: 0.0,
        q3: 0.0,
        min: 0.0,
        max: 0.0,
    };

    /// Summarizes per-pass figures (at least one).
    pub fn from_samples(mut s: Vec<f64>) -> Self {
        if s.is_empty() {
            s.push(0.0);
        }
        s.sort_by(f64::total_cmp);
        let q = |p: f64| {
            // Linear interpolation between order statistics.
            let x = p * (s.len() - 1) as f64;
            let (i, f) = (x.floor() as usize, x.fract());
            let j = (i + 1).min(s.len() - 1);
            s[i] + (s[j] - s[i]) * f
        };
        Self {
            median: q(0.5),
            q1: q(0.25),
            q3: q(0.75),
            min: s[0],
            max: s[s.len() - 1],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quartiles_of_known_samples() {
        let t = Timing::from_samples(vec![5.0, 1.0, 3.0, 2.0, 4.0]);
        assert_eq!(
            (t.min, t.q1, t.median, t.q3, t.max),
            (1.0, 2.0, 3.0, 4.0, 5.0)
        );
        let e = ErrStats::of(&[0.0, 2.0, 1.0]).unwrap();
        assert_eq!((e.max, e.mean, e.count), (2.0, 1.0, 3));
        assert!(ErrStats::of(&[]).is_none());
    }
}
