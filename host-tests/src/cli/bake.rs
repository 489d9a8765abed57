//! `fixshade bake`: turns an OBJ file into Rust constant mesh data for the
//! core (`fixshade::mesh::Mesh`).
//!
//! The OBJ is read and checked as for scene files
//! ([`scene_file::obj`](crate::scene_file::obj)), centred on its
//! bounding-box centre, scaled by 2 / largest extent into [-1, 1]³ and then
//! by `--scale`, and quantised once to Q1.14 by
//! [`bake::bake_rs`](crate::bake::bake_rs). Normals, computed in f64 on the
//! scaled positions before quantisation:
//!
//! * with `--crease-angle DEG`: per-corner normals by
//!   [`crease_normals`] (the core's rules in f64);
//! * otherwise the OBJ's normals when every face corner names one;
//! * otherwise smooth per-vertex normals by
//!   [`averaged_normals`] (as the bunny).

use std::path::{Path, PathBuf};

use clap::Args;

use crate::bake::{averaged_normals, bake_rs, BakeNormals};
use crate::scene_file::obj::{crease_normals, normalize_positions, read_obj};

use super::common::{print_stdout, write_output};
use super::error::CliError;

/// Largest `--scale`: positions must stay inside Q1.14's [-2, 2).
pub const MAX_BAKE_SCALE: f64 = 1.999;

/// Arguments of `fixshade bake`.
#[derive(Clone, Debug, Args)]
pub struct BakeArgs {
    /// The OBJ file to bake.
    #[arg(value_name = "MODEL.obj")]
    pub model: PathBuf,
    /// The Rust file to write (replaced atomically).
    #[arg(long, value_name = "FILE.rs")]
    pub out: PathBuf,
    /// Generate normals with this crease angle in degrees, 0 to 180
    /// (ignores the OBJ's normals).
    #[arg(long, value_name = "DEG")]
    pub crease_angle: Option<f64>,
    /// Scale after normalising to [-1, 1]³, in (0, 1.999].
    #[arg(long, value_name = "S", default_value_t = 1.0)]
    pub scale: f64,
    /// Name of the constant, in upper case (default: from the file name).
    #[arg(long, value_name = "NAME")]
    pub name: Option<String>,
}

/// Bakes the model (see the [module docs](self)).
pub fn run(args: &BakeArgs) -> Result<(), CliError> {
    let (text, counts) = bake(args)?;
    write_output(&args.out, |w| w.write_all(text.as_bytes()))?;
    print_stdout(&format!("wrote {}: {counts}\n", args.out.display()))
}

/// The Rust source and a summary of the counts, or a bad-input error.
pub fn bake(args: &BakeArgs) -> Result<(String, String), CliError> {
    let scale = args.scale;
    if !(scale > 0.0 && scale <= MAX_BAKE_SCALE) {
        return Err(CliError::input(format!(
            "--scale: must be in (0, {MAX_BAKE_SCALE}], got {scale}"
        )));
    }
    if let Some(c) = args.crease_angle {
        if !(0.0..=180.0).contains(&c) {
            return Err(CliError::input(format!(
                "--crease-angle: must be in [0, 180] degrees, got {c}"
            )));
        }
    }
    let name = match &args.name {
        Some(name) if is_const_name(name) => name.clone(),
        Some(name) => {
            return Err(CliError::input(format!(
                "--name: `{name}` is not an upper-case Rust constant name ([A-Z_][A-Z0-9_]*)"
            )))
        }
        None => const_name(&args.model),
    };
    let file = args.model.display().to_string();
    let obj = read_obj(&args.model).map_err(|e| CliError::input(format!("{file}: {e}")))?;
    let n =
        normalize_positions(&obj.positions).map_err(|e| CliError::input(format!("{file}: {e}")))?;
    let positions: Vec<[f64; 3]> = n.positions.iter().map(|p| p.map(|c| c * scale)).collect();
    let (normals, normals_doc) = match (args.crease_angle, &obj.normals) {
        (Some(deg), _) => {
            let (normals, indices) = crease_normals(&positions, &obj.triangles, deg)
                .map_err(|e| CliError::input(format!("{file}: {e}")))?;
            (
                BakeNormals::PerCorner { normals, indices },
                format!("generated with a crease angle of {deg} deg"),
            )
        }
        (None, Some(normals)) => (
            BakeNormals::PerVertex(normals.clone()),
            "from the OBJ file".to_string(),
        ),
        (None, None) => (
            BakeNormals::PerVertex(averaged_normals(&positions, &obj.triangles)),
            "smooth: normalised sums of the unit face normals".to_string(),
        ),
    };
    let normal_count = match &normals {
        BakeNormals::PerVertex(v) => v.len(),
        BakeNormals::PerCorner { normals, .. } => normals.len(),
    };
    let counts = format!(
        "{} vertices, {} triangles, {normal_count} normals",
        positions.len(),
        obj.triangles.len()
    );
    let source_name = args
        .model
        .file_name()
        .map_or_else(|| file.clone(), |s| s.to_string_lossy().into_owned());
    let doc = [
        format!("Baked from `{source_name}`: {counts}."),
        format!(
            "Positions centred on ({}, {}, {}) and scaled by {} (2 / largest extent x {scale}).",
            n.centre[0],
            n.centre[1],
            n.centre[2],
            n.factor * scale
        ),
        format!("Normals {normals_doc}."),
    ];
    let doc: Vec<&str> = doc.iter().map(String::as_str).collect();
    let text = bake_rs(&name, &doc, &positions, &obj.triangles, Some(&normals));
    Ok((retarget(&text, &name, &source_name), counts))
}

/// Replaces [`bake_rs`]'s header (written for the core's own built-in
/// shapes) by one for user crates, which reach the types as
/// `fixshade::mesh`.
fn retarget(text: &str, name: &str, source: &str) -> String {
    let body = text
        .find("use crate::mesh::")
        .map_or(text, |i| &text[i..])
        .replacen("use crate::mesh::", "use fixshade::mesh::", 1);
    format!("//! Mesh `{name}`, baked by `fixshade bake` from `{source}`: do not edit.\n\n{body}")
}

/// Whether `s` is an upper-case constant name.
fn is_const_name(s: &str) -> bool {
    let mut chars = s.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_uppercase() || c == '_')
        && chars.all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_')
        && s != "_"
}

/// An upper-case constant name made from the file stem of `path`.
fn const_name(path: &Path) -> String {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut name: String = stem
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_uppercase()
            } else {
                '_'
            }
        })
        .collect();
    if !name.starts_with(|c: char| c.is_ascii_uppercase()) {
        name.insert_str(0, "MESH_");
    }
    if !is_const_name(&name) {
        name = "MESH".to_string();
    }
    name
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names() {
        assert_eq!(const_name(Path::new("dir/bunny.obj")), "BUNNY");
        assert_eq!(const_name(Path::new("my-mesh 2.obj")), "MY_MESH_2");
        assert_eq!(const_name(Path::new("3d.obj")), "MESH_3D");
        assert_eq!(const_name(Path::new("_x.obj")), "MESH__X");
        assert!(is_const_name("A_1") && is_const_name("_A"));
        assert!(!is_const_name("a") && !is_const_name("_") && !is_const_name("1A"));
    }
}
