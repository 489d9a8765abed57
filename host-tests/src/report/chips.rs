//! Chip costs: the firmware's figures measured under QEMU, committed in
//! [`DEFAULT_PATH`] (`docs/measurements/firmware.json`).
//!
//! The file holds, for every core profile on Cortex-M0 (`thumbv6m-none-eabi`,
//! QEMU `mps2-an385`) and Cortex-M4F (`thumbv7em-none-eabihf`,
//! `mps2-an386`), per firmware scene: instructions per frame (geometry,
//! raster; counted exactly by the QEMU plugin), the estimated Cortex-M0
//! cycles (M0 only: ARM DDI 0432C table 3-1, zero wait states, an
//! estimate), covered pixels, the stack high-water mark, the prepared
//! frame's bytes, and per build the flash and static RAM; and the knob
//! variants of the firmware's `knobs` build ([`KnobResult`]: band rows,
//! 32-bit depth, subpixel bits on one scene). With them: the
//! toolchain, the QEMU version and a fingerprint of every source the
//! firmware is built from ([`source_fingerprint`]).
//!
//! `fixshade measure-firmware --write FILE` regenerates the file (see
//! [`super::measure`]); `--check FILE` re-measures and fails when any
//! figure differs (`.ci/firmware` runs it). `fixshade report` reads the
//! file and refuses it (bad input, exit status 2) when it is missing,
//! malformed, or *stale*: its fingerprint differs from the tree's, so its
//! figures may not be the current code's.
//!
//! # RAM of a configuration
//!
//! [`ChipResult::ram`] is what a firmware sized for that one scene needs:
//! the colour band and 16-bit depth band (`width × 16` pixels each), the
//! prepared frame (`Frame::bytes_used`, measured on the chip) and the
//! stack high-water mark (painted stack, measured on the chip). The
//! measured firmware's own static RAM (its workspace sized for the largest
//! scene, the bunny) is [`ChipResult::static_ram`]; the firmware built
//! for the bunny Gouraud scene alone (`--features bunny`, the build the
//! static-RAM budget is about) is in [`Measurements::alone`].

use std::collections::BTreeMap;
use std::hash::Hasher;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::Error;
use crate::core_render::CoreProfile;

use super::embedded::Target;
use super::Mode;

/// The committed measurements, relative to the repository root.
pub const DEFAULT_PATH: &str = "docs/measurements/firmware.json";
/// The version of the file's layout.
pub const SCHEMA: u32 = 1;
/// The one command that regenerates the committed file (from the
/// repository root).
pub const REGENERATE: &str = "cargo run --release -p fixshade-host --bin fixshade -- measure-firmware --write docs/measurements/firmware.json";

/// The repository root this binary was built from (its sources, the
/// firmware and the committed measurements are under it).
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
}

/// One firmware build: a target and a profile.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Build {
    /// `thumbv6m-none-eabi` or `thumbv7em-none-eabihf`.
    pub target: String,
    /// The core profile every scene is rendered with.
    pub profile: String,
    /// Flash: vector table + text + rodata + the `.data` image, bytes.
    pub flash_bytes: u64,
    /// Code (`.text`), bytes.
    pub text_bytes: u64,
    /// Constants (`.rodata`, the meshes among them), bytes.
    pub rodata_bytes: u64,
    /// Static RAM (`.data` + `.bss` + `.uninit`), bytes.
    pub static_ram_bytes: u64,
    /// Soft-float routines linked (AEABI / compiler-builtins names).
    pub softfloat_routines: u64,
    /// The span loops alone (the default `fast` build measures them; other
    /// builds leave this empty).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub spans: Vec<SpanLoop>,
}

/// One span loop measured alone by the firmware: `rows` spans of `long`
/// pixels and `rows` spans of 1 pixel, depth test and write, RGB565 store.
/// The difference cancels the per-span cost, so
/// [`SpanLoop::insns_per_px`] is the loop's cost per pixel.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpanLoop {
    /// The kernel: `flat`, `gouraud`, `phong` (the generic per-pixel
    /// shader), `phong-k1`/`-k2`/`-k4` (the Phong span kernel with 1, 2, 4
    /// directional lights and the viewer at infinity), `phong-kpoint` (one
    /// point light, local viewer).
    pub kernel: String,
    /// Spans per run.
    pub rows: u64,
    /// Pixels of a long span.
    pub long: u64,
    /// Instructions of the run with long spans.
    pub long_insns: u64,
    /// Instructions of the run with 1-pixel spans.
    pub short_insns: u64,
}

