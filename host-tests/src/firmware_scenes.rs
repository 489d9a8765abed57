//! Scenes for the firmware (`examples/firmware`), as Rust source.
//!
//! The firmware has no floating point, so it cannot read a scene file:
//! [`generate`] turns the built-in scenes named in [`FIRMWARE_SCENES`] (and
//! [`generate_for`] any scene files, a user's for `--measure-firmware`)
//! into the source of `examples/firmware/scenes/src/generated.rs`, where every
//! scalar is the raw Q16.16 bits of exactly the value the host renders
//! with (`Q16::from_f64` of the scene's `f64`, as
//! [`render_core`](crate::core_render::render_core) converts it for the
//! `fast` profile). Meshes are the core's built-in constants, or, where the
//! scene regenerates normals (`crease_angle_deg`) or reads an OBJ file,
//! the welded positions, triangles, normals and face normals as constant
//! arrays. Each scene's storage is a call of the core's `const fn`
//! `Capacity::object(&MESH, layout, reach)` per object (see `rooms`:
//! no size is searched here), and whether it needs a depth band
//! ([`convex`]); the firmware's static storage is their maximum, sized by
//! the compiler.
//!
//! The test `tests/firmware_scenes.rs` regenerates the file and compares it
//! byte for byte with the committed one (`MAKE_FIRMWARE_SCENES=1` rewrites
//! it), and checks that the scene built from the generated values renders
//! to the CRC of `fixshade render --scene NAME --profile fast --crc`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use fixshade::geom::Vec3;
use fixshade::illum::LightKind;
use fixshade::mesh::Mesh;
use fixshade::num::{Fast, Real, Q16};
use fixshade::render::{prepare, BandState, Layout, Pool, Reach, RenderError};

pub use fixshade::render::Capacity;
use fixshade::scene::{Scene, Shading};
use fixshade::target::{BandBuf, Rgb565Be};

use crate::builtin::load_builtin;
use crate::core_render::{crc32, CameraInputs, CoreError, CoreScene, OwnedWorkspace, BAND_ROWS};
use crate::scene_file::{PixelFormat, SceneDesc, SceneError, SceneMesh, BUILTIN_MESHES};

/// Why a scene cannot be one of the firmware's, or its frame not rendered
/// on the host (messages only through `Display`, for the command line).
#[derive(Debug)]
pub enum FirmwareSceneError {
    /// No built-in scene of that name.
    Load(SceneError),
    /// The scene is not RGB565.
    PixelFormat {
        /// The scene's name.
        scene: String,
    },
    /// Wider or taller than [`MAX_WIDTH`].
    TooLarge {
        /// The scene's name.
        scene: String,
        /// Its width, pixels.
        width: u32,
        /// Its height, pixels.
        height: u32,
    },
    /// An object scaled non-uniformly.
    NonUniformScale {
        /// The scene's name.
        scene: String,
        /// The object's index.
        object: usize,
    },
    /// More objects than the core takes.
    TooManyObjects {
        /// The scene's name.
        scene: String,
        /// Its objects.
        objects: usize,
    },
    /// The core refuses the scene (its camera).
    Core {
        /// The scene's name.
        scene: String,
        /// The core's error.
        error: CoreError,
    },
    /// Preparing or rendering the frame failed.
    Render {
        /// The scene's name.
        scene: String,
        /// The core's error.
        error: RenderError,
    },
}

impl std::fmt::Display for FirmwareSceneError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Load(e) => write!(f, "{e}"),
            Self::PixelFormat { scene } => {
                write!(f, "{scene}: the firmware renders RGB565 only")
            }
            Self::TooLarge {
                scene,
                width,
                height,
            } => write!(
                f,
                "{scene}: {width}x{height} is larger than the firmware's {MAX_WIDTH}x{MAX_WIDTH}"
            ),
            Self::NonUniformScale { scene, object } => write!(
                f,
                "{scene}: object {object} is scaled non-uniformly; the firmware's scenes take one scale per object"
            ),
            Self::TooManyObjects { scene, objects } => write!(
                f,
                "{scene}: {objects} objects, the core takes at most {}",
                fixshade::scene::MAX_OBJECTS
            ),
            Self::Core { scene, error } => write!(f, "{scene}: {error}"),
            Self::Render { scene, error } => write!(f, "{scene}: {error}"),
        }
    }
}

impl std::error::Error for FirmwareSceneError {}

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

/// How one object of a firmware scene is stored: its layout and reach
/// (the arguments of [`Capacity::object`] besides the mesh).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ObjectRoom {
    /// Values per prepared vertex.
    pub layout: Layout,
    /// Whether the planes cut it or its back faces add vertices.
    pub reach: Reach,
}

