//! From TOML text to a checked [`SceneDesc`]: parsing, range checks and
//! mesh resolution, each error naming the file and the field.

use std::path::Path;

use crate::bake::{normalize, quantize_q14};
use crate::ideal::{Camera, IdealError, Light, LightKind, Material, Shading, SpecularModel};

use super::error::line_column;
use super::obj::{normalize_positions, read_obj, ObjData};
use super::raw::{
    RawCamera, RawLight, RawLightType, RawMaterial, RawObject, RawScale, RawScene, RawShading,
    RawSpecular,
};
use super::{
    builtin_mesh, crease_from_degrees, generate_corner_normals, ObjectDesc, OwnedMesh, SceneDesc,
    SceneError, SceneMesh, Transform, BUILTIN_MESHES, MAX_COORD, MAX_LIGHTS, MAX_OBJECTS,
    MAX_SHININESS, MAX_SIZE,
};

/// Parses, checks and resolves a scene (see [`SceneDesc::from_toml`]).
pub(crate) fn from_toml(
    text: &str,
    file: &str,
    base: Option<&Path>,
) -> Result<SceneDesc, SceneError> {
    let raw = parse(text, file)?;
    Check { file, base }.scene(raw)
}

/// TOML syntax and serde errors (unknown fields, wrong types, unknown
/// names, missing fields).
fn parse(text: &str, file: &str) -> Result<RawScene, SceneError> {
    let position = |e: &toml::de::Error| e.span().map(|s| line_column(text, s.start));
    let de = toml::Deserializer::parse(text).map_err(|e| {
        let position = position(&e);
        let problem = format!("TOML syntax error: {}", e.message());
        match position.and_then(|(line, _)| key_on_line(text, line)) {
            Some(key) => SceneError::field(file, key, problem),
            None => SceneError::file(file, problem),
        }
        .at(position)
    })?;
    serde_path_to_error::deserialize::<_, RawScene>(de).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.inner();
        let message = match inner.message() {
            "wanted string or table" => "invalid type: expected a name in quotes",
            m => m,
        };
        let mut field = if path == "." { String::new() } else { path };
        // Name the unknown field itself, not the table holding it.
        if let Some(rest) = message.strip_prefix("unknown field `") {
            if let Some(name) = rest.split('`').next() {
                if !field.is_empty() && !field.ends_with(&format!(".{name}")) && field != name {
                    field.push('.');
                    field.push_str(name);
                } else if field.is_empty() {
                    field = name.to_owned();
                }
            }
        }
        let error = if field.is_empty() {
            SceneError::file(file, message)
        } else {
            SceneError::field(file, field, message)
        };
        error.at(position(inner))
    })
}

/// The key assigned on one-based line `line` of `text`, with the path of
/// the table it is in (`object[1].material`), for syntax error messages.
/// A line-based guess: `None` when the line does not start with `key =`.
fn key_on_line(text: &str, line: usize) -> Option<String> {
    let mut table = String::new();
    let mut counts: Vec<(String, usize)> = Vec::new();
    for l in text.lines().take(line.saturating_sub(1)) {
        let l = l.trim();
        if let Some(name) = l.strip_prefix("[[").and_then(|r| r.split("]]").next()) {
            let name = name.trim().to_owned();
            let n = match counts.iter_mut().find(|(k, _)| *k == name) {
                Some((_, n)) => {
                    *n += 1;
                    *n
                }
                None => {
                    counts.push((name.clone(), 0));
                    0
                }
            };
            table = format!("{name}[{n}]");
        } else if let Some(name) = l.strip_prefix('[').and_then(|r| r.split(']').next()) {
            table = name.trim().to_owned();
        }
    }
    let current = text.lines().nth(line.checked_sub(1)?)?;
    let (key, _) = current.split_once('=')?;
    let key = key.trim();
    let plain = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.';
    if key.is_empty() || !key.chars().all(plain) {
        return None;
    }
    Some(if table.is_empty() {
        key.to_owned()
    } else {
        format!("{table}.{key}")
    })
}

/// Range checks and resolution for one file.
struct Check<'a> {
    file: &'a str,
    base: Option<&'a Path>,
}

