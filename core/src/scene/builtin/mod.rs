//! Built-in demo scenes as `static` data, shared by MCU firmware and the
//! host simulator.
//!
//! | scene | shows | paths |
//! |---|---|---|
//! | [`CUBE`] | a flat-shaded cube on a floor (camera: `look_at`) | both |
//! | [`BUNNY`] | the Stanford bunny, Gouraud-lit from vertex normals (camera: angles) | both |
//! | [`CORRIDOR`] | a checker-textured floor and walls, perspective-correct (camera: general vectors) | both |
//! | [`CORRIDOR_AFFINE`] | the same with affine mapping: the checks bend at the triangles' diagonals | both |
//! | [`SPHERES`] | three spheres on a flat floor polygon (camera: orthonormal) | ray (the raster path draws the floor only) |
//!
//! [`COLUMN_MAP`] is a grid map for the column caster
//! ([`crate::ray::column`]); the simulator renders it as the scene `maze`.

mod bunny_data;

pub use bunny_data::{BUNNY_NORMALS, BUNNY_POSITIONS, BUNNY_SCALE, BUNNY_TRIANGLES};

use super::{
    CameraSpec, Color, Light, Material, MeshData, ProjectionSpec, Scene, SceneObject, SceneSphere,
    TextureMode,
};
use crate::math::Vec3;
use crate::texture::Texture;
use crate::transform::{Euler, Pose};

/// Every built-in scene, in listing order.
pub static ALL: [&Scene<'static>; 5] = [&CUBE, &BUNNY, &CORRIDOR, &CORRIDOR_AFFINE, &SPHERES];

/// The scene a bare `sightline-sim` run renders.
pub static DEFAULT: &Scene<'static> = &BUNNY;

/// The built-in scene called `name`.
#[must_use]
pub fn by_name(name: &str) -> Option<&'static Scene<'static>> {
    ALL.iter().copied().find(|s| s.name == name)
}

const LIGHT: Light = Light {
    direction: [0.4, 1.0, 0.6],
    ambient: 0.2,
    diffuse: 0.8,
};

const BACKGROUND: Color = Color::new(4, 8, 10);

const fn pose(origin: [f32; 3], yaw: f32) -> Pose<f32> {
    Pose::new(
        Vec3::new(origin[0], origin[1], origin[2]),
        Euler::new(0.0, 0.0, yaw),
    )
}

// ---------------------------------------------------------------- cube

/// Cube corners: index bit 0 → x, bit 1 → y, bit 2 → z (clear = −1).
static CUBE_POSITIONS: [[i16; 3]; 8] = [
    [-1024, -1024, -1024],
    [1024, -1024, -1024],
    [-1024, 1024, -1024],
    [1024, 1024, -1024],
    [-1024, -1024, 1024],
    [1024, -1024, 1024],
    [-1024, 1024, 1024],
    [1024, 1024, 1024],
];

/// Two counter-clockwise (outward) triangles per face: +X, −X, +Y, −Y,
/// +Z, −Z.
static CUBE_TRIANGLES: [[u16; 3]; 12] = [
    [1, 3, 7],
    [1, 7, 5],
    [0, 4, 6],
    [0, 6, 2],
    [2, 6, 7],
    [2, 7, 3],
    [0, 1, 5],
    [0, 5, 4],
    [4, 5, 7],
    [4, 7, 6],
    [0, 2, 3],
    [0, 3, 1],
];

/// The unit cube (side 2 around the origin).
pub static CUBE_MESH: MeshData<'static> = MeshData {
    closed: true,
    positions: &CUBE_POSITIONS,
    scale: 1.0 / 1024.0,
    triangles: &CUBE_TRIANGLES,
    normals: None,
    uvs: None,
};

static QUAD_POSITIONS: [[i16; 3]; 4] = [
    [-1024, 0, -1024],
    [1024, 0, -1024],
    [1024, 0, 1024],
    [-1024, 0, 1024],
];
static QUAD_TRIANGLES: [[u16; 3]; 2] = [[0, 3, 2], [0, 2, 1]];

/// A horizontal square floor, 8 units wide, facing +Y.
pub static FLOOR_MESH: MeshData<'static> = MeshData {
    closed: false,
    positions: &QUAD_POSITIONS,
    scale: 4.0 / 1024.0,
    triangles: &QUAD_TRIANGLES,
    normals: None,
    uvs: None,
};

static CUBE_OBJECTS: [SceneObject<'static>; 2] = [
    SceneObject {
        mesh: &FLOOR_MESH,
        pose: pose([0.0, -1.0, 0.0], 0.3),
        material: Material::Flat(Color::new(20, 40, 20)),
    },
    SceneObject {
        mesh: &CUBE_MESH,
        pose: Pose::new(Vec3::new(0.0, 0.0, 0.0), Euler::new(0.0, 0.0, 0.6)),
        material: Material::Flat(Color::new(31, 40, 6)),
    },
];

