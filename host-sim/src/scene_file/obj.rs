//! OBJ meshes: a line-by-line check of the text (tobj reports no line
//! numbers), loading with tobj, and quantization to core's i16 form with
//! a check that no triangle collapses.

use super::FileError;
use std::path::Path;

/// An owned mesh in core's quantized form.
#[derive(Clone, Debug, Default)]
pub struct OwnedMesh {
    /// Quantized positions.
    pub positions: Vec<[i16; 3]>,
    /// World units per step.
    pub scale: f32,
    /// Triangles.
    pub triangles: Vec<[u16; 3]>,
    /// Vertex normals (1/32767).
    pub normals: Option<Vec<[i16; 3]>>,
    /// Texture coordinates in [0, 1] (OBJ convention, v up), converted to
    /// texels once the texture size is known.
    pub texcoords: Option<Vec<[f32; 2]>>,
    /// Every edge is used once in each direction: a closed, consistently
    /// oriented surface (its back faces are culled).
    pub closed: bool,
}

/// Whether every directed edge `(a, b)` of `tris` appears exactly once and
/// its reverse `(b, a)` too: the mesh is closed and consistently wound.
#[must_use]
pub fn is_closed(tris: &[[u16; 3]]) -> bool {
    let mut edges = std::collections::HashMap::with_capacity(tris.len() * 3);
    for t in tris {
        for i in 0..3 {
            let e = (t[i], t[(i + 1) % 3]);
            if e.0 == e.1 || edges.insert(e, ()).is_some() {
                return false;
            }
        }
    }
    !tris.is_empty() && edges.keys().all(|&(a, b)| edges.contains_key(&(b, a)))
}