impl Check<'_> {
    fn err(&self, field: impl Into<String>, problem: impl Into<String>) -> SceneError {
        SceneError::field(self.file, field, problem)
    }

    fn scene(&self, raw: RawScene) -> Result<SceneDesc, SceneError> {
        let width = self.size("width", raw.width)?;
        let height = self.size("height", raw.height)?;
        let mut background = [0u8; 3];
        for (slot, &level) in background.iter_mut().zip(&raw.background) {
            *slot = u8::try_from(level).map_err(|_| {
                self.err(
                    "background",
                    format!("levels must be in 0..=255, got {:?}", raw.background),
                )
            })?;
        }
        let camera = self.camera(&raw.camera)?;
        let ambient = raw.lighting.ambient;
        if !(ambient.is_finite() && ambient >= 0.0) {
            return Err(self.err(
                "lighting.ambient",
                format!("must be a finite number >= 0, got {ambient}"),
            ));
        }
        let specular = match raw.lighting.specular {
            RawSpecular::Phong => SpecularModel::Phong,
            RawSpecular::Blinn => SpecularModel::Blinn,
        };
        if raw.light.len() > MAX_LIGHTS {
            return Err(self.err(
                "light",
                format!(
                    "at most {MAX_LIGHTS} lights are allowed, got {}",
                    raw.light.len()
                ),
            ));
        }
        if raw.object.len() > MAX_OBJECTS {
            return Err(self.err(
                "object",
                format!(
                    "at most {MAX_OBJECTS} objects are allowed, got {}",
                    raw.object.len()
                ),
            ));
        }
        let lights = raw
            .light
            .iter()
            .enumerate()
            .map(|(i, l)| self.light(&format!("light[{i}]"), l))
            .collect::<Result<Vec<_>, _>>()?;
        let objects = raw
            .object
            .iter()
            .enumerate()
            .map(|(i, o)| self.object(&format!("object[{i}]"), o))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(SceneDesc {
            source: self.file.to_owned(),
            width,
            height,
            pixel_format: raw.pixel_format,
            profile: raw.profile,
            background,
            camera,
            ambient,
            specular,
            lights,
            objects,
        })
    }

    fn size(&self, field: &str, value: i64) -> Result<u32, SceneError> {
        u32::try_from(value)
            .ok()
            .filter(|v| (1..=MAX_SIZE).contains(v))
            .ok_or_else(|| self.err(field, format!("must be in 1..={MAX_SIZE}, got {value}")))
    }

    /// Finite with magnitude at most [`MAX_COORD`].
    fn coords(&self, field: &str, v: [f64; 3]) -> Result<[f64; 3], SceneError> {
        if v.iter().all(|c| c.is_finite() && c.abs() <= MAX_COORD) {
            Ok(v)
        } else {
            Err(self.err(
                field,
                format!("must be finite numbers of magnitude at most {MAX_COORD:e}, got {v:?}"),
            ))
        }
    }

    fn in_range(&self, field: &str, x: f64, lo: f64, hi: f64) -> Result<f64, SceneError> {
        if x >= lo && x <= hi {
            Ok(x)
        } else {
            Err(self.err(field, format!("must be in [{lo}, {hi}], got {x}")))
        }
    }

    fn color(&self, field: &str, c: [f64; 3]) -> Result<[f64; 3], SceneError> {
        if c.iter().all(|x| (0.0..=1.0).contains(x)) {
            Ok(c)
        } else {
            Err(self.err(field, format!("components must be in [0, 1], got {c:?}")))
        }
    }

    fn camera(&self, raw: &RawCamera) -> Result<Camera, SceneError> {
        let eye = self.coords("camera.eye", raw.eye)?;
        let target = self.coords("camera.target", raw.target)?;
        let up = self.coords("camera.up", raw.up)?;
        let fov = raw.fov_y_deg;
        if !(fov > 0.0 && fov < 180.0) {
            return Err(self.err(
                "camera.fov_y_deg",
                format!("must be in (0, 180) degrees, got {fov}"),
            ));
        }
        let near = raw.near;
        if !(near > 0.0 && near <= MAX_COORD) {
            return Err(self.err(
                "camera.near",
                format!("must be > 0 and at most {MAX_COORD:e}, got {near}"),
            ));
        }
        if let Some(far) = raw.far {
            if !(far > near && far.is_finite()) {
                return Err(self.err(
                    "camera.far",
                    format!("must be finite and > camera.near ({near}), got {far}"),
                ));
            }
        }
        let camera = Camera {
            eye,
            target,
            up,
            fov_y_deg: fov,
            near,
            far: raw.far,
        };
        camera.validate().map_err(|e| match e {
            IdealError::EyeAtTarget => {
                self.err("camera.target", "equals camera.eye: no view direction")
            }
            IdealError::UpParallel => self.err(
                "camera.up",
                "is zero or parallel to the view direction (target - eye)",
            ),
            other => self.err("camera", other.to_string()),
        })?;
        Ok(camera)
    }

    fn light(&self, at: &str, raw: &RawLight) -> Result<Light, SceneError> {
        let kind = match raw.kind {
            RawLightType::Point => {
                if raw.direction.is_some() {
                    return Err(self.err(
                        format!("{at}.direction"),
                        "only directional lights have a direction (point lights have a position)",
                    ));
                }
                let position = raw.position.ok_or_else(|| {
                    self.err(
                        format!("{at}.position"),
                        "missing: a point light needs a position",
                    )
                })?;
                LightKind::Point {
                    position: self.coords(&format!("{at}.position"), position)?,
                }
            }
            RawLightType::Directional => {
                if raw.position.is_some() {
                    return Err(self.err(
                        format!("{at}.position"),
                        "only point lights have a position (directional lights have a direction)",
                    ));
                }
                let field = format!("{at}.direction");
                let direction = raw.direction.ok_or_else(|| {
                    self.err(&field, "missing: a directional light needs a direction")
                })?;
                let direction = self.coords(&field, direction)?;
                if normalize(direction).is_none() {
                    return Err(self.err(&field, "must not be zero"));
                }
                LightKind::Directional { direction }
            }
        };
        let intensity = raw.intensity;
        if !(intensity.is_finite() && intensity >= 0.0) {
            return Err(self.err(
                format!("{at}.intensity"),
                format!("must be a finite number >= 0, got {intensity}"),
            ));
        }
        Ok(Light {
            kind,
            intensity,
            color: self.color(&format!("{at}.color"), raw.color)?,
        })
    }

    fn material(&self, at: &str, raw: &RawMaterial) -> Result<Material, SceneError> {
        let k = |name: &str, x: f64| self.in_range(&format!("{at}.{name}"), x, 0.0, 1.0);
        Ok(Material {
            color: self.color(&format!("{at}.color"), raw.color)?,
            ka: k("ka", raw.ka)?,
            kd: k("kd", raw.kd)?,
            ks: k("ks", raw.ks)?,
            shininess: self.in_range(
                &format!("{at}.shininess"),
                raw.shininess,
                0.0,
                MAX_SHININESS,
            )?,
        })
    }

    fn object(&self, at: &str, raw: &RawObject) -> Result<ObjectDesc, SceneError> {
        let shading = match raw.shading {
            RawShading::Flat => Shading::Flat,
            RawShading::Gouraud => Shading::Gouraud,
            RawShading::Phong => Shading::Phong,
        };
        let crease = raw
            .crease_angle_deg
            .map(|c| self.in_range(&format!("{at}.crease_angle_deg"), c, 0.0, 180.0))
            .transpose()?;
        let ok = |s: f64| s > 0.0 && s <= MAX_COORD;
        let scale = match raw.scale {
            RawScale::Uniform(s) if ok(s) => [s; 3],
            RawScale::Uniform(s) => {
                return Err(self.err(
                    format!("{at}.scale"),
                    format!("must be > 0 and at most {MAX_COORD:e}, got {s}"),
                ))
            }
            RawScale::Axes(axes) if axes.iter().all(|&s| ok(s)) => axes,
            RawScale::Axes(axes) => {
                return Err(self.err(
                    format!("{at}.scale"),
                    format!(
                        "each of [x, y, z] must be > 0 and at most {MAX_COORD:e}, got {axes:?}"
                    ),
                ))
            }
        };
        let rotate = raw.rotate_deg;
        if !rotate.iter().all(|a| a.is_finite() && a.abs() <= MAX_COORD) {
            return Err(self.err(
                format!("{at}.rotate_deg"),
                format!("must be finite angles of magnitude at most {MAX_COORD:e}, got {rotate:?}"),
            ));
        }
        let translate = self.coords(&format!("{at}.translate"), raw.translate)?;
        let material = self.material(&format!("{at}.material"), &raw.material)?;
        let mut transform = Transform {
            scale,
            rotation_rad: rotate.map(f64::to_radians),
            translation: translate,
        };
        let mesh = self.mesh(at, &raw.mesh, crease, &mut transform)?;
        Ok(ObjectDesc {
            mesh,
            transform,
            shading,
            material,
            cull_backfaces: raw.cull_backfaces,
            crease_angle_deg: crease,
        })
    }

    /// Resolves `name`; for an OBJ folds its normalisation into `transform`.
    fn mesh(
        &self,
        at: &str,
        name: &str,
        crease: Option<f64>,
        transform: &mut Transform,
    ) -> Result<SceneMesh, SceneError> {
        let field = format!("{at}.mesh");
        let is_obj = name.to_ascii_lowercase().ends_with(".obj") || name.contains('/');
        if !is_obj {
            let (Some(mesh), Some(&name)) = (
                builtin_mesh(name),
                BUILTIN_MESHES.iter().find(|&&n| n == name),
            ) else {
                return Err(self.err(
                    field,
                    format!(
                        "unknown mesh `{name}`: expected one of {} or a path to an .obj file",
                        BUILTIN_MESHES.join(", ")
                    ),
                ));
            };
            let Some(degrees) = crease else {
                return Ok(SceneMesh::BuiltIn { name, mesh });
            };
            let (normals, indices) = generate_corner_normals(mesh, crease_from_degrees(degrees))
                .map_err(|e| self.err(&field, format!("cannot generate normals: {e}")))?;
            let owned = OwnedMesh::new(
                format!("{name} (crease {degrees} deg)"),
                mesh.positions().to_vec(),
                mesh.triangles().to_vec(),
                normals,
                indices,
            )
            .map_err(|e| self.err(&field, e.to_string()))?;
            return Ok(SceneMesh::Owned(owned));
        }
        let Some(base) = self.base else {
            return Err(self.err(field, "OBJ files cannot be used here (built-in scene)"));
        };
        let path = base.join(name);
        let obj = read_obj(&path)
            .map_err(|e| self.err(&field, format!("OBJ file `{}`: {e}", path.display())))?;
        let (owned, centre, factor) = obj_mesh(&obj, name, crease)
            .map_err(|e| self.err(&field, format!("OBJ file `{}`: {e}", path.display())))?;
        // world = translate + R(S p) with p = q / factor + centre, S the
        // diagonal of the scale: translate + R(S centre) + R((S / factor) q).
        let scaled_centre = std::array::from_fn(|k| transform.scale[k] * centre[k]);
        let r_centre = transform.rotate(scaled_centre);
        for (t, rc) in transform.translation.iter_mut().zip(r_centre) {
            *t += rc;
        }
        for s in &mut transform.scale {
            *s /= factor;
        }
        Ok(SceneMesh::Owned(owned))
    }
}

