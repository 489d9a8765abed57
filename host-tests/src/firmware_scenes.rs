//! Built-in scenes for the firmware (`examples/firmware`), as Rust source.
//!
//! The firmware has no floating point, so it cannot read a scene file:
//! [`generate`] turns the built-in scenes named in [`FIRMWARE_SCENES`] into
//! the source of `examples/firmware/scenes/src/generated.rs`, where every
//! scalar is the raw Q16.16 bits of exactly the value the host renders
//! with (`Q16::from_f64` of the scene's `f64`, as
//! [`render_core`](crate::core_render::render_core) converts it for the
//! `fast` profile). Meshes are the core's built-in constants, or, where the
//! scene regenerates normals (`crease_angle_deg`), the built-in positions
//! and triangles with the regenerated normals and indices as constant
//! arrays. Each scene also records the workspace it needs (prepared
//! vertices, values and triangles: the smallest workspace
//! `prepare::<Fast>` accepts), so the firmware can size its static buffers.
//!
//! The test `tests/firmware_scenes.rs` regenerates the file and compares it
//! byte for byte with the committed one (`MAKE_FIRMWARE_SCENES=1` rewrites
//! it), and checks that the scene built from the generated values renders
//! to the CRC of `fixshade render --scene NAME --profile fast --crc`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use fixshade::geom::{Affine, Vec3};
use fixshade::illum::{Light, LightKind, Material, Specular, Viewer};
use fixshade::mesh::Mesh;
use fixshade::num::{Fast, Real, Q16};
use fixshade::render::{prepare, BandState, Part, Pool, RenderError, Tri, Workspace};
use fixshade::scene::{Camera, Object, Scene, Shading};
use fixshade::target::{BandBuf, Rgb565Be, Rgb8};

use crate::builtin::load_builtin;
use crate::core_render::{crc32, BAND_ROWS};
use crate::ideal::{LightKind as ILightKind, Shading as IShading, SpecularModel};
use crate::scene_file::{PixelFormat, SceneDesc, SceneMesh, BUILTIN_MESHES};

/// The built-in scenes the firmware renders, in order.
pub const FIRMWARE_SCENES: [&str; 6] = [
    "dodeca-flat-n100",
    "dodeca-gouraud-n100",
    "dodeca-phong-n100",
    "bunny-gouraud",
    "bunny-flat",
    "cubes-and-sphere",
];

/// Widest frame the firmware's band buffers hold.
pub const MAX_WIDTH: u32 = 240;

/// The generated file, relative to the repository root.
pub const GENERATED_PATH: &str = "examples/firmware/scenes/src/generated.rs";

/// The generated file under the repository root `root`.
pub fn generated_path(root: &Path) -> PathBuf {
    root.join(GENERATED_PATH)
}

/// Workspace a scene needs: the smallest lengths of the parts of
/// [`Workspace`] with which `prepare::<Fast>` succeeds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Needs {
    /// `xy`: prepared vertices.
    pub vertices: usize,
    /// `vals`: interpolated values.
    pub values: usize,
    /// `tris`: prepared triangles.
    pub triangles: usize,
    /// `Frame::bytes_used()` of the prepared frame.
    pub prepared_bytes: usize,
}

impl Needs {
    /// The larger of each part.
    pub fn max(self, o: Self) -> Self {
        Self {
            vertices: self.vertices.max(o.vertices),
            values: self.values.max(o.values),
            triangles: self.triangles.max(o.triangles),
            prepared_bytes: self.prepared_bytes.max(o.prepared_bytes),
        }
    }

    /// Bytes of a workspace of these lengths (fixed profiles: 4-byte
    /// values), scratch included.
    pub fn workspace_bytes(&self) -> usize {
        self.vertices * 8 + self.values * 4 + self.triangles * core::mem::size_of::<Tri>()
    }
}

/// Q16 bits of `v`, as the host converts it for the `fast` profile.
pub fn q16_bits(v: f64) -> i32 {
    Q16::from_f64(v).to_bits()
}

fn v3(v: [f64; 3]) -> Vec3<Q16> {
    Vec3::new(
        Q16::from_f64(v[0]),
        Q16::from_f64(v[1]),
        Q16::from_f64(v[2]),
    )
}

