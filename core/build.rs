//! Generates the built-in bunny's const data from `data/bunny.obj` when the
//! `demo` feature is on (and does nothing else, so a build without `demo`
//! pays only for compiling this file).
//!
//! Positions are quantized to i16 at 2048 steps per OBJ unit (the bunny
//! spans about 10 units, so at most ~20 000 steps: inside i16 and exact in
//! I16F16); the mesh's `scale` turns steps back into OBJ units. Vertex
//! normals are the area-weighted sums of the face normals (integer cross
//! products of the quantized positions, summed in f64), normalized in f64
//! and stored in units of 1/32767. Rounding is half-to-even throughout.
//!
//! The only way this script fails is a `panic!` whose message names the
//! file (and, for a malformed OBJ, the line) and what was expected.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Position steps per OBJ unit.
const STEPS: f64 = 2048.0;
/// The OBJ file, relative to the package root.
const OBJ: &str = "data/bunny.obj";

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    if std::env::var_os("CARGO_FEATURE_DEMO").is_none() {
        return;
    }
    println!("cargo:rerun-if-changed={OBJ}");
    let root = PathBuf::from(env_or_panic("CARGO_MANIFEST_DIR"));
    let obj = root.join(OBJ);
    let text = match std::fs::read(&obj) {
        Ok(bytes) => match String::from_utf8(bytes) {
            Ok(text) => text,
            Err(e) => panic!("{}: not UTF-8 text: {e}", obj.display()),
        },
        Err(e) => panic!("{}: cannot read: {e}", obj.display()),
    };
    let mesh = match parse_obj(&text) {
        Ok(mesh) => mesh,
        Err((line, message)) => panic!("{}:{line}: {message}", obj.display()),
    };
    let out = PathBuf::from(env_or_panic("OUT_DIR")).join("bunny_data.rs");
    write_or_panic(&out, &render(&mesh));
}

fn env_or_panic(name: &str) -> String {
    match std::env::var(name) {
        Ok(v) => v,
        Err(e) => panic!("build script: environment variable {name}: {e}"),
    }
}

fn write_or_panic(path: &Path, text: &str) {
    if let Err(e) = std::fs::write(path, text) {
        panic!("{}: cannot write: {e}", path.display());
    }
}

/// Quantized positions and triangles of an OBJ file.
struct Mesh {
    positions: Vec<[i64; 3]>,
    triangles: Vec<[usize; 3]>,
}

/// Reads `v` and `f` lines (other lines are ignored); faces are fanned
/// from their first vertex. An error is a 1-based line and a message.
fn parse_obj(text: &str) -> Result<Mesh, (usize, String)> {
    let mut positions: Vec<[i64; 3]> = Vec::new();
    let mut triangles = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line_no = n + 1;
        let fail = |m: String| Err((line_no, m));
        let mut parts = line.split_whitespace();
        match parts.next() {
            Some("v") => {
                let mut p = [0i64; 3];
                for (k, c) in p.iter_mut().enumerate() {
                    let Some(word) = parts.next() else {
                        return fail(format!("`v` with {k} numbers: expected x y z"));
                    };
                    let x = match word.parse::<f64>() {
                        Ok(x) if x.is_finite() => x,
                        _ => return fail(format!("`{word}`: expected a finite number")),
                    };
                    let q = (x * STEPS).round_ties_even();
                    if q.abs() >= 32768.0 {
                        return fail(format!(
                            "`{word}` is {q} steps of 1/2048: expected |x| < 16 (inside i16)"
                        ));
                    }
                    *c = q as i64;
                }
                if positions.len() == 65535 {
                    return fail("more than 65535 vertices: expected u16 indices".to_string());
                }
                positions.push(p);
            }
            Some("f") => {
                let mut idx = Vec::new();
                for word in parts {
                    let first = word.split('/').next().unwrap_or("");
                    let i = match first.parse::<i64>() {
                        Ok(i) => i,
                        Err(_) => return fail(format!("`{word}`: expected a vertex index")),
                    };
                    // OBJ indices are 1-based; negative ones count back
                    // from the last vertex read so far.
                    let len = positions.len() as i64;
                    let k = if i > 0 { i - 1 } else { len + i };
                    if i == 0 || !(0..len).contains(&k) {
                        return fail(format!(
                            "vertex index {i}: expected 1..={len} or -{len}..=-1"
                        ));
                    }
                    idx.push(k as usize);
                }
                if idx.len() < 3 {
                    return fail(format!(
                        "a face with {} vertices: expected at least 3",
                        idx.len()
                    ));
                }
                for pair in idx[1..].windows(2) {
                    triangles.push([idx[0], pair[0], pair[1]]);
                }
            }
            _ => {}
        }
    }
    Ok(Mesh {
        positions,
        triangles,
    })
}

/// Unit vertex normals in units of 1/32767: the sums of the (integer,
/// area-weighted) face normals, in f64 in triangle order.
fn normals(mesh: &Mesh) -> Vec<[i64; 3]> {
    let mut sums = vec![[0.0f64; 3]; mesh.positions.len()];
    for &[a, b, c] in &mesh.triangles {
        let (pa, pb, pc) = (mesh.positions[a], mesh.positions[b], mesh.positions[c]);
        let e1 = [pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]];
        let e2 = [pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]];
        let n = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        for k in [a, b, c] {
            for (sum, x) in sums[k].iter_mut().zip(n) {
                *sum += x as f64;
            }
        }
    }
    sums.iter()
        .map(|n| {
            let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            let length = if length == 0.0 { 1.0 } else { length };
            n.map(|x| (x / length * 32767.0).round_ties_even() as i64)
        })
        .collect()
}

/// The Rust source of the data (three statics and the scale).
fn render(mesh: &Mesh) -> String {
    let steps = STEPS as u32;
    let (np, nt) = (mesh.positions.len(), mesh.triangles.len());
    let mut s = String::new();
    // `write!` into a String cannot fail.
    let _ = write!(
        s,
        "// The Stanford bunny (low resolution) as const data. GENERATED by\n\
         // `core/build.rs` from `core/{OBJ}`; do not edit.\n\n\
         /// OBJ units per position step.\npub const BUNNY_SCALE: f32 = 1.0 / {steps}.0;\n\n\
         /// {np} quantized positions.\n#[rustfmt::skip]\n\
         pub static BUNNY_POSITIONS: [[i16; 3]; {np}] = [\n"
    );
    for p in &mesh.positions {
        let _ = writeln!(s, "[{},{},{}],", p[0], p[1], p[2]);
    }
    let _ = write!(
        s,
        "];\n\n/// {np} unit vertex normals in units of 1/32767.\n#[rustfmt::skip]\n\
         pub static BUNNY_NORMALS: [[i16; 3]; {np}] = [\n"
    );
    for n in normals(mesh) {
        let _ = writeln!(s, "[{},{},{}],", n[0], n[1], n[2]);
    }
    let _ = write!(
        s,
        "];\n\n/// {nt} counter-clockwise triangles.\n#[rustfmt::skip]\n\
         pub static BUNNY_TRIANGLES: [[u16; 3]; {nt}] = [\n"
    );
    for t in &mesh.triangles {
        let _ = writeln!(s, "[{},{},{}],", t[0], t[1], t[2]);
    }
    s.push_str("];\n");
    s
}