impl SpanLoop {
    /// Instructions per pixel: the difference of the two runs over the
    /// `rows · (long - 1)` pixels that tell them apart.
    pub fn insns_per_px(&self) -> f64 {
        let px = self.rows * self.long.saturating_sub(1);
        if px == 0 {
            return 0.0;
        }
        self.long_insns.saturating_sub(self.short_insns) as f64 / px as f64
    }
}

/// One scene measured with one profile on one target.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChipResult {
    /// `thumbv6m-none-eabi` or `thumbv7em-none-eabihf`.
    pub target: String,
    /// The profile.
    pub profile: String,
    /// The firmware scene (a built-in scene's name).
    pub scene: String,
    /// Its shading mode (`null` for a scene mixing modes).
    pub mode: Option<Mode>,
    /// Frame width.
    pub width: u32,
    /// Frame height.
    pub height: u32,
    /// Instructions per frame (geometry + raster).
    pub insns: u64,
    /// Instructions of the geometry (scene, camera, `prepare`).
    pub insns_geometry: u64,
    /// Instructions of the bands (clear, render).
    pub insns_raster: u64,
    /// Estimated Cortex-M0 cycles per frame (M0 only).
    pub cycles: Option<u64>,
    /// ...of the geometry.
    pub cycles_geometry: Option<u64>,
    /// ...of the bands.
    pub cycles_raster: Option<u64>,
    /// Covered pixels.
    pub covered: u64,
    /// Fragments written.
    pub drawn: u64,
    /// Triangle setups.
    pub setups: u64,
    /// Bytes of the prepared frame.
    pub prepared_bytes: u64,
    /// Colour band bytes (width × 16 rows × 2).
    pub band_bytes: u64,
    /// Depth band bytes (width × 16 rows × 2).
    pub depth_bytes: u64,
    /// Stack high-water mark, bytes.
    pub stack: u64,
    /// RAM for this scene: band + depth band + prepared frame + stack
    /// (the built-in scenes); for a user's scene (`--measure-firmware`
    /// with scene files), what a firmware built for it alone holds, as
    /// the firmware reports it: band + depth band (none for one convex
    /// culled object) + storage sized by the compiler + active-triangle
    /// pool + stack.
    pub ram: u64,
    /// Static RAM of the measured firmware (workspace for every scene).
    pub static_ram: u64,
    /// Flash of the measured firmware.
    pub flash: u64,
    /// CRC-32 of the frame on the chip.
    pub crc: String,
    /// CRC-32 of the same frame rendered on the host by the same code
    /// (`host-check`).
    pub host_crc: String,
    /// Whether the two agree.
    pub crc_equal: bool,
}

impl ChipResult {
    /// The chip family.
    pub fn chip(&self) -> Option<Target> {
        target_of(&self.target)
    }

    /// The profile, parsed.
    pub fn core_profile(&self) -> Option<CoreProfile> {
        CoreProfile::parse(&self.profile)
    }

    /// Cycles per frame at the chip: the M0's estimate, or on the M4F
    /// the instructions (one cycle each: a lower bound, the M4 has no
    /// cycle model here).
    pub fn frame_cycles(&self) -> u64 {
        self.cycles.unwrap_or(self.insns)
    }
}

/// The chip of a target triple.
pub fn target_of(triple: &str) -> Option<Target> {
    match triple {
        "thumbv6m-none-eabi" => Some(Target::M0),
        "thumbv7em-none-eabihf" => Some(Target::M4f),
        _ => None,
    }
}