/// The scene `desc` in Q16, exactly as `render_core(desc, Fast)` builds it.
struct Q16Scene<'m> {
    camera_in: ([Vec3<Q16>; 3], Q16, Q16, Option<Q16>),
    objects: Vec<Object<'m, Q16>>,
    /// Per object: scale, rotation, translation (the `from_parts` inputs).
    parts: Vec<(Q16, Vec3<Q16>, Vec3<Q16>)>,
    lights: Vec<Light<Q16>>,
    ambient: Q16,
    specular: Specular,
    background: Rgb8,
}

fn q16_scene(desc: &SceneDesc) -> Q16Scene<'_> {
    let c = &desc.camera;
    let camera_in = (
        [v3(c.eye), v3(c.target), v3(c.up)],
        Q16::from_f64(c.fov_y_deg.to_radians()),
        Q16::from_f64(c.near),
        c.far.map(Q16::from_f64),
    );
    let parts: Vec<_> = desc
        .objects
        .iter()
        .map(|o| {
            // The firmware's ObjectSpec holds one scale: the scenes in
            // FIRMWARE_SCENES are scaled uniformly.
            assert!(o.transform.is_uniform(), "firmware scenes scale uniformly");
            (
                Q16::from_f64(o.transform.scale[0]),
                v3(o.transform.rotation_rad),
                v3(o.transform.translation),
            )
        })
        .collect();
    let objects = desc
        .objects
        .iter()
        .zip(&parts)
        .map(|(o, &(s, r, t))| Object {
            mesh: o.mesh.mesh(),
            transform: Affine::from_parts(s, r, t),
            material: Material {
                color: v3(o.material.color),
                ka: Q16::from_f64(o.material.ka),
                kd: Q16::from_f64(o.material.kd),
                ks: Q16::from_f64(o.material.ks),
                shininess: Q16::from_f64(o.material.shininess),
            },
            shading: match o.shading {
                IShading::Flat => Shading::Flat,
                IShading::Gouraud => Shading::Gouraud,
                IShading::Phong => Shading::Phong,
            },
            cull_backfaces: o.cull_backfaces,
        })
        .collect();
    let lights = desc
        .lights
        .iter()
        .map(|l| Light {
            kind: match l.kind {
                ILightKind::Point { position } => LightKind::Point(v3(position)),
                ILightKind::Directional { direction } => LightKind::Directional(v3(direction)),
            },
            intensity: Q16::from_f64(l.intensity),
            color: v3(l.color),
        })
        .collect();
    let [r, g, b] = desc.background;
    Q16Scene {
        camera_in,
        objects,
        parts,
        lights,
        ambient: Q16::from_f64(desc.ambient),
        specular: match desc.specular {
            SpecularModel::Phong => Specular::Phong,
            SpecularModel::Blinn => Specular::Blinn,
        },
        background: Rgb8::new(r, g, b),
    }
}

impl Q16Scene<'_> {
    fn scene(&self) -> Result<Scene<'_, '_, Q16>, String> {
        let ([eye, target, up], fov, near, far) = self.camera_in;
        let camera = Camera::look_at(eye, target, up, fov, near, far).map_err(|e| e.to_string())?;
        Ok(Scene {
            camera,
            objects: &self.objects,
            lights: &self.lights,
            ambient: self.ambient,
            specular: self.specular,
            viewer: Viewer::Local,
            background: self.background,
        })
    }
}

/// Prepares `scene` into a workspace of the lengths `n`: the result of
/// `prepare`, and on success the frame's bytes, vertices, values and
/// triangles in use.
fn try_prepare(scene: &Scene<'_, '_, Q16>, w: u32, h: u32, n: Needs) -> Result<Needs, RenderError> {
    let mut xy = vec![[0i32; 2]; n.vertices];
    let mut vals = vec![0i32; n.values];
    let mut tris = vec![Tri::default(); n.triangles];
    let ws = Workspace {
        xy: &mut xy,
        vals: &mut vals,
        tris: &mut tris,
    };
    let frame = prepare::<Fast>(scene, w, h, ws)?;
    let values = frame
        .objects()
        .last()
        .map_or(0, |o| o.val_base + o.verts.len() * o.stride);
    Ok(Needs {
        vertices: frame.vertex_count(),
        values,
        triangles: frame.triangle_count(),
        prepared_bytes: frame.bytes_used(),
    })
}