/// Quantises an OBJ into an [`OwnedMesh`]; returns it with the centre and
/// factor of the normalisation.
fn obj_mesh(
    obj: &ObjData,
    name: &str,
    crease: Option<f64>,
) -> Result<(OwnedMesh, [f64; 3], f64), String> {
    let n = normalize_positions(&obj.positions).map_err(|e| e.to_string())?;
    let positions: Vec<[i16; 3]> = n.positions.iter().map(|p| p.map(quantize_q14)).collect();
    let triangles = obj.triangles.clone();
    let (normals, indices) = match &obj.normals {
        Some(normals) => (
            normals
                .iter()
                .map(|v| normalize(*v).unwrap_or([0.0; 3]).map(quantize_q14))
                .collect(),
            triangles.clone(),
        ),
        None => {
            let mesh = fixshade::mesh::Mesh::new(&positions, &triangles, None)
                .map_err(|e| e.to_string())?;
            generate_corner_normals(&mesh, crease_from_degrees(crease.unwrap_or(180.0)))
                .map_err(|e| format!("cannot generate normals: {e}"))?
        }
    };
    let owned = OwnedMesh::new(name.to_owned(), positions, triangles, normals, indices)
        .map_err(|e| e.to_string())?;
    Ok((owned, n.centre, n.factor))
}