/// One knob variant on one target (the firmware's `knobs` build): `fast`,
/// one scene, band rows × depth bits × subpixel bits.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KnobResult {
    /// `thumbv6m-none-eabi` or `thumbv7em-none-eabihf`.
    pub target: String,
    /// The scene.
    pub scene: String,
    /// Rows per band.
    pub rows: u32,
    /// Depth bits (16 or 32).
    pub depth_bits: u32,
    /// Subpixel bits.
    pub subpixel_bits: u32,
    /// Instructions per frame.
    pub insns: u64,
    /// ...of the geometry.
    pub insns_geometry: u64,
    /// ...of the bands.
    pub insns_raster: u64,
    /// Estimated M0 cycles per frame (M0 only).
    pub cycles: Option<u64>,
    /// Covered pixels.
    pub covered: u64,
    /// Triangle setups (a triangle counts once per band it is set up in).
    pub setups: u64,
    /// Bytes of the prepared frame.
    pub prepared_bytes: u64,
    /// Colour band bytes.
    pub band_bytes: u64,
    /// Depth band bytes.
    pub depth_bytes: u64,
    /// Stack high-water mark.
    pub stack: u64,
    /// band + depth + prepared + stack.
    pub ram: u64,
    /// CRC-32 of the frame (equal to host-check's, checked).
    pub crc: String,
}

impl KnobResult {
    /// Cycles per frame (as [`ChipResult::frame_cycles`]).
    pub fn frame_cycles(&self) -> u64 {
        self.cycles.unwrap_or(self.insns)
    }
}

/// `docs/measurements/firmware.json`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Measurements {
    /// [`SCHEMA`].
    pub schema: u32,
    /// What the file is.
    pub about: String,
    /// The command that regenerates it.
    pub regenerate: String,
    /// `rustc -V` of the toolchain that built the firmware.
    pub toolchain: String,
    /// `qemu-system-arm --version`, first line.
    pub qemu: String,
    /// [`source_fingerprint`] of the sources measured.
    pub source_fingerprint: String,
    /// The firmware's release opt-level.
    pub opt_level: String,
    /// Rows per band.
    pub band_rows: u32,
    /// Depth bits.
    pub depth_bits: u32,
    /// One per target × profile.
    pub builds: Vec<Build>,
    /// One per target × profile × scene.
    pub results: Vec<ChipResult>,
    /// The knob variants per target.
    #[serde(default)]
    pub knobs: Vec<KnobResult>,
    /// Pixels where the knob scene's frame with a 32-bit depth buffer
    /// differs from the 16-bit one (z-fighting the 16 bits lose), host.
    #[serde(default)]
    pub knob_depth32_vs_depth16_pixels: u64,
    /// The firmwares built for one scene alone (`--features bunny`: the
    /// bunny Gouraud scene, what its RAM budget is measured in), per
    /// target; empty in files measured before they were recorded.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub alone: Vec<AloneBuild>,
}

/// A firmware built for some scenes alone (a cargo feature of
/// `examples/firmware`, profile `fast`): its storage, pool and bands sized
/// by the compiler for those scenes only.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AloneBuild {
    /// `thumbv6m-none-eabi` or `thumbv7em-none-eabihf`.
    pub target: String,
    /// The firmware's feature (`bunny`).
    pub features: String,
    /// The scenes it rendered.
    pub scenes: Vec<String>,
    /// Flash: vector table + text + rodata + the `.data` image, bytes.
    pub flash_bytes: u64,
    /// Static RAM (`.data` + `.bss` + `.uninit`), bytes.
    pub static_ram_bytes: u64,
    /// The largest stack high-water mark of its scenes, bytes.
    pub stack: u64,
}

impl Measurements {
    /// The same measurements with only the results and builds of
    /// `profiles` (by name; the knobs and the header stay): what a partial
    /// re-measurement (`measure-firmware --check FILE --profiles ...`) is
    /// compared with.
    pub fn restricted_to(&self, profiles: &[&str]) -> Self {
        let keep = |p: &String| profiles.contains(&p.as_str());
        Self {
            builds: self
                .builds
                .iter()
                .filter(|b| keep(&b.profile))
                .cloned()
                .collect(),
            results: self
                .results
                .iter()
                .filter(|r| keep(&r.profile))
                .cloned()
                .collect(),
            ..self.clone()
        }
    }

