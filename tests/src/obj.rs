//! A tiny Wavefront OBJ reader: `v` and `f` lines only, enough for the
//! bunny of workloads W1/W2. Faces with more than three vertices are
//! fanned into triangles; `f a/b/c` forms keep only the position index;
//! negative (relative) indices are resolved. Everything else is ignored.

use std::fmt;

/// A triangle mesh: positions and 0-based triangle indices.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions as written in the file.
    pub positions: Vec<[f64; 3]>,
    /// Triangles, counter-clockwise as in the file.
    pub triangles: Vec<[u32; 3]>,
}

/// Why an OBJ text could not be read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ObjError {
    /// A `v` line without three numbers.
    BadVertex {
        /// 1-based line number.
        line: usize,
    },
    /// An `f` line with fewer than three indices, or an index that is not
    /// a number, is zero, or refers to a vertex that does not exist.
    BadFace {
        /// 1-based line number.
        line: usize,
    },
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::BadVertex { line } => write!(f, "line {line}: malformed `v` line"),
            Self::BadFace { line } => write!(f, "line {line}: malformed `f` line"),
        }
    }
}

impl std::error::Error for ObjError {}

/// Parses OBJ text.
///
/// # Errors
/// [`ObjError`] for a malformed `v` or `f` line. Faces may refer only to
/// vertices defined before them (as the OBJ format requires).
pub fn parse(text: &str) -> Result<Mesh, ObjError> {
    let mut mesh = Mesh::default();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let mut words = raw.split_whitespace();
        match words.next() {
            Some("v") => {
                let mut p = [0.0; 3];
                for c in &mut p {
                    *c = words
                        .next()
                        .and_then(|w| w.parse().ok())
                        .ok_or(ObjError::BadVertex { line })?;
                }
                mesh.positions.push(p);
            }
            Some("f") => {
                let n = mesh.positions.len() as i64;
                let mut idx = Vec::with_capacity(4);
                for w in words {
                    let first = w.split('/').next().unwrap_or("");
                    let k: i64 = first.parse().map_err(|_| ObjError::BadFace { line })?;
                    // 1-based, or negative = relative to the end.
                    let k = if k > 0 { k - 1 } else { n + k };
                    if k < 0 || k >= n {
                        return Err(ObjError::BadFace { line });
                    }
                    idx.push(k as u32);
                }
                if idx.len() < 3 {
                    return Err(ObjError::BadFace { line });
                }
                for j in 1..idx.len() - 1 {
                    mesh.triangles.push([idx[0], idx[j], idx[j + 1]]);
                }
            }
            _ => {}
        }
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_quads_slashes_and_relative_indices() {
        let m = parse("# c\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1/1 2//2 3 4\nf -4 -3 -2\n")
            .unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 1, 2]]);
    }

    #[test]
    fn rejects_bad_lines() {
        assert_eq!(parse("v 1 2\n"), Err(ObjError::BadVertex { line: 1 }));
        assert_eq!(
            parse("v 0 0 0\nf 1 2 3\n"),
            Err(ObjError::BadFace { line: 2 })
        );
        assert_eq!(
            parse("v 0 0 0\nf 1 1\n"),
            Err(ObjError::BadFace { line: 2 })
        );
        assert_eq!(
            parse("v 0 0 0\nf 0 1 1\n"),
            Err(ObjError::BadFace { line: 2 })
        );
    }
}