/// The words of `line` with their 1-based columns.
fn words(line: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in line.char_indices().chain([(line.len(), ' ')]) {
        match (c.is_whitespace(), start) {
            (true, Some(s)) => {
                out.push((line[..s].chars().count() + 1, &line[s..i]));
                start = None;
            }
            (false, None) => start = Some(i),
            _ => {}
        }
    }
    out
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Whether the polygon `p` is convex in its plane: for every edge, no
/// other vertex lies on its outer side (a star polygon fails too).
/// A polygon of zero area counts as convex (its fan triangles are empty).
fn is_convex(p: &[[f64; 3]]) -> bool {
    // Newell's normal: the polygon's area vector.
    let mut n = [0.0; 3];
    for (i, a) in p.iter().enumerate() {
        let b = p[(i + 1) % p.len()];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    let len = norm(n);
    if len == 0.0 {
        return true;
    }
    let n = n.map(|c| c / len);
    for (i, &a) in p.iter().enumerate() {
        let e = sub(p[(i + 1) % p.len()], a);
        for &c in p {
            let d = sub(c, a);
            if dot(cross(e, d), n) < -1e-6 * norm(e) * norm(d) {
                return false;
            }
        }
    }
    true
}

/// Checks an OBJ text line by line, so that what tobj would reject or get
/// wrong is reported with its line and column: numbers that do not parse
/// or are NaN or infinite, wrong counts of numbers, bad face indices,
/// faces with fewer than three vertices and non-convex faces (tobj
/// triangulates them as fans, which is wrong for a non-convex polygon).
fn check_obj_text(path: &Path, text: &str) -> Result<(), FileError> {
    let err = |line: usize, col: usize, message: String| FileError {
        file: path.to_path_buf(),
        line,
        col,
        message,
    };
    let mut pos: Vec<[f64; 3]> = Vec::new();
    let (mut nt, mut nn) = (0usize, 0usize);
    for (ln, line) in text.lines().enumerate() {
        let ln = ln + 1;
        let words = words(line);
        let Some(&(key_col, key)) = words.first() else {
            continue;
        };
        let args = &words[1..];
        match key {
            "v" | "vt" | "vn" => {
                let what = match key {
                    "v" => "vertex coordinate",
                    "vt" => "texture coordinate",
                    _ => "normal component",
                };
                let mut vals = Vec::with_capacity(args.len());
                for &(col, w) in args {
                    let Ok(x) = w.parse::<f32>() else {
                        return Err(err(
                            ln,
                            col,
                            format!("bad {what} {w:?}: expected a decimal number"),
                        ));
                    };
                    if !x.is_finite() {
                        return Err(err(ln, col, format!("{what} is NaN or infinite ({w})")));
                    }
                    vals.push(x);
                }
                let (ok, expected) = match key {
                    "v" => (
                        matches!(vals.len(), 3 | 4 | 6),
                        "x y z, x y z w or x y z r g b",
                    ),
                    "vt" => (matches!(vals.len(), 2 | 3), "u v or u v w"),
                    _ => (vals.len() == 3, "x y z"),
                };
                if !ok {
                    return Err(err(
                        ln,
                        key_col,
                        format!("`{key}` with {} numbers: expected {expected}", vals.len()),
                    ));
                }
                match key {
                    "v" => {
                        let w = if vals.len() == 4 { vals[3] } else { 1.0 };
                        let p = [vals[0] / w, vals[1] / w, vals[2] / w];
                        if w == 0.0 || !p.iter().all(|c| c.is_finite()) {
                            let col = if vals.len() == 4 { args[3].0 } else { key_col };
                            return Err(err(
                                ln,
                                col,
                                format!(
                                    "vertex weight w = {w} makes a coordinate NaN or infinite: expected a non-zero w"
                                ),
                            ));
                        }
                        pos.push(p.map(f64::from));
                    }
                    "vt" => nt += 1,
                    _ => nn += 1,
                }
            }
            "f" | "l" => {
                let counts = [pos.len(), nt, nn];
                let mut face = Vec::with_capacity(args.len());
                for &(col, w) in args {
                    let parts: Vec<&str> = w.split('/').collect();
                    if parts.len() > 3 || parts[0].is_empty() {
                        return Err(err(
                            ln,
                            col,
                            format!("bad face vertex {w:?}: expected v, v/vt, v//vn or v/vt/vn"),
                        ));
                    }
                    for (k, part) in parts.iter().enumerate() {
                        if part.is_empty() {
                            continue;
                        }
                        let count = counts[k];
                        let kind = ["vertex", "texture coordinate", "normal"][k];
                        let index = part.parse::<i64>().ok().and_then(|i| {
                            let c = count as i64;
                            if i > 0 && i <= c {
                                Some((i - 1) as usize)
                            } else if i < 0 && -i <= c {
                                Some((c + i) as usize)
                            } else {
                                None
                            }
                        });
                        let Some(index) = index else {
                            let message = if count == 0 {
                                let (kinds, line) = [
                                    ("vertices", "v"),
                                    ("texture coordinates", "vt"),
                                    ("normals", "vn"),
                                ][k];
                                format!(
                                    "bad face index {part:?}: there are no {kinds} (`{line}` lines) before this face"
                                )
                            } else {
                                format!(
                                    "bad face index {part:?}: expected a {kind} index in 1..={count} (or -1..=-{count})"
                                )
                            };
                            return Err(err(ln, col, message));
                        };
                        if k == 0 {
                            face.push(pos[index]);
                        }
                    }
                }
                if key == "f" && face.len() < 3 {
                    return Err(err(
                        ln,
                        key_col,
                        format!(
                            "face with {} vertices: expected at least 3 (use `l` for lines)",
                            face.len()
                        ),
                    ));
                }
                if key == "f" && face.len() > 3 && !is_convex(&face) {
                    return Err(err(
                        ln,
                        key_col,
                        format!(
                            "face with {} vertices is not convex in its plane: expected a convex polygon (split it into triangles)",
                            face.len()
                        ),
                    ));
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// How many triangles have a non-zero area in `f` but zero area in the
/// quantized `q`.
fn collapsed(f: &[[f32; 3]], q: &[[i16; 3]], tris: &[[u16; 3]]) -> usize {
    tris.iter()
        .filter(|t| {
            let [a, b, c] = t.map(|k| f[k as usize].map(f64::from));
            let area_f = cross(sub(b, a), sub(c, a));
            let [a, b, c] = t.map(|k| q[k as usize].map(i64::from));
            let (e1, e2) = (
                [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
                [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
            );
            let area_q = [
                e1[1] * e2[2] - e1[2] * e2[1],
                e1[2] * e2[0] - e1[0] * e2[2],
                e1[0] * e2[1] - e1[1] * e2[0],
            ];
            area_f != [0.0; 3] && area_q == [0; 3]
        })
        .count()
}

/// Loads an OBJ file into core's quantized form, with `scale` (> 0)
/// applied.
///
/// # Errors
/// [`FileError`] naming the OBJ file, with the line and column where the
/// error has one (line 0 otherwise: a tobj error the line check did not
/// catch, no faces, too many vertices, triangles that collapse when
/// quantized).
pub fn load_obj(path: &Path, scale: f32) -> Result<OwnedMesh, FileError> {
    let err = |message: String| FileError {
        file: path.to_path_buf(),
        line: 0,
        col: 0,
        message,
    };
    if !(scale.is_finite() && scale > 0.0) {
        return Err(err(format!("scale {scale}: expected a finite number > 0")));
    }
    let text = std::fs::read_to_string(path).map_err(|e| err(format!("cannot read: {e}")))?;
    check_obj_text(path, &text)?;
    let opts = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _materials) =
        tobj::load_obj(path, &opts).map_err(|e| err(format!("not a valid OBJ file: {e}")))?;
    let mut pos: Vec<[f32; 3]> = Vec::new();
    let mut normals: Vec<[f32; 3]> = Vec::new();
    let mut tcs: Vec<[f32; 2]> = Vec::new();
    let mut tris: Vec<[u32; 3]> = Vec::new();
    let all_normals = models.iter().all(|m| !m.mesh.normals.is_empty());
    let all_tc = models.iter().all(|m| !m.mesh.texcoords.is_empty());
    for m in &models {
        let base = pos.len() as u32;
        let mesh = &m.mesh;
        pos.extend(mesh.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        if all_normals {
            normals.extend(mesh.normals.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        }
        if all_tc {
            tcs.extend(mesh.texcoords.chunks_exact(2).map(|p| [p[0], p[1]]));
        }
        tris.extend(
            mesh.indices
                .chunks_exact(3)
                .map(|t| [base + t[0], base + t[1], base + t[2]]),
        );
    }
    if pos.is_empty() || tris.is_empty() {
        return Err(err(
            "no faces: expected at least one `f` line with 3 or more vertices".to_string(),
        ));
    }
    if pos.len() > 65536 {
        return Err(err(format!(
            "{} vertices: expected at most 65536 (u16 indices)",
            pos.len()
        )));
    }
    let m = pos
        .iter()
        .flat_map(|p| p.iter().map(|c| c.abs()))
        .fold(0f32, f32::max);
    if !pos.iter().flatten().all(|c| c.is_finite()) {
        // The line check refuses these; this guards against tobj
        // reading the numbers differently.
        return Err(err("a vertex coordinate is NaN or infinite".to_string()));
    }
    if m == 0.0 {
        return Err(err(
            "every vertex is at the origin: expected a mesh with an extent".to_string(),
        ));
    }
    // 30 000 steps for the largest coordinate: inside i16, exact in I16F16.
    let step = m / 30000.0;
    let positions: Vec<[i16; 3]> = pos
        .iter()
        .map(|p| p.map(|c| (c / step).round() as i16))
        .collect();
    let triangles: Vec<[u16; 3]> = tris.iter().map(|t| t.map(|k| k as u16)).collect();
    let lost = collapsed(&pos, &positions, &triangles);
    if lost > 0 {
        return Err(err(format!(
            "{lost} of {} triangles collapse when quantized: the largest coordinate {m} forces a step of {step} \
             (positions are quantized to 30000 steps of the largest coordinate; expected no stray far vertex)",
            triangles.len()
        )));
    }
    let normals = if all_normals && normals.len() == pos.len() {
        normals
    } else {
        area_weighted_normals(&positions, &triangles)
    };
    let normals = normals
        .iter()
        .map(|n| {
            let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            let l = if l > 0.0 && l.is_finite() { l } else { 1.0 };
            n.map(|c| (c / l * 32767.0).round() as i16)
        })
        .collect();
    Ok(OwnedMesh {
        positions,
        scale: step * scale,
        closed: is_closed(&triangles),
        triangles,
        normals: Some(normals),
        texcoords: (all_tc && tcs.len() == pos.len()).then_some(tcs),
    })
}

fn area_weighted_normals(p: &[[i16; 3]], tris: &[[u16; 3]]) -> Vec<[f32; 3]> {
    let mut n = vec![[0f32; 3]; p.len()];
    for t in tris {
        let v = t.map(|k| p[k as usize].map(f32::from));
        let e1 = [v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]];
        let e2 = [v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]];
        let c = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        for &k in t {
            for i in 0..3 {
                n[k as usize][i] += c[i];
            }
        }
    }
    n
}