/// Q16 bits of `v`, as the host converts it for the `fast` profile.
pub fn q16_bits(v: f64) -> i32 {
    Q16::from_f64(v).to_bits()
}

/// The scene `desc` in Q16, exactly as `render_core(desc, Fast)` builds it.
///
/// # Errors
/// A camera the core refuses.
fn q16_scene(desc: &SceneDesc) -> Result<CoreScene<'_, Q16>, CoreError> {
    CoreScene::new(desc)
}

/// A `Fast` workspace of the lengths `cap`, on the heap.
fn owned(cap: Capacity) -> OwnedWorkspace<i32> {
    // A colour per triangle number: room for any layout.
    OwnedWorkspace::new(cap.vertices, cap.values, cap.made, cap.triangles)
}

/// The storage of `scene` as the firmware sizes it: per object the
/// layout `prepare::<Fast>` chooses and its [`Reach`], and the
/// [`Capacity`] they give.
///
/// The layout comes from one `prepare` into a storage with room for any
/// object (every object [`Reach::Clipped`], 7 values per vertex); the
/// reach from the same frame: an object with more prepared vertices
/// than mesh vertices in the firmware's (fixed) view is cut by the
/// planes or lights back faces of its own, and is given
/// [`Reach::Clipped`] (room for both); a two-sided Gouraud object is
/// given [`Reach::TwoSided`]; the others [`Reach::Inside`]. The sizes
/// themselves are the core's `const fn` ([`Capacity::object`]), which the
/// generated source calls: no size is searched here.
fn rooms(
    scene: &Scene<'_, '_, Q16>,
    w: u32,
    h: u32,
) -> Result<(Vec<ObjectRoom>, Capacity), RenderError> {
    let any = scene.objects.iter().fold(Capacity::EMPTY, |c, o| {
        c.object(&o.mesh, Layout::PhongPosition, Reach::Clipped)
    });
    let mut mem = owned(any);
    let frame = prepare::<Fast>(scene, w, h, mem.ws())?;
    let mut cap = Capacity::EMPTY;
    let rooms = scene
        .objects
        .iter()
        .zip(frame.objects())
        .map(|(o, p)| {
            let reach = if p.verts.len() > o.mesh.vertex_count() {
                Reach::Clipped
            } else if !o.cull_backfaces && o.shading == Shading::Gouraud {
                Reach::TwoSided
            } else {
                Reach::Inside
            };
            cap = cap.object(&o.mesh, p.layout(), reach);
            ObjectRoom {
                layout: p.layout(),
                reach,
            }
        })
        .collect();
    Ok((rooms, cap))
}

/// How far a vertex may lie in front of a face's plane for [`convex`]:
/// 4 units of the Q1.14 positions (2^-12 of the unit), for the rounding
/// of the positions to the grid (measured: the dodecahedron's vertices lie
/// up to 0.05 units in front of a face's plane, its pentagons being split
/// into three triangles each; the sphere's up to 1.56; the bunny's 32 198).
pub const CONVEX_SLACK: f64 = 4.0;

/// Whether `mesh` is convex up to the rounding of its positions: every
/// vertex lies behind the plane of every triangle, or at most
/// [`CONVEX_SLACK`] units in front of it (integer cross and dot products:
/// edge components below 2^16, the cross product below 2^33, the dot
/// product below 2^51; the distance in `f64`). The front faces of a
/// convex mesh never overlap on the screen (nor once clipped), so a scene
/// of one such object with back faces culled draws each pixel at most
/// once (the top-left rule shares edges) and needs no depth band.
/// [`FirmwareScene::new`] leaves the depth band out only when, besides,
/// the frame rendered without it is the frame rendered with it (checked
/// on the host for the firmware's view).
pub fn convex(mesh: &Mesh<'_>) -> bool {
    let p = mesh.positions();
    let sub = |a: [i16; 3], b: [i16; 3]| [0, 1, 2].map(|i| i64::from(a[i]) - i64::from(b[i]));
    mesh.triangles().iter().all(|t| {
        let [a, b, c] = t.map(|i| p.get(usize::from(i)).copied().unwrap_or([0; 3]));
        let (u, v) = (sub(b, a), sub(c, a));
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let len = (n.iter().map(|&x| (x as f64) * (x as f64)).sum::<f64>()).sqrt();
        p.iter().all(|&q| {
            let d = sub(q, a);
            let dot = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
            dot <= 0 || (dot as f64) <= CONVEX_SLACK * len
        })
    })
}

