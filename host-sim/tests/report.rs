//! The report command at its smoke-test size: files exist, the tables
//! parse back with finite numbers, and the figures say what they must.

use sightline_sim::report::parse_tables;
use std::path::PathBuf;

fn temp_dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("sightline-sim-report-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// Runs `sightline-sim report --tiny --out DIR` and returns its
/// `accuracy.md`.
fn tiny_report(dir: &std::path::Path) -> String {
    let mut out = Vec::new();
    sightline_sim::run(
        [
            "sightline-sim",
            "report",
            "--tiny",
            "--out",
            dir.to_str().unwrap(),
        ],
        &mut out,
    )
    .unwrap();
    std::fs::read_to_string(dir.join("accuracy.md")).unwrap()
}

#[test]
fn tiny_report_writes_parseable_tables_and_plots() {
    let dir = temp_dir();
    let md = tiny_report(&dir);
    assert!(md.contains("## Method"), "method section missing");

    let rows = parse_tables(&md).unwrap();
    let ids = [
        "transform",
        "projection",
        "solver3",
        "solver4",
        "camera",
        "texture_vectors",
        "line_plane",
        "line_polygon",
        "line_sphere",
        "texture_mapping",
    ];
    for id in ids {
        let png = dir.join(format!("{id}.png"));
        let bytes = std::fs::read(&png).unwrap_or_else(|e| panic!("{}: {e}", png.display()));
        assert_eq!(&bytes[1..4], b"PNG", "{id}.png is not a PNG");
        assert!(
            rows.iter().filter(|r| r.table == id).count() >= 3,
            "table {id} has fewer than three rows"
        );
        assert!(md.contains(&format!("]({id}.png)")), "{id} plot not linked");
    }
    for r in &rows {
        assert!(
            r.time.iter().all(|t| t.is_finite() && *t >= 0.0),
            "{r:?}: bad time"
        );
        assert!(
            r.time[3] <= r.time[0] && r.time[0] <= r.time[4],
            "{r:?}: median outside min–max"
        );
        if let Some((max, mean)) = r.err {
            assert!(
                max.is_finite() && mean.is_finite(),
                "{r:?}: non-finite error"
            );
            assert!(mean <= max * (1.0 + 1e-9) + 1e-12, "{r:?}: mean above max");
        }
    }

    let get = |table: &str, repr: &str| {
        rows.iter()
            .find(|r| r.table == table && r.repr == repr)
            .unwrap_or_else(|| panic!("no row {repr} in {table}"))
            .err
            .unwrap_or_else(|| panic!("{repr} in {table} has no error figure"))
    };
    // f64 is the reference: zero error.
    assert_eq!(get("transform", "f64"), (0.0, 0.0));
    assert_eq!(get("projection", "f64"), (0.0, 0.0));
    // 24 significand bits beat 16 fraction bits for view coordinates
    // below 256; the mixed scheme sits between.
    let (f32_max, _) = get("transform", "f32");
    let (fx_max, _) = get("transform", "I16F16");
    let (mixed_max, _) = get("transform", "Q2.30×Q16.16");
    assert!(
        f32_max > 0.0 && f32_max < fx_max,
        "f32 {f32_max} vs I16F16 {fx_max}"
    );
    assert!(mixed_max < fx_max, "mixed {mixed_max} vs I16F16 {fx_max}");
    // I16F16 keeps vertices within a grid step or so (2^-16 ≈ 1.5e-5 per
    // rounding, a few roundings per coordinate, view coordinates ≤ ~150).
    assert!(fx_max < 1e-3, "I16F16 transform error {fx_max}");
    // Affine texture mapping is worse than exact on the steep floor.
    let (_, exact_mean) = get("texture_mapping", "f32, exact");
    let (_, affine_mean) = get("texture_mapping", "f32, affine");
    assert!(
        exact_mean < affine_mean,
        "exact {exact_mean} vs affine {affine_mean}"
    );

    let _ = std::fs::remove_dir_all(&dir);
}

/// The committed report's Cortex-M columns are what the current generated
/// tables (`docs/mcu/kernels.md`, `docs/mcu/tables.md`, compiled into the
/// simulator) give: the report is generated too, and `tests/mcu/run`
/// changing those tables must be followed by rerunning it. (Host times
/// and errors depend on the machine and the sample size, so only these
/// columns are compared, and the one recommendation sentence built from
/// Cortex-M figures alone.)
#[test]
fn committed_report_has_the_current_cortex_m_figures() {
    let committed = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../docs/report/accuracy.md"
    ))
    .unwrap();
    // Its own directory: `temp_dir()` clears the other test's.
    let dir = std::env::temp_dir().join(format!("sightline-sim-report-mcu-{}", std::process::id()));
    let fresh = tiny_report(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    let mcu = |md: &str| -> Vec<(String, String, [String; 2])> {
        parse_tables(md)
            .unwrap()
            .into_iter()
            .map(|r| (r.table, r.repr, r.mcu))
            .collect()
    };
    let (old, new) = (mcu(&committed), mcu(&fresh));
    assert_eq!(old.len(), new.len(), "the report's rows changed");
    let stale = "docs/report/accuracy.md is stale; rerun \
                 `cargo run --release -p sightline-sim -- report --out docs/report`";
    for (o, n) in old.iter().zip(&new) {
        assert_eq!(o, n, "{stale}");
    }
    // The texture recommendation's Cortex-M0 sentence (span-loop figures
    // from `docs/mcu/tables.md`), up to where its host ratio begins.
    let m0 = |md: &str| -> Option<String> {
        let rest = md.get(md.find("On a Cortex-M0-class core")?..)?;
        Some(rest.get(..rest.find("the exact cost.")?)?.to_string())
    };
    let want = m0(&fresh);
    assert!(
        want.is_some(),
        "the texture recommendation lost its Cortex-M0 sentence"
    );
    assert_eq!(m0(&committed), want, "{stale}");
}