    /// The figures that differ from `other`'s, one line each (empty when
    /// they agree).
    pub fn differences(&self, other: &Self) -> Vec<String> {
        let mut out = Vec::new();
        for (what, a, b) in [
            ("schema", self.schema.to_string(), other.schema.to_string()),
            ("toolchain", self.toolchain.clone(), other.toolchain.clone()),
            ("qemu", self.qemu.clone(), other.qemu.clone()),
            (
                "source_fingerprint",
                self.source_fingerprint.clone(),
                other.source_fingerprint.clone(),
            ),
            ("opt_level", self.opt_level.clone(), other.opt_level.clone()),
        ] {
            if a != b {
                out.push(format!("{what}: {a} -> {b}"));
            }
        }
        let key = |r: &ChipResult| (r.target.clone(), r.profile.clone(), r.scene.clone());
        let mine: BTreeMap<_, &ChipResult> = self.results.iter().map(|r| (key(r), r)).collect();
        let theirs: BTreeMap<_, &ChipResult> = other.results.iter().map(|r| (key(r), r)).collect();
        for (k, a) in &mine {
            match theirs.get(k) {
                None => out.push(format!("{} {} {}: no longer measured", k.0, k.1, k.2)),
                Some(b) if a != b => {
                    let (ja, jb) = (
                        serde_json::to_value(a).unwrap_or_default(),
                        serde_json::to_value(b).unwrap_or_default(),
                    );
                    let mut fields = Vec::new();
                    if let (Some(oa), Some(ob)) = (ja.as_object(), jb.as_object()) {
                        for (f, va) in oa {
                            if ob.get(f) != Some(va) {
                                fields.push(format!(
                                    "{f} {va} -> {}",
                                    ob.get(f).cloned().unwrap_or_default()
                                ));
                            }
                        }
                    }
                    out.push(format!("{} {} {}: {}", k.0, k.1, k.2, fields.join(", ")));
                }
                Some(_) => {}
            }
        }
        if self.knobs != other.knobs
            || self.knob_depth32_vs_depth16_pixels != other.knob_depth32_vs_depth16_pixels
        {
            let n = self
                .knobs
                .iter()
                .zip(&other.knobs)
                .filter(|(a, b)| a != b)
                .count();
            out.push(format!(
                "knobs: {n} variant(s) differ ({} measured before, {} now)",
                self.knobs.len(),
                other.knobs.len()
            ));
        }
        for k in theirs.keys().filter(|k| !mine.contains_key(*k)) {
            out.push(format!("{} {} {}: newly measured", k.0, k.1, k.2));
        }
        if self.alone != other.alone {
            for a in &other.alone {
                let was = self
                    .alone
                    .iter()
                    .find(|o| o.target == a.target && o.features == a.features);
                if was != Some(a) {
                    out.push(format!(
                        "{} alone ({}): flash {} static RAM {} stack {} (was {:?})",
                        a.features,
                        a.target,
                        a.flash_bytes,
                        a.static_ram_bytes,
                        a.stack,
                        was.map(|o| (o.flash_bytes, o.static_ram_bytes, o.stack))
                    ));
                }
            }
            for a in &self.alone {
                if !other
                    .alone
                    .iter()
                    .any(|o| o.target == a.target && o.features == a.features)
                {
                    out.push(format!(
                        "{} alone ({}): no longer measured",
                        a.features, a.target
                    ));
                }
            }
        }
        let bkey = |b: &Build| (b.target.clone(), b.profile.clone());
        let bmine: BTreeMap<_, &Build> = self.builds.iter().map(|b| (bkey(b), b)).collect();
        for b in &other.builds {
            if bmine.get(&bkey(b)) != Some(&b) {
                out.push(format!(
                    "build {} {}: flash {} text {} rodata {} static RAM {} (was {:?})",
                    b.target,
                    b.profile,
                    b.flash_bytes,
                    b.text_bytes,
                    b.rodata_bytes,
                    b.static_ram_bytes,
                    bmine
                        .get(&bkey(b))
                        .map(|o| (o.flash_bytes, o.static_ram_bytes))
                ));
            }
        }
        out
    }

    /// The results of one chip.
    pub fn of(&self, chip: Target) -> impl Iterator<Item = &ChipResult> {
        self.results.iter().filter(move |r| r.chip() == Some(chip))
    }
}

/// Reads and checks a measurements file: readable, valid JSON of this
/// layout ([`SCHEMA`]), every target and profile known, every result
/// with a positive instruction count. Not the freshness: see
/// [`check_fresh`].
///
/// # Errors
/// [`Error::Input`] naming the file and the problem.
pub fn load(path: &Path) -> Result<Measurements, Error> {
    let file = path.display();
    let text = std::fs::read_to_string(path).map_err(|e| {
        Error::input(format!(
            "{file}: cannot read the firmware measurements: {e} (regenerate with `{REGENERATE}`)"
        ))
    })?;
    parse(&text, &file.to_string())
}

