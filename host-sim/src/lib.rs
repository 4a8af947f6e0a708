//! `sightline-sim`: the host simulator. Renders built-in scenes (from
//! core) and scene files with the raster and the ray path to PNG, and
//! compares the two paths.
//!
//! The command line is `run` (feature `cli`, on by default); `main` only
//! forwards the process arguments, so tests call `run` directly.
//!
//! Without the `cli` feature the library is the scene-file parser
//! ([`scene_file`]) and PNG input and output ([`image`]): what the
//! `scene_file` fuzz target links, without the command line's parser,
//! thread pool, progress bars and plotting.

pub mod image;
pub mod scene_file;

#[cfg(feature = "cli")]
mod cli;
#[cfg(feature = "cli")]
pub mod render;
#[cfg(feature = "cli")]
pub mod report;
#[cfg(feature = "cli")]
pub mod turntable;

#[cfg(feature = "cli")]
pub use cli::*;