/// The smallest workspace `prepare::<Fast>` accepts for `scene`: starts
/// from what a generous workspace uses and grows a part while `prepare`
/// reports it too small.
fn needs(scene: &Scene<'_, '_, Q16>, w: u32, h: u32) -> Result<Needs, String> {
    let tris: usize = scene.objects.iter().map(|o| o.mesh.triangle_count()).sum();
    let big = Needs {
        vertices: (scene
            .objects
            .iter()
            .map(|o| o.mesh.vertex_count())
            .sum::<usize>()
            + tris * 14)
            .min(u16::MAX as usize - 1),
        values: (u16::MAX as usize - 1) * 8,
        triangles: tris * 8,
        prepared_bytes: 0,
    };
    let mut n = try_prepare(scene, w, h, big).map_err(|e| e.to_string())?;
    for _ in 0..100_000 {
        match try_prepare(scene, w, h, n) {
            Ok(used) => {
                return Ok(Needs {
                    prepared_bytes: used.prepared_bytes,
                    ..n
                })
            }
            Err(RenderError::Capacity { part, .. }) => match part {
                Part::Vertices => n.vertices += 1,
                Part::Values => n.values += 1,
                Part::Triangles => n.triangles += 1,
                // Not a part `prepare` fills.
                Part::Order => return Err("order scratch".into()),
            },
            Err(e) => return Err(e.to_string()),
        }
    }
    Err("no workspace found".into())
}

/// Renders the Q16 scene as the firmware does (bands of 16 rows, 16-bit
/// depth band, background cleared per band) into a workspace of exactly
/// `n`: the CRC-32 of the RGB565 big-endian frame and the covered pixels.
fn render_crc(
    scene: &Scene<'_, '_, Q16>,
    w: u32,
    h: u32,
    n: Needs,
) -> Result<(u32, u32), RenderError> {
    let mut xy = vec![[0i32; 2]; n.vertices];
    let mut vals = vec![0i32; n.values];
    let mut tris = vec![Tri::default(); n.triangles];
    let ws = Workspace {
        xy: &mut xy,
        vals: &mut vals,
        tris: &mut tris,
    };
    let frame = prepare::<Fast>(scene, w, h, ws)?;
    let mut band = vec![[0u8; 2]; (w * BAND_ROWS) as usize];
    let mut depth = vec![0u16; (w * BAND_ROWS) as usize];
    let mut buf = BandBuf::<Rgb565Be>::new(&mut band, Some(&mut depth), w, BAND_ROWS)?;
    let mut order = vec![0u16; 2 * frame.triangle_count()];
    let mut pool = Box::new(Pool::<i32, 256, 8>::new());
    let mut state = BandState::new(&mut order, &mut pool);
    let mut bytes = Vec::with_capacity((w * h * 2) as usize);
    let mut covered = 0;
    frame.render_bands(scene, &mut state, &mut buf, |b| {
        bytes.extend(b.bytes());
        covered += b
            .depth()
            .unwrap_or(&[])
            .iter()
            .filter(|&&d| d != u16::MAX)
            .count() as u32;
        Ok::<(), RenderError>(())
    })?;
    Ok((crc32(&bytes), covered))
}

/// A firmware scene: its description, Q16 values and needs.
pub struct FirmwareScene {
    /// Built-in name.
    pub name: &'static str,
    /// The scene as the host reads it.
    pub desc: SceneDesc,
    /// The workspace it needs.
    pub needs: Needs,
}

impl FirmwareScene {
    /// Loads the built-in scene `name` and measures its needs.
    ///
    /// # Errors
    /// A scene the firmware cannot take: not RGB565, wider than
    /// [`MAX_WIDTH`], a mesh other than a built-in one, or one the core
    /// refuses.
    pub fn load(name: &'static str) -> Result<Self, String> {
        let desc = load_builtin(name).map_err(|e| e.to_string())?;
        if desc.pixel_format != PixelFormat::Rgb565 {
            return Err(format!("{name}: the firmware renders RGB565 only"));
        }
        if desc.width > MAX_WIDTH || desc.height > MAX_WIDTH {
            return Err(format!("{name}: larger than {MAX_WIDTH}x{MAX_WIDTH}"));
        }
        let q = q16_scene(&desc);
        let needs = needs(&q.scene()?, desc.width, desc.height)?;
        Ok(Self { name, desc, needs })
    }