/// [`load`] from text; `file` names it in errors.
///
/// # Errors
/// As [`load`].
pub fn parse(text: &str, file: &str) -> Result<Measurements, Error> {
    let de = &mut serde_json::Deserializer::from_str(text);
    let m: Measurements = serde_path_to_error::deserialize(de).map_err(|e| {
        Error::input(format!(
            "{file}: malformed firmware measurements at `{}`: {}",
            e.path(),
            e.inner()
        ))
    })?;
    if m.schema != SCHEMA {
        return Err(Error::input(format!(
            "{file}: schema {} is not {SCHEMA} (regenerate with `{REGENERATE}`)",
            m.schema
        )));
    }
    if m.results.is_empty() {
        return Err(Error::input(format!("{file}: no results")));
    }
    for (i, r) in m.results.iter().enumerate() {
        let bad = |what: String| Error::input(format!("{file}: results[{i}]: {what}"));
        if r.chip().is_none() {
            return Err(bad(format!("unknown target `{}`", r.target)));
        }
        if r.core_profile().is_none() {
            return Err(bad(format!("unknown profile `{}`", r.profile)));
        }
        if r.insns == 0 || r.insns != r.insns_geometry + r.insns_raster {
            return Err(bad(format!(
                "insns {} is not geometry {} + raster {} (or is 0)",
                r.insns, r.insns_geometry, r.insns_raster
            )));
        }
    }
    Ok(m)
}

/// Checks that `m` was measured from the sources under `root`.
///
/// # Errors
/// Bad input naming `file`, both fingerprints and the command that
/// regenerates the file.
pub fn check_fresh(m: &Measurements, root: &Path, file: &str) -> Result<(), Error> {
    let now = source_fingerprint(root)?;
    if now != m.source_fingerprint {
        return Err(Error::input(format!(
            "{file}: stale firmware measurements: measured from sources {} but the tree's are {now} (core, firmware or toolchain changed); regenerate with `{REGENERATE}`, or pass --allow-stale to use them anyway",
            m.source_fingerprint
        )));
    }
    Ok(())
}

/// Appends the source files (`.rs`, `.toml`, `.lock`, `.x`, `.c`, `.h`)
/// under `root/rel` to `out`, skipping cargo's build folders (those holding
/// a `CACHEDIR.TAG`; a source module may well be called `target`, as
/// `src/target/` is).
fn walk(root: &Path, rel: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(root.join(rel)) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name();
        let r = rel.join(&name);
        let Ok(ft) = e.file_type() else { continue };
        if ft.is_dir() {
            if !root.join(&r).join("CACHEDIR.TAG").is_file() {
                walk(root, &r, out);
            }
        } else if ft.is_file() {
            let keep = r
                .extension()
                .and_then(|x| x.to_str())
                .is_some_and(|x| matches!(x, "rs" | "toml" | "lock" | "x" | "c" | "h"));
            if keep {
                out.push(r);
            }
        }
    }
}

/// The files a firmware build needs besides [`source_files`] but which do
/// not change its code: the README the core's docs include, the firmware
/// workspace's host member `host-check`, and the root manifest's benches
/// and examples.
pub fn build_only_files(root: &Path) -> Vec<PathBuf> {
    let mut out = vec![PathBuf::from("README.md")];
    walk(root, Path::new("examples/firmware/host-check"), &mut out);
    // The root manifest's bench and example targets must exist for cargo
    // to read it.
    walk(root, Path::new("benches"), &mut out);
    if let Ok(entries) = std::fs::read_dir(root.join("examples")) {
        for e in entries.flatten() {
            let p = Path::new("examples").join(e.file_name());
            if e.file_type().is_ok_and(|t| t.is_file()) && p.extension().is_some_and(|x| x == "rs")
            {
                out.push(p);
            }
        }
    }
    out
}