/// What [`FirmwareScene::render_crc`] gives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HostFrame {
    /// CRC-32 of the RGB565 big-endian frame.
    pub crc: u32,
    /// Pixels covered (with a depth band: depth no longer clear; without:
    /// fragments drawn, each pixel at most once).
    pub covered: u32,
    /// Fragments drawn.
    pub drawn: u32,
    /// Prepared vertices.
    pub vertices: usize,
    /// Prepared triangles.
    pub triangles: usize,
    /// `Frame::bytes_used()`.
    pub prepared_bytes: usize,
}

/// Renders the Q16 scene as the firmware does (bands of 16 rows, a 16-bit
/// depth band unless `depth` is false, background cleared per band)
/// into a workspace of exactly `cap`.
fn render_crc(
    scene: &Scene<'_, '_, Q16>,
    w: u32,
    h: u32,
    cap: Capacity,
    depth: bool,
) -> Result<HostFrame, RenderError> {
    let mut mem = owned(cap);
    let frame = prepare::<Fast>(scene, w, h, mem.ws())?;
    let mut band = vec![0u16; (w * BAND_ROWS) as usize];
    let mut z = vec![0u16; (w * BAND_ROWS) as usize];
    let mut buf = BandBuf::<Rgb565Be>::new(&mut band, depth.then_some(&mut z[..]), w, BAND_ROWS)?;
    let mut order = vec![0u16; cap.triangles];
    let mut pool = Box::new(Pool::<i32, 256, 8>::new());
    let mut state = BandState::new(&mut order, &mut pool);
    let mut bytes = Vec::with_capacity((w * h * 2) as usize);
    let mut covered = 0;
    let stats = frame.render_bands(scene, &mut state, &mut buf, |b| {
        bytes.extend(b.bytes());
        covered += b
            .depth()
            .unwrap_or(&[])
            .iter()
            .filter(|&&d| d != u16::MAX)
            .count() as u32;
        Ok::<(), RenderError>(())
    })?;
    Ok(HostFrame {
        crc: crc32(&bytes),
        covered: if depth { covered } else { stats.pixels },
        drawn: stats.pixels,
        vertices: frame.vertex_count(),
        triangles: frame.triangle_count(),
        prepared_bytes: frame.bytes_used(),
    })
}

/// A firmware scene: its description and how it is stored.
pub struct FirmwareScene {
    /// Its name (the built-in name, or the scene file's stem).
    pub name: String,
    /// The scene as the host reads it.
    pub desc: SceneDesc,
    /// Per object: layout and reach.
    pub rooms: Vec<ObjectRoom>,
    /// The storage the generated `Capacity` expression gives.
    pub capacity: Capacity,
    /// Whether it needs a depth band (not for one convex object with back
    /// faces culled: see [`convex`]).
    pub depth: bool,
}

impl FirmwareScene {
    /// Loads the built-in scene `name`.
    ///
    /// # Errors
    /// As [`Self::new`].
    pub fn load(name: &str) -> Result<Self, FirmwareSceneError> {
        let desc = load_builtin(name).map_err(FirmwareSceneError::Load)?;
        Self::new(name.to_string(), desc)
    }

    /// The scene `desc` called `name` for the firmware.
    ///
    /// # Errors
    /// A scene the firmware cannot take: not RGB565, wider or taller than
    /// [`MAX_WIDTH`], a non-uniform scale, more objects than the core
    /// takes, or one the core refuses.
    pub fn new(name: String, desc: SceneDesc) -> Result<Self, FirmwareSceneError> {
        if desc.pixel_format != PixelFormat::Rgb565 {
            return Err(FirmwareSceneError::PixelFormat { scene: name });
        }
        if desc.width > MAX_WIDTH || desc.height > MAX_WIDTH {
            return Err(FirmwareSceneError::TooLarge {
                scene: name,
                width: desc.width,
                height: desc.height,
            });
        }
        if let Some(object) = desc.objects.iter().position(|o| !o.transform.is_uniform()) {
            return Err(FirmwareSceneError::NonUniformScale {
                scene: name,
                object,
            });
        }
        if desc.objects.len() > fixshade::scene::MAX_OBJECTS {
            return Err(FirmwareSceneError::TooManyObjects {
                scene: name,
                objects: desc.objects.len(),
            });
        }
        let q = match q16_scene(&desc) {
            Ok(q) => q,
            Err(error) => return Err(FirmwareSceneError::Core { scene: name, error }),
        };
        let scene = q.scene();
        let (rooms, capacity) = match rooms(&scene, desc.width, desc.height) {
            Ok(r) => r,
            Err(error) => return Err(FirmwareSceneError::Render { scene: name, error }),
        };
        let depth = !(scene.objects.len() == 1
            && scene.objects[0].cull_backfaces
            && convex(&scene.objects[0].mesh));
        Ok(Self {
            name,
            desc,
            rooms,
            capacity,
            depth,
        })
    }