    /// Whether `prepare::<Fast>` accepts a workspace of the lengths `n`.
    ///
    /// # Errors
    /// The core's error, e.g. [`RenderError::Capacity`].
    pub fn prepare_with(&self, n: Needs) -> Result<(), RenderError> {
        let q = q16_scene(&self.desc);
        let scene = q.scene().map_err(|_| RenderError::Window)?;
        try_prepare(&scene, self.desc.width, self.desc.height, n).map(|_| ())
    }

    /// CRC-32 and covered pixels of the frame rendered from the Q16 values
    /// the generated source holds, into a workspace of exactly
    /// [`needs`](Self::needs), as the firmware renders it.
    ///
    /// # Errors
    /// The core's error.
    pub fn render_crc(&self) -> Result<(u32, u32), String> {
        let q = q16_scene(&self.desc);
        let scene = q.scene()?;
        render_crc(&scene, self.desc.width, self.desc.height, self.needs).map_err(|e| e.to_string())
    }
}

fn builtin_const(name: &str) -> String {
    name.to_ascii_uppercase()
}

/// The built-in mesh an owned mesh was made from (its origin reads
/// `NAME (crease ...)`).
fn builtin_base(origin: &str) -> Option<&'static str> {
    let name = origin.split(" (crease").next()?;
    BUILTIN_MESHES.into_iter().find(|n| *n == name)
}

/// Distinct constant tables, by content (the compiler merges identical
/// constants: the bunny's normal indices are its triangles).
#[derive(Default)]
struct Tables(Vec<Vec<u8>>);

impl Tables {
    /// Bytes `table` adds to the image: 0 when an equal table is counted.
    fn add(&mut self, bytes: Vec<u8>) -> usize {
        if self.0.contains(&bytes) {
            return 0;
        }
        let n = bytes.len();
        self.0.push(bytes);
        n
    }

    fn add_i16(&mut self, t: &[[i16; 3]]) -> usize {
        self.add(t.iter().flatten().flat_map(|v| v.to_le_bytes()).collect())
    }

    fn add_u16(&mut self, t: &[[u16; 3]]) -> usize {
        self.add(t.iter().flatten().flat_map(|v| v.to_le_bytes()).collect())
    }

    /// Bytes of the mesh's shape (positions, triangles) and of its normals
    /// (vertex and face normals) not counted yet.
    fn add_mesh(&mut self, m: &Mesh<'_>) -> (usize, usize) {
        let shape = self.add_i16(m.positions()) + self.add_u16(m.triangles());
        let normals = m.vertex_normals().map_or(0, |n| self.add_i16(n))
            + m.face_normals().map_or(0, |n| self.add_i16(n));
        (shape, normals)
    }
}

fn q(v: Q16) -> String {
    format!("q({})", v.to_bits())
}

fn vec(v: Vec3<Q16>) -> String {
    format!("v({}, {}, {})", v.x.to_bits(), v.y.to_bits(), v.z.to_bits())
}

/// Writes `items` as `[a, b, c]` triples, wrapped below 100 columns.
fn triples<T: std::fmt::Display>(out: &mut String, items: &[[T; 3]]) {
    let mut line = String::from("   ");
    for t in items {
        let item = format!(" [{}, {}, {}],", t[0], t[1], t[2]);
        if line.len() + item.len() > 99 {
            out.push_str(&line);
            out.push('\n');
            line = String::from("   ");
        }
        line.push_str(&item);
    }
    out.push_str(&line);
    out.push('\n');
}

