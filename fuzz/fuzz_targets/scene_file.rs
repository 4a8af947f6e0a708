//! `scene_file`: the host simulator's RON scene-file parser
//! (`sightline_sim::scene_file::parse`) on arbitrary text and on mutated
//! valid scene files (the seed corpus holds the checked-in scenes).
//!
//! Oracle: it never panics; an error names the file and a position inside
//! the text (line 1..=lines + 1, column 1..=longest line + 1, or 0:0 when
//! unknown) and says what was expected; a successful parse has a finite
//! camera (checked by the loader) and hands the same name to `with_scene`.
//! Referenced files resolve against a directory that does not exist, so
//! only built-in meshes can load.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let path = Path::new("/nonexistent-sightline-fuzz/scene.ron");
    match sightline_sim::scene_file::parse(&text, path) {
        Ok(scene) => {
            let name = scene.name().to_string();
            scene.with_scene(|s| assert_eq!(s.name, name));
        }
        Err(e) => {
            assert_eq!(e.file, path);
            assert!(!e.message.is_empty());
            let lines = text.split('\n').count();
            let longest = text
                .split('\n')
                .map(|l| l.chars().count())
                .max()
                .unwrap_or(0);
            if e.line == 0 {
                assert_eq!(e.col, 0, "{e}");
            } else {
                assert!(
                    e.line <= lines + 1 && e.col >= 1 && e.col <= longest + 1,
                    "{e}: {lines} lines, longest {longest}"
                );
            }
        }
    }
});