/// A flat-shaded cube on a floor.
pub static CUBE: Scene<'static> = Scene {
    name: "cube",
    description: "flat-shaded cube on a floor (look_at camera)",
    camera: CameraSpec::LookAt {
        eye: [3.0, 2.5, 5.0],
        target: [0.0, 0.0, 0.0],
        up: [0.0, 1.0, 0.0],
    },
    projection: ProjectionSpec::Perspective { fov_x: 0.9 },
    near: 0.1,
    far: 100.0,
    light: LIGHT,
    background: BACKGROUND,
    objects: &CUBE_OBJECTS,
    spheres: &[],
};

// ---------------------------------------------------------------- bunny

/// The Stanford bunny (about 10 units tall, feet at y = 0) with vertex
/// normals.
pub static BUNNY_MESH: MeshData<'static> = MeshData {
    closed: true,
    positions: &BUNNY_POSITIONS,
    scale: BUNNY_SCALE,
    triangles: &BUNNY_TRIANGLES,
    normals: Some(&BUNNY_NORMALS),
    uvs: None,
};

/// A floor 32 units wide.
pub static BIG_FLOOR_MESH: MeshData<'static> = MeshData {
    closed: false,
    positions: &QUAD_POSITIONS,
    scale: 16.0 / 1024.0,
    triangles: &QUAD_TRIANGLES,
    normals: None,
    uvs: None,
};

static BUNNY_OBJECTS: [SceneObject<'static>; 2] = [
    SceneObject {
        mesh: &BIG_FLOOR_MESH,
        pose: pose([0.0, 0.0, 0.0], 0.0),
        material: Material::Flat(Color::new(12, 24, 16)),
    },
    SceneObject {
        mesh: &BUNNY_MESH,
        pose: pose([0.0, 0.0, 0.0], 0.5),
        material: Material::Gouraud(Color::new(31, 58, 26)),
    },
];

/// The Gouraud-lit bunny (the default scene).
pub static BUNNY: Scene<'static> = Scene {
    name: "bunny",
    description: "Gouraud-lit Stanford bunny, 3674 triangles (angles camera)",
    camera: CameraSpec::Angles {
        position: [0.0, 9.0, 20.0],
        angles: [0.0, -0.3, 0.0],
    },
    projection: ProjectionSpec::Perspective { fov_x: 0.8 },
    near: 0.5,
    far: 200.0,
    light: LIGHT,
    background: BACKGROUND,
    objects: &BUNNY_OBJECTS,
    spheres: &[],
};

// ---------------------------------------------------------------- corridor

/// Side of the checker texture in texels.
pub const CHECKER_SIDE: u16 = 64;

const fn checker() -> [Color; 64 * 64] {
    let mut t = [Color::new(0, 0, 0); 64 * 64];
    let mut y = 0;
    while y < 64 {
        let mut x = 0;
        while x < 64 {
            let dark = ((x / 8) + (y / 8)) % 2 == 1;
            // A thin line every 32 texels makes bending easy to see.
            let line = x % 32 == 0 || y % 32 == 0;
            t[y * 64 + x] = if line {
                Color::new(31, 10, 4)
            } else if dark {
                Color::new(4, 12, 12)
            } else {
                Color::new(28, 56, 26)
            };
            x += 1;
        }
        y += 1;
    }
    t
}

/// A 64×64 checker of 8-texel squares with a red line every 32 texels.
pub static CHECKER_TEXELS: [Color; 64 * 64] = checker();

/// [`CHECKER_TEXELS`] as a texture.
pub static CHECKER: Texture<'static, Color> = match Texture::new(
    &CHECKER_TEXELS,
    CHECKER_SIDE,
    CHECKER_SIDE,
    CHECKER_SIDE as usize,
) {
    Ok(t) => t,
    Err(_) => panic!("the checker is 64x64"),
};

/// Floor (x ∈ [−2, 2], y = 0), left wall (x = −2) and right wall (x = 2),
/// from z = 0 to z = −24, 3 units high; 1/256 unit per step.
static CORRIDOR_POSITIONS: [[i16; 3]; 12] = [
    [-512, 0, 0],
    [512, 0, 0],
    [512, 0, -6144],
    [-512, 0, -6144],
    [-512, 0, 0],
    [-512, 0, -6144],
    [-512, 768, -6144],
    [-512, 768, 0],
    [512, 0, 0],
    [512, 0, -6144],
    [512, 768, -6144],
    [512, 768, 0],
];

/// 32 texels per unit.
static CORRIDOR_UVS: [[i16; 2]; 12] = [
    [0, 0],
    [128, 0],
    [128, 768],
    [0, 768],
    [0, 0],
    [768, 0],
    [768, 96],
    [0, 96],
    [0, 0],
    [768, 0],
    [768, 96],
    [0, 96],
];

static CORRIDOR_TRIANGLES: [[u16; 3]; 6] = [
    [0, 1, 2],
    [0, 2, 3],
    [4, 5, 6],
    [4, 6, 7],
    [8, 10, 9],
    [8, 11, 10],
];

