//! The crate docs' layer table is the truth: each module's code names
//! exactly the modules its *uses* column lists, and each of those sits
//! below it in the table. Read from the source text, so that an upward
//! `use crate::…` (or a path such as `crate::raster::X` in an
//! expression) fails here, not in review.
//!
//! What is scanned: every `.rs` file of a module's tree except test code
//! (`tests.rs`, `*_tests.rs`, a `tests/` directory, and the rest of a file
//! from an inline `#[cfg(test)]` module on); comments are dropped. Test
//! code may use any layer (`test_util` draws with the raster).

use std::fs;
use std::path::{Path, PathBuf};
use std::string::{String, ToString};
use std::vec::Vec;
use std::{format, vec};

/// The layer table of `lib.rs`: (module, uses), bottom to top.
fn layer_table(lib_rs: &str) -> Vec<(String, Vec<String>)> {
    let ticked = |cell: &str| -> Vec<String> {
        cell.split('`')
            .skip(1)
            .step_by(2)
            .map(ToString::to_string)
            .collect()
    };
    let mut rows = Vec::new();
    let mut inside = false;
    for line in lib_rs.lines() {
        let Some(doc) = line.strip_prefix("//!") else {
            continue;
        };
        let doc = doc.trim();
        if doc.starts_with("## ") {
            inside = doc.starts_with("## Layers");
            continue;
        }
        if !inside || !doc.starts_with("| [`") {
            continue;
        }
        let cells: Vec<&str> = doc.trim_matches('|').split(" | ").collect();
        let name = ticked(cells[0]).remove(0);
        let uses = ticked(cells[cells.len() - 1]);
        rows.push((name, uses));
    }
    rows
}

/// Code (comments dropped) of a file, up to its first inline test module.
fn code_of(text: &str) -> String {
    let mut out = String::new();
    let mut lines = text.lines().peekable();
    while let Some(line) = lines.next() {
        let t = line.trim_start();
        if t.starts_with("#[cfg(test)]")
            && lines
                .peek()
                .is_some_and(|n| n.trim_start().contains("mod ") && n.trim_end().ends_with('{'))
        {
            break;
        }
        let code = match t.find("//") {
            Some(i) => &t[..i],
            None => t,
        };
        out.push_str(code);
        out.push('\n');
    }
    out
}

/// The top-level modules a piece of code names as `crate::<module>`,
/// including each item of a grouped `crate::{a, b::c}`.
fn named_modules(code: &str) -> Vec<String> {
    let ident = |s: &str| -> String {
        s.trim()
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    let mut found = Vec::new();
    for (i, _) in code.match_indices("crate::") {
        let rest = &code[i + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let mut depth = 0;
            let mut item = String::new();
            for c in group.chars() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        found.push(ident(&item));
                        item.clear();
                        continue;
                    }
                    _ => {}
                }
                item.push(c);
            }
            found.push(ident(&item));
        } else {
            found.push(ident(rest));
        }
    }
    found.retain(|m| !m.is_empty());
    found
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if p.is_dir() {
            if name != "tests" {
                rust_files(&p, out);
            }
        } else if name.ends_with(".rs") && name != "tests.rs" && !name.ends_with("_tests.rs") {
            out.push(p);
        }
    }
}

/// Every violation of the table by the sources under `src`: a module that
/// names one outside its *uses*, lists one it does not name, or lists one
/// that is not below it.
fn violations(src: &Path, table: &[(String, Vec<String>)]) -> Vec<String> {
    let mut bad = Vec::new();
    for (pos, (module, uses)) in table.iter().enumerate() {
        let below: Vec<&String> = table[..pos].iter().map(|(m, _)| m).collect();
        for u in uses {
            if !below.contains(&u) {
                bad.push(format!("{module}: lists `{u}`, which is not below it"));
            }
        }
        let mut files = Vec::new();
        let single = src.join(format!("{module}.rs"));
        if single.is_file() {
            files.push(single);
        }
        rust_files(&src.join(module), &mut files);
        assert!(!files.is_empty(), "no source for module `{module}`");
        let mut named: Vec<String> = Vec::new();
        for f in &files {
            let text = fs::read_to_string(f).unwrap();
            for m in named_modules(&code_of(&text)) {
                if m == *module || m == "test_util" {
                    continue;
                }
                if !uses.contains(&m) {
                    bad.push(format!(
                        "{}: names `crate::{m}`, not in {module}'s uses",
                        f.display()
                    ));
                }
                if !named.contains(&m) {
                    named.push(m);
                }
            }
        }
        for u in uses {
            if !named.contains(u) {
                bad.push(format!("{module}: lists `{u}` but never names it"));
            }
        }
    }
    bad
}

#[test]
fn layers_only_point_down() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let lib = fs::read_to_string(root.join("lib.rs")).unwrap();
    let table = layer_table(&lib);
    let names: Vec<&str> = table.iter().map(|(m, _)| m.as_str()).collect();
    assert_eq!(
        names,
        [
            "scalar",
            "math",
            "solve",
            "texture",
            "transform",
            "camera",
            "target",
            "raster",
            "pipeline",
            "ray",
            "scene"
        ],
        "the layer table lists every public module once"
    );
    let bad = violations(&root, &table);
    assert!(bad.is_empty(), "layer table violated:\n{}", bad.join("\n"));
}

/// The checker is not hollow: an upward import in math, a grouped one in
/// scalar, a listed layer above the module and a stale listing are each
/// reported.
#[test]
fn the_layer_check_catches_upward_imports() {
    let dir = std::env::temp_dir().join(format!("sightline-layers-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(dir.join("math")).unwrap();
    fs::write(dir.join("scalar.rs"), "use crate::{math::Vec3, scalar};\n").unwrap();
    fs::write(
        dir.join("math").join("mod.rs"),
        "use crate::scalar::Scalar;\n// use crate::raster::Fine; (a comment)\nfn f() { crate::solve::solve(); }\n#[cfg(test)]\nmod tests {\n    use crate::scene::X;\n}\n",
    )
    .unwrap();
    fs::write(dir.join("solve.rs"), "use crate::scalar::Scalar;\n").unwrap();
    let table = vec![
        ("scalar".to_string(), vec![]),
        ("math".to_string(), vec!["scalar".to_string()]),
        (
            "solve".to_string(),
            vec!["scalar".to_string(), "math".to_string()],
        ),
    ];
    let bad = violations(&dir, &table);
    let up = vec![("math".to_string(), vec!["solve".to_string()])];
    let up_bad = violations(&dir, &up);
    let _ = fs::remove_dir_all(&dir);
    let has = |s: &str| bad.iter().any(|b| b.contains(s));
    assert!(has("names `crate::math`, not in scalar's uses"), "{bad:?}");
    assert!(has("names `crate::solve`, not in math's uses"), "{bad:?}");
    assert!(has("solve: lists `math` but never names it"), "{bad:?}");
    assert_eq!(
        bad.len(),
        3,
        "comments and test modules are not code: {bad:?}"
    );
    assert!(
        up_bad[0].contains("math: lists `solve`, which is not below it"),
        "{up_bad:?}"
    );
}