/// The files a firmware measurement depends on, relative to `root`:
/// the core (`Cargo.toml`, `src/`), the toolchain pin, and the firmware
/// (`examples/firmware/`: manifests, lock file, build script, memory
/// maps, sources, scenes, QEMU plugin), sorted.
pub fn source_files(root: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for f in ["Cargo.toml", "build.rs", "rust-toolchain.toml"] {
        if root.join(f).is_file() {
            out.push(PathBuf::from(f));
        }
    }
    walk(root, Path::new("src"), &mut out);
    let fw = Path::new("examples/firmware");
    for f in ["Cargo.toml", "Cargo.lock", "build.rs"] {
        if root.join(fw).join(f).is_file() {
            out.push(fw.join(f));
        }
    }
    for d in ["src", "scenes", "memory", "qemu-plugin"] {
        walk(root, &fw.join(d), &mut out);
    }
    out.sort();
    out
}

/// FNV-1a (64 bits) of every [`source_files`] path and content:
/// `fnv1a64:` and 16 hex digits.
///
/// # Errors
/// Bad input when `root` holds none of the sources (not a checkout).
pub fn source_fingerprint(root: &Path) -> Result<String, Error> {
    let files = source_files(root);
    if !files.iter().any(|f| f.starts_with("src")) {
        return Err(Error::input(format!(
            "{}: no fixshade sources here to check the firmware measurements against",
            root.display()
        )));
    }
    let mut h = fnv::FnvHasher::default();
    let mut eat = |bytes: &[u8]| h.write(bytes);
    for f in &files {
        // Paths with `/` whatever the OS.
        let name: Vec<String> = f
            .components()
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .collect();
        eat(name.join("/").as_bytes());
        eat(&[0]);
        eat(&std::fs::read(root.join(f)).unwrap_or_default());
        eat(&[0]);
    }
    Ok(format!("fnv1a64:{:016x}", h.finish()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Measurements {
        let r = ChipResult {
            target: "thumbv6m-none-eabi".into(),
            profile: "fast".into(),
            scene: "dodeca-flat-n100".into(),
            mode: Some(Mode::Flat),
            width: 160,
            height: 160,
            insns: 300,
            insns_geometry: 100,
            insns_raster: 200,
            cycles: Some(450),
            cycles_geometry: Some(150),
            cycles_raster: Some(300),
            covered: 6764,
            drawn: 6764,
            setups: 53,
            prepared_bytes: 492,
            band_bytes: 5120,
            depth_bytes: 5120,
            stack: 1000,
            ram: 11732,
            static_ram: 80480,
            flash: 100_000,
            crc: "0x1".into(),
            host_crc: "0x1".into(),
            crc_equal: true,
        };
        Measurements {
            schema: SCHEMA,
            about: String::new(),
            regenerate: REGENERATE.into(),
            toolchain: "rustc 1.95.0".into(),
            qemu: "QEMU 7.2".into(),
            source_fingerprint: "fnv1a64:0".into(),
            opt_level: "3".into(),
            band_rows: 16,
            depth_bits: 16,
            builds: vec![],
            results: vec![r],
            knobs: vec![],
            knob_depth32_vs_depth16_pixels: 0,
            alone: Vec::new(),
        }
    }

    #[test]
    fn reads_what_it_writes_and_names_the_problems() {
        let m = sample();
        let text = serde_json::to_string_pretty(&m).unwrap();
        assert_eq!(parse(&text, "f.json").unwrap(), m);
        let e = parse("{", "f.json").unwrap_err();
        assert!(e.to_string().starts_with("f.json: malformed"), "{e}");
        assert!(e.is_input(), "{e:?}");
        let bad = text.replace("\"insns\": 300", "\"insns\": \"many\"");
        let e = parse(&bad, "f.json").unwrap_err();
        assert!(e.to_string().contains("`results[0].insns`"), "{e}");
        let bad = text.replace("thumbv6m-none-eabi", "thumbv8m");
        let e = parse(&bad, "f.json").unwrap_err();
        assert!(e.to_string().contains("unknown target `thumbv8m`"), "{e}");
        let bad = text.replace("\"insns\": 300", "\"insns\": 301");
        assert!(parse(&bad, "f.json")
            .unwrap_err()
            .to_string()
            .contains("not geometry 100 + raster 200"));
        let bad = text.replace("\"schema\": 1", "\"schema\": 0");
        assert!(parse(&bad, "f.json")
            .unwrap_err()
            .to_string()
            .contains("schema 0 is not 1"));
        let e = load(Path::new("/nonexistent/firmware.json")).unwrap_err();
        assert!(e
            .to_string()
            .contains("cannot read the firmware measurements"));
    }

    #[test]
    fn differences_name_the_figure() {
        let a = sample();
        let mut b = a.clone();
        assert!(a.differences(&b).is_empty());
        b.results[0].insns_raster = 250;
        b.results[0].insns = 350;
        let d = a.differences(&b);
        assert_eq!(d.len(), 1, "{d:?}");
        assert!(
            d[0].starts_with("thumbv6m-none-eabi fast dodeca-flat-n100: "),
            "{}",
            d[0]
        );
        assert!(d[0].contains("insns 300 -> 350"), "{}", d[0]);
        assert!(d[0].contains("insns_raster 200 -> 250"), "{}", d[0]);
    }

    #[test]
    fn the_alone_builds_are_read_from_old_files_and_compared() {
        let a = sample();
        let text = serde_json::to_string_pretty(&a).unwrap();
        assert!(!text.contains("\"alone\""), "{text}");
        assert_eq!(parse(&text, "f.json").unwrap().alone, []);
        let mut b = a.clone();
        b.alone.push(AloneBuild {
            target: "thumbv6m-none-eabi".into(),
            features: "bunny".into(),
            scenes: vec!["bunny-gouraud".into()],
            flash_bytes: 60_000,
            static_ram_bytes: 40_616,
            stack: 5_000,
        });
        let text = serde_json::to_string_pretty(&b).unwrap();
        assert_eq!(parse(&text, "f.json").unwrap(), b);
        assert_eq!(
            a.differences(&b),
            ["bunny alone (thumbv6m-none-eabi): flash 60000 static RAM 40616 stack 5000 (was None)"]
        );
        assert_eq!(
            b.differences(&a),
            ["bunny alone (thumbv6m-none-eabi): no longer measured"]
        );
        // A partial check still compares them.
        let mut c = b.clone();
        c.alone[0].static_ram_bytes += 4;
        assert_eq!(b.restricted_to(&["fast"]).differences(&c).len(), 1);
    }

    #[test]
    fn a_partial_check_compares_only_its_profiles_and_the_sources() {
        let mut committed = sample();
        let mut precise = committed.results[0].clone();
        precise.profile = "precise".into();
        committed.results.push(precise);
        // A re-measurement of `fast` alone.
        let mut fresh = sample();
        assert_eq!(committed.differences(&fresh).len(), 1, "precise is missing");
        assert!(committed
            .restricted_to(&["fast"])
            .differences(&fresh)
            .is_empty());
        // Its figures are still compared...
        fresh.results[0].insns_raster += 1;
        let d = committed.restricted_to(&["fast"]).differences(&fresh);
        assert_eq!(d.len(), 1, "{d:?}");
        assert!(d[0].contains("insns_raster 200 -> 201"), "{}", d[0]);
        // ...and so are the sources the whole file was measured from.
        fresh.results[0].insns_raster -= 1;
        fresh.source_fingerprint = "fnv1a64:1".into();
        let d = committed.restricted_to(&["fast"]).differences(&fresh);
        assert_eq!(d, ["source_fingerprint: fnv1a64:0 -> fnv1a64:1"]);
    }

    #[test]
    fn the_fingerprint_hash_is_fnv1a_64() {
        // The published FNV-1a 64 test vectors: the fingerprints recorded
        // in docs/measurements/firmware.json stay comparable.
        let fnv = |bytes: &[u8]| {
            let mut h = fnv::FnvHasher::default();
            h.write(bytes);
            h.finish()
        };
        assert_eq!(fnv(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv(b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn the_fingerprint_covers_core_firmware_and_toolchain() {
        let files = source_files(&repo_root());
        let has = |p: &str| files.iter().any(|f| f == Path::new(p));
        assert!(has("src/lib.rs") && has("Cargo.toml"));
        assert!(has("examples/firmware/src/main.rs"));
        assert!(has("examples/firmware/scenes/src/generated.rs"));
        assert!(has("examples/firmware/qemu-plugin/insn_count.c"));
        assert!(has("rust-toolchain.toml"));
        assert!(!files.iter().any(|f| f.starts_with("host-tests")));
        let fp = source_fingerprint(&repo_root()).unwrap();
        assert!(fp.starts_with("fnv1a64:") && fp.len() == 24, "{fp}");
        assert!(source_fingerprint(Path::new("/nonexistent")).is_err());
    }
}