    /// Whether `prepare::<Fast>` accepts a workspace of the lengths `cap`
    /// in `fast` ([`Capacity::in_profile`]: `packed_values` values).
    ///
    /// # Errors
    /// The core's error, e.g. [`RenderError::Capacity`].
    pub fn prepare_with(&self, cap: Capacity) -> Result<(), RenderError> {
        let q = q16_scene(&self.desc).map_err(|_| RenderError::Window)?;
        let scene = q.scene();
        let mut mem = owned(cap.in_profile::<Fast>());
        prepare::<Fast>(&scene, self.desc.width, self.desc.height, mem.ws()).map(|_| ())
    }

    /// The frame rendered from the Q16 values the generated source holds,
    /// into a workspace of exactly [`capacity`](Self::capacity), with a
    /// depth band or none as the firmware renders it.
    ///
    /// # Errors
    /// The core's error.
    pub fn render_crc(&self) -> Result<HostFrame, FirmwareSceneError> {
        let q = q16_scene(&self.desc).map_err(|error| FirmwareSceneError::Core {
            scene: self.name.clone(),
            error,
        })?;
        let scene = q.scene();
        render_crc(
            &scene,
            self.desc.width,
            self.desc.height,
            self.capacity,
            self.depth,
        )
        .map_err(|error| FirmwareSceneError::Render {
            scene: self.name.clone(),
            error,
        })
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
pub fn generate_for(scenes: &[FirmwareScene]) -> Result<String, FirmwareSceneError> {
    let mut out = String::new();
    let mut meshes = String::new();
    // Distinct tables in flash, and the shapes they belong to.
    let mut tables = Tables::default();
    let mut shapes: Vec<&str> = vec![];
    let mut regenerated: Vec<String> = vec![];
    let (mut shape_bytes, mut normal_bytes) = (0, 0);
    let mut caps: Vec<String> = vec![];
    let mut owned_meshes: Vec<&crate::scene_file::OwnedMesh> = vec![];
    let mut depth = false;
    let mut max_objects = 0;
    let mut body = String::new();

    for s in scenes {
        let d = &s.desc;
        let cs = q16_scene(d).map_err(|error| FirmwareSceneError::Core {
            scene: s.name.clone(),
            error,
        })?;
        let qs = cs.scene();
        depth |= s.depth;
        max_objects = max_objects.max(d.objects.len());
        let CameraInputs {
            eye,
            target,
            up,
            fov_y: fov,
            near,
            far,
        } = cs.camera_inputs();
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
        let mut cap_expr = String::from("Capacity::EMPTY");
        for (oi, ((o, obj), parts)) in d
            .objects
            .iter()
            .zip(qs.objects)
            .zip(cs.object_parts())
            .enumerate()
        {
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
                    // A built-in mesh with regenerated normals is named
                    // after it and its crease; an OBJ mesh by its place
                    // among the distinct owned meshes.
                    let (c, about) = match (builtin_base(owned.origin()), o.crease_angle_deg) {
                        (Some(base), Some(crease)) => {
                            let bc = builtin_const(base);
                            if !shapes.contains(&base) {
                                shapes.push(base);
                            }
                            (
                                format!(
                                    "{bc}_CREASE_{}",
                                    format!("{crease}").replace(['.', '-'], "_")
                                ),
                                format!(
                                    "`{bc}` with normals regenerated by the core's `generate_normals`\n\
                                     /// with a crease angle of {crease}°, welded"
                                ),
                            )
                        }
                        _ => {
                            let k = match owned_meshes.iter().position(|t| *t == owned) {
                                Some(k) => k,
                                None => {
                                    owned_meshes.push(owned);
                                    owned_meshes.len() - 1
                                }
                            };
                            let origin = owned.origin().replace(['`', '\n'], " ");
                            (
                                format!("MESH_{k}"),
                                format!("The mesh of `{origin}`, baked (welded, face normals)"),
                            )
                        }
                    };
                    let (a, b) = tables.add_mesh(&m);
                    shape_bytes += a;
                    normal_bytes += b;
                    if !regenerated.contains(&c) {
                        regenerated.push(c.clone());
                        writeln!(
                            meshes,
                            "\n/// {about}: {} vertices.\n\
                             const {c}: Mesh<'static> =\n    \
                             match Mesh::new({c}_POSITIONS, {c}_TRIANGLES, Some({c}_NORMALS)) {{\n        \
                             Ok(mesh) => match mesh.with_face_normals({c}_FACE_NORMALS) {{\n            \
                             Ok(mesh) => mesh,\n            \
                             Err(_) => panic!(\"invalid face normals {c}\"),\n        \
                             }},\n        \
                             Err(_) => panic!(\"invalid normals {c}\"),\n    \
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
            let room = s.rooms[oi];
            cap_expr.push_str(&format!(
                "\n    .object(&{mesh}, Layout::{:?}, Reach::{:?})",
                room.layout, room.reach
            ));
            let m = &obj.material;
            writeln!(body, "            ObjectSpec {{").unwrap();
            writeln!(body, "                mesh: {mesh},").unwrap();
            writeln!(body, "                scale: {},", q(parts.scale)).unwrap();
            writeln!(body, "                rotation: {},", vec(parts.rotation)).unwrap();
            writeln!(
                body,
                "                translation: {},",
                vec(parts.translation)
            )
            .unwrap();
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
        for l in qs.lights {
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
        let k = caps.len();
        writeln!(body, "        capacity: CAPACITY_{k},").unwrap();
        writeln!(body, "        depth: {},", s.depth).unwrap();
        caps.push(format!(
            "\n/// The storage of `{}`.\nconst CAPACITY_{k}: Capacity = {cap_expr};\n",
            s.name
        ));
        writeln!(body, "    }},").unwrap();
    }

    let names: Vec<String> = (0..caps.len()).map(|k| format!("CAPACITY_{k}")).collect();
    let max_cap = names.iter().skip(1).fold(
        names.first().cloned().unwrap_or("Capacity::EMPTY".into()),
        |a, n| format!("{a}\n    .max({n})"),
    );
    let width = scenes.iter().map(|s| s.desc.width).max().unwrap_or(1);
    write!(
        out,
        "//! The firmware's scenes, generated by `fixshade_host::firmware_scenes`\n\
         //! from scene files (the built-in scenes of `host-tests/scenes/`, or\n\
         //! yours for `fixshade report SCENE.toml --measure-firmware`): do not\n\
         //! edit.\n\
         //!\n\
         //! Regenerate with\n\
         //! `MAKE_FIRMWARE_SCENES=1 cargo test -p fixshade-host --test firmware_scenes`\n\
         //! (from the repository root). Every scalar is the Q16.16 bits of\n\
         //! `Q16::from_f64` of the scene file's value, as the host renders the\n\
         //! scene with `--profile fast`. Storage is sized by the core's\n\
         //! `const fn`s (`Capacity::object`) from the meshes each scene uses.\n\
         \n\
         use crate::spec::{{q, v, ObjectSpec, SceneSpec}};\n\
         use fixshade::illum::{{Light, LightKind, Material, Specular}};\n"
    )
    .unwrap();
    if !regenerated.is_empty() {
        writeln!(out, "use fixshade::mesh::Mesh;").unwrap();
    }
    write!(
        out,
        "use fixshade::render::{{Capacity, Layout, Reach}};\n\
         use fixshade::scene::Shading;\n\
         use fixshade::target::Rgb8;\n\
         \n\
         /// Every scene, in the order the firmware renders them.\n\
         pub static SCENES: [SceneSpec; {}] = [\n{body}];\n\
         {}\n\
         /// The largest storage part over the scenes: the firmware's capacities.\n\
         pub const CAPACITY: Capacity = {max_cap};\n\
         \n\
         /// Whether some scene needs a depth band.\n\
         pub const DEPTH: bool = {depth};\n\
         \n\
         /// The widest scene, pixels: the band buffers' width.\n\
         pub const WIDTH: u32 = {width};\n\
         \n\
         /// Most objects in a scene.\n\
         pub const MAX_OBJECTS: usize = {max_objects};\n\
         \n\
         /// Bytes of mesh tables the scenes use: positions and triangles of\n\
         /// the built-in shapes ({}) and of the scene files' meshes,\n\
         /// identical tables counted once.\n\
         pub const MESH_SHAPE_BYTES: usize = {shape_bytes};\n\
         \n\
         /// Bytes of normal tables the scenes use (normals and their corner\n\
         /// indices, built-in or regenerated), identical tables counted once.\n\
         pub const MESH_NORMAL_BYTES: usize = {normal_bytes};\n",
        scenes.len(),
        caps.concat(),
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
pub fn generate() -> Result<String, FirmwareSceneError> {
    let scenes = FIRMWARE_SCENES
        .iter()
        .map(|n| FirmwareScene::load(n))
        .collect::<Result<Vec<_>, _>>()?;
    generate_for(&scenes)
}