/// The corridor's floor and walls.
pub static CORRIDOR_MESH: MeshData<'static> = MeshData {
    closed: false,
    positions: &CORRIDOR_POSITIONS,
    scale: 1.0 / 256.0,
    triangles: &CORRIDOR_TRIANGLES,
    normals: None,
    uvs: Some(&CORRIDOR_UVS),
};

static CORRIDOR_OBJECTS: [SceneObject<'static>; 1] = [SceneObject {
    mesh: &CORRIDOR_MESH,
    pose: pose([0.0, 0.0, 0.0], 0.0),
    material: Material::Texture {
        texture: CHECKER,
        mode: TextureMode::Perspective,
    },
}];

static CORRIDOR_AFFINE_OBJECTS: [SceneObject<'static>; 1] = [SceneObject {
    mesh: &CORRIDOR_MESH,
    pose: pose([0.0, 0.0, 0.0], 0.0),
    material: Material::Texture {
        texture: CHECKER,
        mode: TextureMode::Affine,
    },
}];

/// A camera from general (non-orthonormal) vectors: u and v are the
/// screen axes, w is skewed slightly, which the solver inverts.
const CORRIDOR_CAMERA: CameraSpec = CameraSpec::Vectors {
    position: [0.3, 1.4, 1.0],
    u: [0.98, 0.0, -0.2],
    v: [0.0, -1.0, 0.0],
    w: [-0.2, -0.15, -0.98],
};

/// A perspective-textured corridor.
pub static CORRIDOR: Scene<'static> = Scene {
    name: "corridor",
    description: "checker-textured floor and walls, perspective-correct (general-vector camera)",
    camera: CORRIDOR_CAMERA,
    projection: ProjectionSpec::Perspective { fov_x: 1.4 },
    near: 0.1,
    far: 100.0,
    light: LIGHT,
    background: BACKGROUND,
    objects: &CORRIDOR_OBJECTS,
    spheres: &[],
};

/// The corridor with affine texture mapping, to show where affine fails.
pub static CORRIDOR_AFFINE: Scene<'static> = Scene {
    name: "corridor-affine",
    description: "the corridor mapped affinely: checks bend at the triangle diagonals",
    camera: CORRIDOR_CAMERA,
    projection: ProjectionSpec::Perspective { fov_x: 1.4 },
    near: 0.1,
    far: 100.0,
    light: LIGHT,
    background: BACKGROUND,
    objects: &CORRIDOR_AFFINE_OBJECTS,
    spheres: &[],
};

// ---------------------------------------------------------------- spheres

static SPHERES_OBJECTS: [SceneObject<'static>; 1] = [SceneObject {
    mesh: &FLOOR_MESH,
    pose: pose([0.0, 0.0, 0.0], 0.0),
    material: Material::Flat(Color::new(16, 32, 16)),
}];

static SPHERE_LIST: [SceneSphere; 3] = [
    SceneSphere {
        centre: [-1.6, 0.8, 0.0],
        radius: 0.8,
        color: Color::new(31, 16, 8),
    },
    SceneSphere {
        centre: [0.4, 1.0, -1.0],
        radius: 1.0,
        color: Color::new(8, 40, 31),
    },
    SceneSphere {
        centre: [1.6, 0.5, 1.0],
        radius: 0.5,
        color: Color::new(31, 60, 8),
    },
];

/// Spheres on a floor polygon, for the ray path.
pub static SPHERES: Scene<'static> = Scene {
    name: "spheres",
    description: "three spheres on a floor polygon (orthonormal camera; spheres are ray-only)",
    camera: CameraSpec::Orthonormal {
        position: [0.0, 2.4, 6.0],
        right: [1.0, 0.0, 0.0],
        down: [0.0, -0.928_476_7, 0.371_390_7],
        forward: [0.0, -0.371_390_7, -0.928_476_7],
    },
    projection: ProjectionSpec::Perspective { fov_x: 1.0 },
    near: 0.1,
    far: 100.0,
    light: LIGHT,
    background: BACKGROUND,
    objects: &SPHERES_OBJECTS,
    spheres: &SPHERE_LIST,
};

// ---------------------------------------------------------------- column map

#[cfg(feature = "column")]
pub use crate::ray::column::GridMap;

/// A 16×12 maze for the column caster ([`crate::ray::column`]), enclosed
/// by walls; the viewer starts in the top-left room.
#[cfg(feature = "column")]
pub static COLUMN_MAP: GridMap<'static> = GridMap {
    width: 16,
    height: 12,
    cells: b"################\
              #......#.......#\
              #.##...#..###..#\
              #.#....#....#..#\
              #.#..###....#..#\
              #..............#\
              #####..####..###\
              #...#.....#....#\
              #...#..#..#.#..#\
              #......#....#..#\
              #..#...#.......#\
              ################",
    start: [1.5, 1.5],
    heading: 0.3,
};