/// Rust source of the generated file for `scenes`.
///
/// # Errors
/// A scene the generator cannot express.
pub fn generate_for(scenes: &[FirmwareScene]) -> Result<String, String> {
    let mut out = String::new();
    let mut meshes = String::new();
    // Distinct tables in flash, and the shapes they belong to.
    let mut tables = Tables::default();
    let mut shapes: Vec<&str> = vec![];
    let mut regenerated: Vec<String> = vec![];
    let (mut shape_bytes, mut normal_bytes) = (0, 0);
    let mut max = Needs::default();
    let mut max_objects = 0;
    let mut body = String::new();

    for s in scenes {
        let d = &s.desc;
        let qs = q16_scene(d);
        max = max.max(s.needs);
        max_objects = max_objects.max(d.objects.len());
        let ([eye, target, up], fov, near, far) = qs.camera_in;
        writeln!(body, "    SceneSpec {{").unwrap();
        writeln!(body, "        name: {:?},", s.name).unwrap();
        writeln!(body, "        width: {},", d.width).unwrap();
        writeln!(body, "        height: {},", d.height).unwrap();
        writeln!(body, "        eye: {},", vec(eye)).unwrap();
        writeln!(body, "        target: {},", vec(target)).unwrap();
        writeln!(body, "        up: {},", vec(up)).unwrap();
        writeln!(body, "        fov_y: {},", q(fov)).unwrap();
        writeln!(body, "        near: {},", q(near)).unwrap();
        match far {
            Some(f) => writeln!(body, "        far: Some({}),", q(f)).unwrap(),
            None => writeln!(body, "        far: None,").unwrap(),
        }
        writeln!(body, "        objects: &[").unwrap();
        for ((o, obj), &(scale, rot, tr)) in d.objects.iter().zip(&qs.objects).zip(&qs.parts) {
            let mesh = match &o.mesh {
                SceneMesh::BuiltIn { name, mesh } => {
                    let c = builtin_const(name);
                    if !shapes.contains(name) {
                        shapes.push(name);
                    }
                    let (a, b) = tables.add_mesh(mesh);
                    shape_bytes += a;
                    normal_bytes += b;
                    format!("fixshade::mesh::{c}")
                }
                SceneMesh::Owned(owned) => {
                    let m = owned.mesh();
                    let base = builtin_base(owned.origin())
                        .ok_or_else(|| format!("{}: only built-in meshes are supported", s.name))?;
                    let crease = o
                        .crease_angle_deg
                        .ok_or_else(|| format!("{}: owned mesh without a crease", s.name))?;
                    let c = format!(
                        "{}_CREASE_{}",
                        builtin_const(base),
                        format!("{crease}").replace(['.', '-'], "_")
                    );
                    if !shapes.contains(&base) {
                        shapes.push(base);
                    }
                    let (a, b) = tables.add_mesh(&m);
                    shape_bytes += a;
                    normal_bytes += b;
                    if !regenerated.contains(&c) {
                        regenerated.push(c.clone());
                        let bc = builtin_const(base);
                        writeln!(
                            meshes,
                            "\n/// `{bc}` with normals regenerated by the core's `generate_normals`\n\
                             /// with a crease angle of {crease}°, welded: {} vertices.\n\
                             const {c}: Mesh<'static> =\n    \
                             match Mesh::new({c}_POSITIONS, {c}_TRIANGLES, Some({c}_NORMALS)) {{\n        \
                             Ok(mesh) => match mesh.with_face_normals({c}_FACE_NORMALS) {{\n            \
                             Ok(mesh) => mesh,\n            \
                             Err(_) => panic!(\"invalid face normals {c}\"),\n        \
                             }},\n        \
                             Err(_) => panic!(\"invalid regenerated normals {c}\"),\n    \
                             }};",
                            owned.positions().len()
                        )
                        .unwrap();
                        for (suffix, ty, i16s, u16s) in [
                            ("POSITIONS", "i16", Some(owned.positions()), None),
                            ("TRIANGLES", "u16", None, Some(owned.triangles())),
                            ("NORMALS", "i16", Some(owned.normals()), None),
                            ("FACE_NORMALS", "i16", Some(owned.face_normals()), None),
                        ] {
                            writeln!(meshes, "\nconst {c}_{suffix}: &[[{ty}; 3]] = &[").unwrap();
                            if let Some(t) = i16s {
                                triples(&mut meshes, t);
                            }
                            if let Some(t) = u16s {
                                triples(&mut meshes, t);
                            }
                            writeln!(meshes, "];").unwrap();
                        }
                    }
                    c
                }
            };
            let m = &obj.material;
            writeln!(body, "            ObjectSpec {{").unwrap();
            writeln!(body, "                mesh: {mesh},").unwrap();
            writeln!(body, "                scale: {},", q(scale)).unwrap();
            writeln!(body, "                rotation: {},", vec(rot)).unwrap();
            writeln!(body, "                translation: {},", vec(tr)).unwrap();
            writeln!(
                body,
                "                material: Material {{ color: {}, ka: {}, kd: {}, ks: {}, shininess: {} }},",
                vec(m.color),
                q(m.ka),
                q(m.kd),
                q(m.ks),
                q(m.shininess)
            )
            .unwrap();
            writeln!(body, "                shading: Shading::{:?},", obj.shading).unwrap();
            writeln!(
                body,
                "                cull_backfaces: {},",
                obj.cull_backfaces
            )
            .unwrap();
            writeln!(body, "            }},").unwrap();
        }
        writeln!(body, "        ],").unwrap();
        writeln!(body, "        lights: &[").unwrap();
        for l in &qs.lights {
            let kind = match l.kind {
                LightKind::Point(p) => format!("LightKind::Point({})", vec(p)),
                LightKind::Directional(p) => format!("LightKind::Directional({})", vec(p)),
            };
            writeln!(
                body,
                "            Light {{ kind: {kind}, intensity: {}, color: {} }},",
                q(l.intensity),
                vec(l.color)
            )
            .unwrap();
        }
        writeln!(body, "        ],").unwrap();
        writeln!(body, "        ambient: {},", q(qs.ambient)).unwrap();
        writeln!(body, "        specular: Specular::{:?},", qs.specular).unwrap();
        let bg = qs.background;
        writeln!(
            body,
            "        background: Rgb8::new({}, {}, {}),",
            bg.r, bg.g, bg.b
        )
        .unwrap();
        let n = s.needs;
        writeln!(
            body,
            "        needs: Needs {{ vertices: {}, values: {}, triangles: {}, prepared_bytes: {} }},",
            n.vertices, n.values, n.triangles, n.prepared_bytes
        )
        .unwrap();
        writeln!(body, "    }},").unwrap();
    }

    write!(
        out,
        "//! The firmware's scenes, generated by `fixshade_host::firmware_scenes`\n\
         //! from the built-in scenes of `host-tests/scenes/`: do not edit.\n\
         //!\n\
         //! Regenerate with\n\
         //! `MAKE_FIRMWARE_SCENES=1 cargo test -p fixshade-host --test firmware_scenes`\n\
         //! (from the repository root). Every scalar is the Q16.16 bits of\n\
         //! `Q16::from_f64` of the scene file's value, as the host renders the\n\
         //! scene with `--profile fast`.\n\
         \n\
         use crate::spec::{{q, v, Needs, ObjectSpec, SceneSpec}};\n\
         use fixshade::illum::{{Light, LightKind, Material, Specular}};\n"
    )
    .unwrap();
    if !regenerated.is_empty() {
        writeln!(out, "use fixshade::mesh::Mesh;").unwrap();
    }
    write!(
        out,
        "use fixshade::scene::Shading;\n\
         use fixshade::target::Rgb8;\n\
         \n\
         /// Every scene, in the order the firmware renders them.\n\
         pub static SCENES: [SceneSpec; {}] = [\n{body}];\n\
         \n\
         /// The largest workspace part over the scenes: the firmware's capacities.\n\
         pub const MAX_NEEDS: Needs = Needs {{\n    \
         vertices: {},\n    \
         values: {},\n    \
         triangles: {},\n    \
         prepared_bytes: {},\n\
         }};\n\
         \n\
         /// Most objects in a scene.\n\
         pub const MAX_OBJECTS: usize = {max_objects};\n\
         \n\
         /// Bytes of mesh tables the scenes use: positions and triangles of\n\
         /// the built-in shapes ({}), identical tables counted once.\n\
         pub const MESH_SHAPE_BYTES: usize = {shape_bytes};\n\
         \n\
         /// Bytes of normal tables the scenes use (normals and their corner\n\
         /// indices, built-in or regenerated), identical tables counted once.\n\
         pub const MESH_NORMAL_BYTES: usize = {normal_bytes};\n",
        scenes.len(),
        max.vertices,
        max.values,
        max.triangles,
        max.prepared_bytes,
        shapes.join(", "),
    )
    .unwrap();
    out.push_str(&meshes);
    Ok(out)
}

/// Rust source of the generated file for [`FIRMWARE_SCENES`].
///
/// # Errors
/// As [`FirmwareScene::load`] and [`generate_for`].
pub fn generate() -> Result<String, String> {
    let scenes = FIRMWARE_SCENES
        .iter()
        .map(|n| FirmwareScene::load(n))
        .collect::<Result<Vec<_>, _>>()?;
    generate_for(&scenes)
}
