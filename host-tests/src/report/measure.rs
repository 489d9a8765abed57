//! Measuring the firmware under QEMU: every profile on both targets
//! (`fixshade measure-firmware`, `fixshade report --measure-firmware`).
//!
//! For each target (`thumbv6m-none-eabi` on QEMU `mps2-an385` with the
//! plugin's M0 cycle model, `thumbv7em-none-eabihf` on `mps2-an386`) and
//! each profile, builds `examples/firmware` (the default build for `fast`,
//! the feature `profile-NAME` otherwise), reads
//! the ELF's section sizes and soft-float symbols, runs it under QEMU with
//! the instruction-counting plugin (`qemu-plugin/insn_count.c`, built with
//! `gcc`), and pairs the i-th `scene` line with the plugin's regions 2i
//! (geometry) and 2i + 1 (bands). The host renders the same scenes with the
//! same code (`host-check [--profile NAME]`) for the CRCs. Then the
//! firmwares built for some scenes alone ([`ALONE`]: the bunny): their
//! static RAM and stack, their frames the default build's.
//!
//! The builds are made from a copy of the sources at a fixed path (see
//! `Stage`: counts are then the same on every clone), one target folder
//! per target (`examples/firmware/target/measure-TARGET`), both targets at
//! once; cargo keeps one artifact per feature set, so an unchanged profile
//! is not rebuilt. The default build (`target/TARGET/release`) is not
//! touched.
//!
//! One measurement at a time per machine: each holds an exclusive lock
//! on [`STAGE_LOCK`] from the plugin's build to its last run (a second one
//! prints "waiting for another measurement (lock FILE)" and waits; see
//! [`StageLock`]).
//!
//! Needs `qemu-system-arm`, `gcc` and the two Rust targets (`rustup target
//! add`, pinned by `rust-toolchain.toml`); a missing tool is bad input
//! (exit status 2) naming it. A failed build or run, a plugin warning, or
//! a chip CRC that differs from the host's for a fixed-point profile, or
//! a fixed-point profile linking soft-float routines on the M0, is a
//! failure (exit status 1): float profiles' CRCs are recorded and compared,
//! never required to agree.

use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::Command;

use indicatif::{ProgressBar, ProgressStyle};

use crate::core_render::{CoreProfile, BAND_ROWS};

use crate::firmware_scenes::{generate_for, FirmwareScene};
use crate::scene_file::SceneDesc;

use super::chips::{
    self, AloneBuild, Build, ChipResult, KnobResult, Measurements, SpanLoop, REGENERATE, SCHEMA,
};
use super::{Error, Mode};

mod lock;
pub use lock::{waiting_message, StageLock, LOCK_FD_ENV, STAGE_LOCK};

/// The targets, with their QEMU machine and plugin arguments.
pub const TARGETS: [(&str, &str, &str, &str); 2] = [
    ("thumbv6m-none-eabi", "cortex-m3", "mps2-an385", ",m0=on"),
    ("thumbv7em-none-eabihf", "cortex-m4", "mps2-an386", ""),
];

/// What to measure.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MeasureOptions {
    /// The repository root.
    pub root: PathBuf,
    /// The profiles (all by default).
    pub profiles: Vec<CoreProfile>,
    /// Draw a progress bar on stderr (only on a terminal).
    pub progress: bool,
}

fn failed(message: String) -> Error {
    Error::Measurement(message)
}

fn run(cmd: &mut Command, what: &str) -> Result<String, Error> {
    let out = cmd
        .output()
        .map_err(|e| Error::input(format!("{what}: cannot run: {e}")))?;
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        let tail: Vec<&str> = err.lines().rev().take(15).collect();
        let tail: Vec<&str> = tail.into_iter().rev().collect();
        return Err(failed(format!(
            "{what} failed ({}): {}",
            out.status,
            tail.join(" | ")
        )));
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// The first line a tool prints for `--version`, or bad input naming it.
fn tool_version(tool: &str, hint: &str) -> Result<String, Error> {
    let out = Command::new(tool).arg("--version").output().map_err(|_| {
        Error::input(format!(
            "{tool} not found: measuring the firmware needs it ({hint})"
        ))
    })?;
    Ok(String::from_utf8_lossy(&out.stdout)
        .lines()
        .next()
        .unwrap_or("")
        .trim()
        .to_string())
}

/// `key=value` of a firmware line.
fn kv<'a>(line: &'a str, key: &str) -> Option<&'a str> {
    line.split_whitespace()
        .find_map(|w| w.strip_prefix(key)?.strip_prefix('='))
}

fn num(line: &str, key: &str) -> Result<u64, Error> {
    kv(line, key)
        .and_then(|v| v.parse().ok())
        .ok_or_else(|| failed(format!("firmware line without a number `{key}`: {line}")))
}

/// Section sizes in bytes: flash, static RAM, text, rodata.
type Sizes = (u64, u64, u64, u64);

/// Section sizes of an ELF32 little-endian file and the names of the
/// defined symbols.
fn elf_info(path: &Path) -> Result<(Sizes, Vec<String>), Error> {
    let bytes =
        std::fs::read(path).map_err(|e| failed(format!("{}: cannot read: {e}", path.display())))?;
    let bad = || {
        failed(format!(
            "{}: not a 32-bit little-endian ELF",
            path.display()
        ))
    };
    let u16_at = |o: usize| -> Option<u64> {
        Some(u64::from(u16::from_le_bytes(
            bytes.get(o..o + 2)?.try_into().ok()?,
        )))
    };
    let u32_at = |o: usize| -> Option<u64> {
        Some(u64::from(u32::from_le_bytes(
            bytes.get(o..o + 4)?.try_into().ok()?,
        )))
    };
    if bytes.get(..6) != Some(&[0x7f, b'E', b'L', b'F', 1, 1][..]) {
        return Err(bad());
    }
    let shoff = u32_at(0x20).ok_or_else(bad)? as usize;
    let shentsize = u16_at(0x2e).ok_or_else(bad)? as usize;
    let shnum = u16_at(0x30).ok_or_else(bad)? as usize;
    let shstrndx = u16_at(0x32).ok_or_else(bad)? as usize;
    // (name offset, type, offset, size, link)
    let sec = |i: usize| -> Option<(u64, u64, u64, u64, u64)> {
        let b = shoff + i * shentsize;
        Some((
            u32_at(b)?,
            u32_at(b + 4)?,
            u32_at(b + 16)?,
            u32_at(b + 20)?,
            u32_at(b + 24)?,
        ))
    };
    let cstr = |o: usize| -> String {
        let s = bytes.get(o..).unwrap_or(&[]);
        let end = s.iter().position(|&c| c == 0).unwrap_or(s.len());
        String::from_utf8_lossy(&s[..end]).into_owned()
    };
    let strtab = sec(shstrndx).ok_or_else(bad)?.2 as usize;
    let (mut flash, mut ram, mut text, mut rodata) = (0, 0, 0, 0);
    let mut symbols = Vec::new();
    for i in 0..shnum {
        let (name, kind, off, size, link) = sec(i).ok_or_else(bad)?;
        match cstr(strtab + name as usize).as_str() {
            ".vector_table" => flash += size,
            ".text" => {
                flash += size;
                text = size;
            }
            ".rodata" => {
                flash += size;
                rodata = size;
            }
            ".data" => {
                flash += size;
                ram += size;
            }
            ".bss" | ".uninit" => ram += size,
            _ => {}
        }
        // SHT_SYMTAB: 16-byte entries, names in the linked string table.
        if kind == 2 {
            let names = sec(link as usize).ok_or_else(bad)?.2 as usize;
            for s in 0..(size as usize / 16) {
                let e = off as usize + 16 * s;
                let (Some(n), Some(shndx)) = (u32_at(e), u16_at(e + 14)) else {
                    return Err(bad());
                };
                if shndx != 0 && n != 0 {
                    symbols.push(cstr(names + n as usize));
                }
            }
        }
    }
    Ok(((flash, ram, text, rodata), symbols))
}

/// Soft-float routines by name (the AEABI helpers and compiler-builtins'
/// `__addsf3`-style names), as `.ci/firmware` finds them.
fn is_softfloat(name: &str) -> bool {
    let Some(rest) = name.strip_prefix("__") else {
        return false;
    };
    rest.starts_with("aeabi_f")
        || rest.starts_with("aeabi_d")
        || rest.starts_with("float")
        || rest.starts_with("fix")
        || ["sf2", "df2", "sf3", "df3", "sf", "df"].iter().any(|s| {
            rest.ends_with(s)
                && rest.len() > s.len()
                && rest.chars().all(|c| c.is_ascii_alphanumeric())
        })
}

/// `cargo run` of the firmware workspace's `host-check` (profile `host`)
/// in `fw`; its arguments follow a `--`.
fn host_check(fw: &Path) -> Command {
    let mut cmd = Command::new("cargo");
    cmd.current_dir(fw).args([
        "run",
        "-q",
        "--profile",
        "host",
        "-p",
        "fixshade-host-check",
    ]);
    cmd
}

/// The CRCs of `host-check` for a profile, by scene.
fn host_crcs(
    fw: &Path,
    profile: CoreProfile,
    target_dir: Option<&Path>,
) -> Result<BTreeMap<String, String>, Error> {
    let mut cmd = host_check(fw);
    if let Some(dir) = target_dir {
        cmd.env("CARGO_TARGET_DIR", dir);
    }
    if profile != CoreProfile::Fast {
        cmd.args(["--", "--profile", profile.name()]);
    }
    let out = run(
        &mut cmd,
        &format!("host-check --profile {}", profile.name()),
    )?;
    Ok(out
        .lines()
        .filter(|l| l.starts_with("scene "))
        .filter_map(|l| {
            Some((
                l.split_whitespace().nth(1)?.to_string(),
                kv(l, "crc")?.to_string(),
            ))
        })
        .collect())
}

/// Instructions and estimated M0 cycles of each counted region.
type Regions = Vec<(u64, Option<u64>)>;

/// What one firmware build printed and counted.
struct Run {
    /// Its semihosting output.
    out: String,
    /// The plugin's regions.
    regions: Regions,
    /// Flash, static RAM, text, rodata.
    sizes: Sizes,
    /// Defined symbols.
    symbols: Vec<String>,
}

/// Where the measured firmware is built from: a copy of exactly the
/// fingerprinted sources ([`chips::source_files`], and
/// [`chips::build_only_files`]) at the fixed path [`STAGE`], built into the firmware's own
/// `target/`.
///
/// Why a copy: the core is a path dependency outside the firmware's
/// workspace, so cargo hashes its absolute path into the crate's metadata
/// and with it every symbol name, and LLVM's inlining order follows the
/// names: the same sources built in two clones at different paths differed
/// by up to 25 000 instructions (0.12 %, `fast-pc` bunny on thumbv6m) and
/// 28 bytes of flash. Built from one path, the counts are reproducible on
/// any clone, which `measure-firmware --check` requires.
struct Stage {
    /// The copy's root.
    src: PathBuf,
    /// The firmware's `target/` in the repository (builds stay cached).
    target_dir: PathBuf,
}

/// The fixed path of the measured copy of the sources (one path for every
/// clone: see the module's notes on reproducible counts).
pub const STAGE: &str = "/tmp/fixshade-measure-src";

impl Stage {
    /// The same copy built into a target folder of its own for `target`
    /// (`target/measure-TARGET`), so that both targets build at once.
    fn for_target(&self, target: &str) -> Self {
        Self {
            src: self.src.clone(),
            target_dir: self.target_dir.join(format!("measure-{target}")),
        }
    }

    /// Copies the fingerprinted sources of `root` to [`STAGE`] (see
    /// [`sync_copy`]: a file whose staged copy already holds its content
    /// keeps it, and its time, so cargo does not rebuild what was built
    /// from it, e.g. the core after `cli_firmware`'s measurement).
    fn new(root: &Path) -> Result<Self, Error> {
        let src = PathBuf::from(STAGE);
        let mut files = chips::source_files(root);
        files.extend(chips::build_only_files(root));
        sync_copy(root, &files, &src)?;
        Ok(Self {
            src,
            target_dir: root.join("examples/firmware/target"),
        })
    }
}

/// Makes `dest` hold exactly `files` (relative paths) of `root`: a file
/// whose copy in `dest` has the same content is left alone (its
/// modification time too: cargo decides freshness by it), any other is
/// written anew (a new time: rebuilt), and files in `dest` that are not in
/// `files` are removed. Content, not time, decides, so a staged file that
/// another checkout or a user's scene (the generated scenes file) changed
/// is always rewritten.
fn sync_copy(root: &Path, files: &[PathBuf], dest: &Path) -> Result<(), Error> {
    fn existing(dir: &Path, rel: &Path, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir.join(rel)) else {
            return;
        };
        for e in entries.flatten() {
            let p = rel.join(e.file_name());
            match e.file_type() {
                Ok(t) if t.is_dir() => existing(dir, &p, out),
                Ok(_) => out.push(p),
                Err(_) => {}
            }
        }
    }
    let wanted: std::collections::BTreeSet<&Path> = files.iter().map(PathBuf::as_path).collect();
    let mut old = Vec::new();
    existing(dest, Path::new(""), &mut old);
    for f in old.iter().filter(|f| !wanted.contains(f.as_path())) {
        let p = dest.join(f);
        std::fs::remove_file(&p).map_err(|e| Error::write(&p, e))?;
    }
    for f in files {
        let from = root.join(f);
        let data = std::fs::read(&from)
            .map_err(|e| failed(format!("{}: cannot read: {e}", from.display())))?;
        let to = dest.join(f);
        if std::fs::read(&to).is_ok_and(|d| d == data) {
            continue;
        }
        if let Some(dir) = to.parent() {
            std::fs::create_dir_all(dir).map_err(|e| Error::write(dir, e))?;
        }
        std::fs::write(&to, &data).map_err(|e| Error::write(&to, e))?;
    }
    Ok(())
}

/// Cargo's home (`CARGO_HOME`, else `~/.cargo`), where registry sources
/// live.
fn cargo_home() -> Option<PathBuf> {
    std::env::var_os("CARGO_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cargo")))
}

/// Builds the firmware for `target` with `features` (the default build
/// without) and runs it under QEMU with the counting plugin. Only the
/// measured binary (`fixshade-firmware`): without `--bin`, cargo also
/// built and LTO-linked the animation (`fixshade-animate`) for every
/// feature set, a link per profile and target that nothing ran.
fn build_run(
    stage: &Stage,
    plugin: &Path,
    (target, cpu, machine, plugarg): (&str, &str, &str, &str),
    features: Option<&str>,
    tag: &str,
) -> Result<Run, Error> {
    let mut cmd = Command::new("cargo");
    cmd.current_dir(stage.src.join("examples/firmware")).args([
        "build",
        "-q",
        "--release",
        "--target",
        target,
        "--bin",
        "fixshade-firmware",
    ]);
    let target_dir = &stage.target_dir;
    if let Some(f) = features {
        cmd.args(["--features", f]);
    }
    cmd.env("CARGO_TARGET_DIR", target_dir);
    // Registry crates' panic locations name their source files under
    // CARGO_HOME: the same text whoever measures.
    if let Some(home) = cargo_home() {
        cmd.env(
            "CARGO_ENCODED_RUSTFLAGS",
            format!("--remap-path-prefix={}=/cargo", home.display()),
        );
    }
    run(&mut cmd, &format!("cargo build {target} {tag}")).map_err(|e| {
        let message = e.to_string();
        if message.contains("will not fit in region") || message.contains("overflowed by") {
            failed(format!(
                "the firmware for {target} ({tag}) does not fit the board's memory (4 MiB of flash, 4 MiB of RAM: the scenes' meshes and storage are too large): {message}"
            ))
        } else {
            e
        }
    })?;
    let elf = target_dir.join(target).join("release/fixshade-firmware");
    let (sizes, symbols) = elf_info(&elf)?;
    let log = target_dir.join(format!("plugin-{target}-{tag}.log"));
    let _ = std::fs::remove_file(&log);
    let out = run(
        Command::new("qemu-system-arm")
            .args(["-cpu", cpu, "-machine", machine, "-nographic"])
            .args(["-semihosting-config", "enable=on,target=native"])
            .arg("-plugin")
            .arg(format!("{}{plugarg}", plugin.display()))
            .args(["-d", "plugin", "-D"])
            .arg(&log)
            .arg("-kernel")
            .arg(&elf),
        &format!("qemu {target} {tag}"),
    )?;
    // What `.ci/firmware` checks for the default build (soft-float, CRCs,
    // its table) without building and running it again: the ELF (the next
    // build overwrites cargo's copy) and the firmware's output, beside the
    // plugin's log.
    let keep = target_dir.join(format!("elf-{target}-{tag}"));
    std::fs::copy(&elf, &keep).map_err(|e| Error::write(&keep, e))?;
    let printed = target_dir.join(format!("fw-{target}-{tag}.txt"));
    std::fs::write(&printed, &out).map_err(|e| Error::write(&printed, e))?;
    let log_text = std::fs::read_to_string(&log)
        .map_err(|e| failed(format!("{}: cannot read: {e}", log.display())))?;
    if log_text.contains("insn_count: warning") || !log_text.contains(" warnings 0") {
        return Err(failed(format!(
            "{target} {tag}: the instruction-counting plugin warned: {}",
            log_text
                .lines()
                .filter(|l| l.contains("warning"))
                .collect::<Vec<_>>()
                .join(" | ")
        )));
    }
    let regions = log_text
        .lines()
        .filter(|l| l.starts_with("region "))
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            (
                w.get(3).and_then(|v| v.parse().ok()).unwrap_or(0),
                w.get(5).and_then(|v| v.parse().ok()),
            )
        })
        .collect();
    Ok(Run {
        out,
        regions,
        sizes,
        symbols,
    })
}

/// Builds, runs and parses one target × profile.
fn measure_one(
    stage: &Stage,
    plugin: &Path,
    t: (&str, &str, &str, &str),
    profile: CoreProfile,
    host: &BTreeMap<String, String>,
    user: Option<&BTreeMap<String, Mode>>,
) -> Result<(Build, Vec<ChipResult>), Error> {
    let target = t.0;
    let features = format!("profile-{}", profile.name());
    let Run {
        out,
        regions,
        sizes: (flash, static_ram, text, rodata),
        symbols,
    } = build_run(
        stage,
        plugin,
        t,
        (profile != CoreProfile::Fast).then_some(features.as_str()),
        profile.name(),
    )?;
    let softfloat: Vec<&String> = symbols.iter().filter(|s| is_softfloat(s)).collect();
    if profile.is_fixed() && target.starts_with("thumbv6m") && !softfloat.is_empty() {
        return Err(failed(format!(
            "{target} {}: a fixed-point profile links soft-float routines: {}",
            profile.name(),
            softfloat
                .iter()
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    let softfloat = softfloat.len() as u64;
    let scenes: Vec<&str> = out.lines().filter(|l| l.starts_with("scene ")).collect();
    if scenes.is_empty() || regions.len() < 2 * scenes.len() {
        return Err(failed(format!(
            "{target} {}: {} scenes but {} counted regions (want two each)",
            profile.name(),
            scenes.len(),
            regions.len()
        )));
    }
    let mut results = Vec::new();
    for (i, line) in scenes.iter().enumerate() {
        let name = line.split_whitespace().nth(1).unwrap_or("").to_string();
        let (w, h) = kv(line, "size")
            .and_then(|s| s.split_once('x'))
            .and_then(|(w, h)| Some((w.parse::<u32>().ok()?, h.parse::<u32>().ok()?)))
            .ok_or_else(|| failed(format!("firmware line without a size: {line}")))?;
        let (g, r) = (regions[2 * i], regions[2 * i + 1]);
        let crc = kv(line, "crc").unwrap_or("").to_string();
        let host_crc = host.get(&name).cloned().unwrap_or_default();
        let band = u64::from(w) * u64::from(BAND_ROWS) * 2;
        let (prepared, stack) = (num(line, "prepared_bytes")?, num(line, "stack")?);
        // Built-in scenes: bands + prepared frame + stack (comparable with
        // the committed figures). A user's scene: what a firmware built for
        // it alone holds, as the firmware reports it: colour band, depth
        // band (none for one convex culled object), the storage sized by
        // the compiler for its meshes, the active-triangle pool, and the
        // stack.
        let (depth, ram, mode) = match user {
            None => (
                band,
                2 * band + prepared + stack,
                name.split('-').find_map(Mode::parse),
            ),
            Some(modes) => {
                let depth = num(line, "depth_bytes")?;
                (
                    depth,
                    band + depth + num(line, "storage_bytes")? + num(line, "pool_bytes")? + stack,
                    modes.get(&name).copied(),
                )
            }
        };
        results.push(ChipResult {
            target: target.to_string(),
            profile: profile.name().to_string(),
            mode,
            scene: name,
            width: w,
            height: h,
            insns: g.0 + r.0,
            insns_geometry: g.0,
            insns_raster: r.0,
            cycles: g.1.zip(r.1).map(|(a, b)| a + b),
            cycles_geometry: g.1,
            cycles_raster: r.1,
            covered: num(line, "covered")?,
            drawn: num(line, "drawn")?,
            setups: num(line, "setups")?,
            prepared_bytes: prepared,
            band_bytes: band,
            depth_bytes: depth,
            stack,
            ram,
            static_ram,
            flash,
            crc_equal: crc == host_crc,
            crc,
            host_crc,
        });
    }
    if profile.is_fixed() {
        if let Some(r) = results.iter().find(|r| !r.crc_equal) {
            return Err(failed(format!(
                "{target} {} {}: CRC {} on the chip but {} on the host (a fixed profile must compute the same bits)",
                r.profile, r.scene, r.crc, r.host_crc
            )));
        }
    }
    let build = Build {
        target: target.to_string(),
        profile: profile.name().to_string(),
        flash_bytes: flash,
        text_bytes: text,
        rodata_bytes: rodata,
        static_ram_bytes: static_ram,
        softfloat_routines: softfloat,
        spans: span_loops(&out, &regions, scenes.len())?,
    };
    Ok((build, results))
}

/// The span loops a build printed (`span NAME rows=R long=L short=1`):
/// the k-th line owns the regions `2·scenes + 2k` (long spans) and `+ 1`
/// (1-pixel spans).
fn span_loops(out: &str, regions: &Regions, scenes: usize) -> Result<Vec<SpanLoop>, Error> {
    out.lines()
        .filter(|l| l.starts_with("span "))
        .enumerate()
        .map(|(k, line)| {
            let g = 2 * scenes + 2 * k;
            let (long, short) = regions.get(g).zip(regions.get(g + 1)).ok_or_else(|| {
                failed(format!(
                    "span line {k} without its two counted regions: {line}"
                ))
            })?;
            Ok(SpanLoop {
                kernel: line.split_whitespace().nth(1).unwrap_or("").to_string(),
                rows: num(line, "rows")?,
                long: num(line, "long")?,
                long_insns: long.0,
                short_insns: short.0,
            })
        })
        .collect()
}

/// The knob variants on one target (the firmware's `knobs` build), with
/// host-check's CRCs (`host`: by `rows/depth/subpixel`).
fn measure_knobs(
    stage: &Stage,
    plugin: &Path,
    t: (&str, &str, &str, &str),
    host: &BTreeMap<String, String>,
) -> Result<Vec<KnobResult>, Error> {
    let target = t.0;
    let r = build_run(stage, plugin, t, Some("knobs"), "knobs")?;
    let lines: Vec<&str> = r.out.lines().filter(|l| l.starts_with("knob ")).collect();
    if lines.is_empty() || r.regions.len() < 2 * lines.len() {
        return Err(failed(format!(
            "{target} knobs: {} variants but {} counted regions (want two each)",
            lines.len(),
            r.regions.len()
        )));
    }
    lines
        .iter()
        .enumerate()
        .map(|(i, line)| {
            let (g, ra) = (r.regions[2 * i], r.regions[2 * i + 1]);
            let key = format!(
                "{}/{}/{}",
                kv(line, "rows").unwrap_or(""),
                kv(line, "depth").unwrap_or(""),
                kv(line, "subpixel").unwrap_or("")
            );
            let crc = kv(line, "crc").unwrap_or("").to_string();
            let host_crc = host.get(&key).cloned().unwrap_or_default();
            if crc != host_crc {
                return Err(failed(format!(
                    "{target} knob {key}: CRC {crc} on the chip but {host_crc} on the host"
                )));
            }
            let (band, depth, prepared, stack) = (
                num(line, "band_bytes")?,
                num(line, "depth_bytes")?,
                num(line, "prepared_bytes")?,
                num(line, "stack")?,
            );
            Ok(KnobResult {
                target: target.to_string(),
                scene: kv(line, "scene").unwrap_or("").to_string(),
                rows: num(line, "rows")? as u32,
                depth_bits: num(line, "depth")? as u32,
                subpixel_bits: num(line, "subpixel")? as u32,
                insns: g.0 + ra.0,
                insns_geometry: g.0,
                insns_raster: ra.0,
                cycles: g.1.zip(ra.1).map(|(a, b)| a + b),
                covered: num(line, "covered")?,
                setups: num(line, "setups")?,
                prepared_bytes: prepared,
                band_bytes: band,
                depth_bytes: depth,
                stack,
                ram: band + depth + prepared + stack,
                crc,
            })
        })
        .collect()
}

/// The firmware features built for some scenes alone and measured on
/// every target (profile `fast`): `bunny`, the bunny Gouraud scene alone,
/// the build its static-RAM budget is about.
pub const ALONE: [&str; 1] = ["bunny"];

/// The firmware built with `feature` (one of [`ALONE`]) on one target:
/// its sizes and its scenes' largest stack; each scene's CRC must equal
/// host-check's (`host`, profile `fast`): the same frame as the default
/// build's. Its ELF and output are kept as `elf-/fw-TARGET-FEATURE` (see
/// [`build_run`]).
fn measure_alone(
    stage: &Stage,
    plugin: &Path,
    t: (&str, &str, &str, &str),
    feature: &str,
    host: &BTreeMap<String, String>,
) -> Result<AloneBuild, Error> {
    let target = t.0;
    let r = build_run(stage, plugin, t, Some(feature), feature)?;
    let (flash, static_ram, _, _) = r.sizes;
    let mut scenes = Vec::new();
    let mut stack = 0;
    for line in r.out.lines().filter(|l| l.starts_with("scene ")) {
        let name = line.split_whitespace().nth(1).unwrap_or("").to_string();
        let crc = kv(line, "crc").unwrap_or("");
        let host_crc = host.get(&name).map_or("", String::as_str);
        if crc != host_crc {
            return Err(failed(format!(
                "{target} {feature} alone {name}: CRC {crc} on the chip but {host_crc} on the host"
            )));
        }
        stack = stack.max(num(line, "stack")?);
        scenes.push(name);
    }
    if scenes.is_empty() {
        return Err(failed(format!(
            "{target} {feature} alone: the firmware rendered no scene"
        )));
    }
    Ok(AloneBuild {
        target: target.to_string(),
        features: feature.to_string(),
        scenes,
        flash_bytes: flash,
        static_ram_bytes: static_ram,
        stack,
    })
}

/// host-check `--knobs`: CRCs by `rows/depth/subpixel`, and the pixels
/// where the 32-bit depth frame differs from the 16-bit one.
fn host_knobs(fw: &Path) -> Result<(BTreeMap<String, String>, u64), Error> {
    let out = run(host_check(fw).args(["--", "--knobs"]), "host-check --knobs")?;
    let crcs = out
        .lines()
        .filter(|l| l.starts_with("knob "))
        .filter_map(|l| {
            Some((
                format!(
                    "{}/{}/{}",
                    kv(l, "rows")?,
                    kv(l, "depth")?,
                    kv(l, "subpixel")?
                ),
                kv(l, "crc")?.to_string(),
            ))
        })
        .collect();
    let differ = out
        .lines()
        .find_map(|l| kv(l, "depth32_vs_depth16_pixels")?.parse().ok())
        .ok_or_else(|| failed("host-check --knobs printed no depth comparison".into()))?;
    Ok((crcs, differ))
}

/// The firmware's release opt-level from its manifest.
fn opt_level(fw: &Path) -> String {
    let text = std::fs::read_to_string(fw.join("Cargo.toml")).unwrap_or_default();
    let mut in_release = false;
    for l in text.lines() {
        let l = l.trim();
        if l.starts_with('[') {
            in_release = l == "[profile.release]";
        } else if in_release {
            if let Some(v) = l.strip_prefix("opt-level") {
                return v
                    .trim_start_matches([' ', '='])
                    .trim_matches('"')
                    .to_string();
            }
        }
    }
    "unknown".into()
}

/// The measuring tools: QEMU's version, the toolchain's, and the built
/// plugin.
struct Tools {
    qemu: String,
    toolchain: String,
    plugin: PathBuf,
}

/// Checks for QEMU and gcc (bad input naming a missing one) and builds the
/// counting plugin.
fn tools(fw: &Path) -> Result<Tools, Error> {
    let qemu = tool_version("qemu-system-arm", "apt-get install qemu-system-arm")?;
    tool_version("gcc", "apt-get install gcc, for the QEMU plugin")?;
    let toolchain = run(Command::new("rustc").arg("-V").current_dir(fw), "rustc -V")?
        .trim()
        .to_string();
    let plugin_dir = fw.join("target/measure");
    std::fs::create_dir_all(&plugin_dir).map_err(|e| Error::write(&plugin_dir, e))?;
    let plugin = plugin_dir.join("insn_count.so");
    run(
        Command::new("gcc")
            .args([
                "-O2", "-Wall", "-Wextra", "-Werror", "-shared", "-fPIC", "-o",
            ])
            .arg(&plugin)
            .arg(fw.join("qemu-plugin/insn_count.c")),
        "gcc (QEMU plugin)",
    )?;
    Ok(Tools {
        qemu,
        toolchain,
        plugin,
    })
}

/// `root`'s firmware folder (`examples/firmware`), or bad input when it
/// has none.
fn firmware_dir(root: &Path) -> Result<PathBuf, Error> {
    let fw = root.join("examples/firmware");
    if fw.join("Cargo.toml").is_file() {
        Ok(fw)
    } else {
        Err(Error::input(format!(
            "{}: no firmware here (examples/firmware) to measure",
            root.display()
        )))
    }
}

/// What a measurement holds from its start to its end: the lock (one
/// measurement at a time, held over the plugin's build, the staged copy,
/// the builds and runs), the tools, the sources' fingerprint and the
/// staged copy.
struct Session {
    /// The firmware folder (`examples/firmware`).
    fw: PathBuf,
    tools: Tools,
    fingerprint: String,
    stage: Stage,
    /// Last: released after everything else.
    _lock: StageLock,
}

impl Session {
    /// Takes the lock, then checks and builds the tools, fingerprints the
    /// sources of `root` and stages them.
    fn begin(root: &Path, fw: PathBuf) -> Result<Self, Error> {
        let lock = StageLock::acquire(Path::new(STAGE_LOCK))?;
        Ok(Self {
            tools: tools(&fw)?,
            fw,
            fingerprint: chips::source_fingerprint(root)?,
            stage: Stage::new(root)?,
            _lock: lock,
        })
    }

    /// The measurements of `builds` and `results` (no knobs), with this
    /// session's tools, fingerprint and build settings; ends the session.
    fn finish(
        self,
        about: String,
        regenerate: String,
        builds: Vec<Build>,
        results: Vec<ChipResult>,
    ) -> Measurements {
        Measurements {
            schema: SCHEMA,
            about,
            regenerate,
            toolchain: self.tools.toolchain,
            qemu: self.tools.qemu,
            source_fingerprint: self.fingerprint,
            opt_level: opt_level(&self.fw),
            band_rows: BAND_ROWS,
            depth_bits: 16,
            builds,
            results,
            knobs: Vec::new(),
            knob_depth32_vs_depth16_pixels: 0,
            alone: Vec::new(),
        }
    }
}

fn progress_bar(show: bool, total: u64) -> ProgressBar {
    let bar = if show && std::io::stderr().is_terminal() {
        ProgressBar::new(total)
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} {elapsed} measuring {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar
}

/// `job` for each target at once, one thread each: each builds in its own
/// target folder (cargo locks a folder per build), and the single-unit
/// LTO links keep one core each busy. The results in target order, or
/// the first error.
fn on_targets<T: Send>(
    targets: &[(&str, &str, &str, &str)],
    job: impl Fn((&str, &str, &str, &str)) -> Result<T, Error> + Sync,
) -> Result<Vec<T>, Error> {
    std::thread::scope(|s| {
        let jobs: Vec<_> = targets
            .iter()
            .map(|&t| {
                let job = &job;
                s.spawn(move || job(t))
            })
            .collect();
        jobs.into_iter()
            .map(|j| {
                j.join()
                    .unwrap_or_else(|_| Err(failed("a measuring thread panicked".into())))
            })
            .collect()
    })
}

/// What [`measure_firmware`]'s measurements are.
const ABOUT: &str = "fixshade firmware (examples/firmware) under QEMU 7.2: instructions counted exactly by the plugin (qemu-plugin/insn_count.c); est. Cortex-M0 cycles from ARM DDI 0432C table 3-1, zero wait states (an ESTIMATE, M0 only); RAM per scene = colour band + 16-bit depth band (16 rows) + prepared frame + stack high-water mark. Generated: do not edit.";

/// Measures every profile of `opts` on both targets (see the module
/// docs).
///
/// # Errors
/// A missing tool ([`Error::Input`]); a lock file that cannot be taken
/// ([`Error::Lock`]); a failed build, run or CRC check
/// ([`Error::Measurement`]).
pub fn measure_firmware(opts: &MeasureOptions) -> Result<Measurements, Error> {
    let root = &opts.root;
    let fw = firmware_dir(root)?;
    let session = Session::begin(root, fw)?;
    let (stage, plugin) = (&session.stage, &session.tools.plugin);
    let total =
        ((opts.profiles.len() + 1) * (TARGETS.len() + 1) + ALONE.len() * TARGETS.len()) as u64;
    let bar = progress_bar(opts.progress, total);
    // The host's CRCs first (one host build, cached), then both targets
    // at once: each builds in its own target folder (cargo locks a folder
    // per build), and the single-unit LTO links keep one core each busy.
    let mut hosts = Vec::new();
    for &profile in &opts.profiles {
        bar.set_message(format!("{} on the host", profile.name()));
        hosts.push((profile, host_crcs(&session.fw, profile, None)?));
        bar.inc(1);
    }
    bar.set_message("knobs on the host");
    let (knob_host, depth_differ) = host_knobs(&session.fw)?;
    bar.inc(1);
    // The frames of the firmwares built for some scenes alone are the
    // default (`fast`) build's.
    let fast_host = match hosts.iter().find(|(p, _)| *p == CoreProfile::Fast) {
        Some((_, h)) => h.clone(),
        None => host_crcs(&session.fw, CoreProfile::Fast, None)?,
    };
    let per_target = on_targets(&TARGETS, |t| {
        let stage = stage.for_target(t.0);
        let (mut builds, mut results) = (Vec::new(), Vec::new());
        for (profile, host) in &hosts {
            bar.set_message(format!("{} on {}", profile.name(), t.0));
            let (b, r) = measure_one(&stage, plugin, t, *profile, host, None)?;
            builds.push(b);
            results.extend(r);
            bar.inc(1);
        }
        bar.set_message(format!("knobs on {}", t.0));
        let knobs = measure_knobs(&stage, plugin, t, &knob_host)?;
        bar.inc(1);
        let mut alone = Vec::new();
        for feature in ALONE {
            bar.set_message(format!("{feature} alone on {}", t.0));
            alone.push(measure_alone(&stage, plugin, t, feature, &fast_host)?);
            bar.inc(1);
        }
        Ok((builds, results, knobs, alone))
    });
    let (mut builds, mut results, mut knobs, mut alone) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (b, r, k, a) in per_target? {
        builds.extend(b);
        results.extend(r);
        knobs.extend(k);
        alone.extend(a);
    }
    bar.finish_and_clear();
    let rank = |p: &str| CoreProfile::ALL.iter().position(|c| c.name() == p);
    builds.sort_by_key(|b: &Build| (rank(&b.profile), b.target.clone()));
    results.sort_by_key(|r: &ChipResult| (rank(&r.profile), r.target.clone()));
    Ok(Measurements {
        knobs,
        knob_depth32_vs_depth16_pixels: depth_differ,
        alone,
        ..session.finish(ABOUT.into(), REGENERATE.into(), builds, results)
    })
}

/// A user's scene files to measure on the chips (`fixshade report
/// SCENE.toml... --measure-firmware`, `fixshade pick --scene SCENE.toml
/// --measure-firmware`, `fixshade measure-firmware --scene SCENE.toml`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UserMeasureOptions {
    /// The repository root (the firmware's sources).
    pub root: PathBuf,
    /// The scene files.
    pub files: Vec<PathBuf>,
    /// The profiles.
    pub profiles: Vec<CoreProfile>,
    /// The targets (of [`TARGETS`]).
    pub targets: Vec<String>,
    /// Draw a progress bar on stderr (only on a terminal).
    pub progress: bool,
}

/// The firmware scenes of the user's scene files: each file in each
/// shading mode (every object given the mode, as the report sweeps them),
/// named `STEM-MODE` (`STEM` the file's name without `.toml`, numbered
/// when two files share it), with the mode of each name.
///
/// # Errors
/// A file that does not load, or a scene the firmware cannot take (bad
/// input, naming the file).
pub fn user_firmware_scenes(
    files: &[PathBuf],
) -> Result<(Vec<FirmwareScene>, BTreeMap<String, Mode>), Error> {
    let mut scenes = Vec::new();
    let mut modes = BTreeMap::new();
    let mut stems: Vec<String> = Vec::new();
    for f in files {
        let desc = SceneDesc::load(f)?;
        let base: String = f
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into())
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        let mut stem = base.clone();
        let mut k = 2;
        while stems.contains(&stem) {
            stem = format!("{base}{k}");
            k += 1;
        }
        stems.push(stem.clone());
        for m in Mode::ALL {
            let mut d = desc.clone();
            for o in &mut d.objects {
                o.shading = m.shading();
            }
            let name = format!("{stem}-{}", m.name());
            let fs = FirmwareScene::new(name.clone(), d).map_err(|e| {
                Error::input(format!(
                    "{}: the firmware cannot render this scene: {e}",
                    f.display()
                ))
            })?;
            modes.insert(name, m);
            scenes.push(fs);
        }
    }
    Ok((scenes, modes))
}

/// Measures the user's scenes ([`user_firmware_scenes`]) on the chips:
/// the firmware's scenes are generated from them (meshes baked as
/// constant tables, storage sized by the core's `const fn`s) into the
/// staged copy, built for each target and profile, run under QEMU with
/// the counting plugin; the fixed profiles' CRCs must equal the host's
/// (`fast`: rendered here from the same Q16 values; the others by
/// `host-check` built from the staged copy). The results' RAM is what a
/// firmware built for the scene alone holds (see [`ChipResult::ram`]:
/// colour band, depth band if the scene needs one, storage, pool, stack,
/// as the firmware prints them).
///
/// # Errors
/// A bad scene file or one the firmware cannot take, a missing tool
/// ([`Error::Input`], [`Error::Scene`]); a lock file that cannot be taken
/// ([`Error::Lock`]); a failed build (e.g. meshes beyond the board's
/// flash), run or CRC check ([`Error::Measurement`]).
pub fn measure_user_scenes(opts: &UserMeasureOptions) -> Result<Measurements, Error> {
    let root = &opts.root;
    let fw = firmware_dir(root)?;
    let targets: Vec<(&str, &str, &str, &str)> = opts
        .targets
        .iter()
        .map(|t| {
            TARGETS.iter().copied().find(|x| x.0 == t).ok_or_else(|| {
                Error::input(format!(
                    "unknown target `{t}` (known: {})",
                    TARGETS.map(|x| x.0).join(", ")
                ))
            })
        })
        .collect::<Result<_, _>>()?;
    let (scenes, modes) = user_firmware_scenes(&opts.files)?;
    let source = generate_for(&scenes).map_err(|e| Error::input(e.to_string()))?;
    let fast_crcs: BTreeMap<String, String> = scenes
        .iter()
        .map(|s| {
            let f = s
                .render_crc()
                .map_err(|e| Error::input(format!("{}: {e}", s.name)))?;
            Ok((s.name.clone(), format!("0x{:08x}", f.crc)))
        })
        .collect::<Result<_, Error>>()?;
    let session = Session::begin(root, fw)?;
    let (stage, plugin) = (&session.stage, &session.tools.plugin);
    let generated = stage.src.join(crate::firmware_scenes::GENERATED_PATH);
    std::fs::write(&generated, source).map_err(|e| Error::write(&generated, e))?;
    let others = opts
        .profiles
        .iter()
        .filter(|p| **p != CoreProfile::Fast)
        .count();
    let total = (others + opts.profiles.len() * targets.len()) as u64;
    let bar = progress_bar(opts.progress, total);
    let mut hosts = Vec::new();
    for &profile in &opts.profiles {
        let crcs = if profile == CoreProfile::Fast {
            fast_crcs.clone()
        } else {
            bar.set_message(format!("{} on the host", profile.name()));
            let c = host_crcs(
                &stage.src.join("examples/firmware"),
                profile,
                Some(&stage.target_dir),
            )?;
            bar.inc(1);
            c
        };
        hosts.push((profile, crcs));
    }
    let per_target = on_targets(&targets, |t| {
        let stage = stage.for_target(t.0);
        let (mut builds, mut results) = (Vec::new(), Vec::new());
        for (profile, host) in &hosts {
            bar.set_message(format!("your scenes, {} on {}", profile.name(), t.0));
            let (b, r) = measure_one(&stage, plugin, t, *profile, host, Some(&modes))?;
            builds.push(b);
            results.extend(r);
            bar.inc(1);
        }
        Ok((builds, results))
    });
    let (mut builds, mut results) = (Vec::new(), Vec::new());
    for (b, r) in per_target? {
        builds.extend(b);
        results.extend(r);
    }
    bar.finish_and_clear();
    let about = format!(
        "fixshade firmware under QEMU, generated for your scenes ({}): instructions counted exactly by the plugin; est. Cortex-M0 cycles from ARM DDI 0432C table 3-1, zero wait states (an ESTIMATE, M0 only); RAM per scene = what a firmware built for it alone holds: colour band + depth band (none for one convex object with back faces culled) + storage sized by the compiler for its meshes + active-triangle pool + stack high-water mark.",
        opts.files
            .iter()
            .map(|f| f.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(session.finish(
        about,
        "fixshade measure-firmware --scene SCENE.toml --write FILE".into(),
        builds,
        results,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_staged_copy_keeps_unchanged_files_and_their_times() {
        let base = std::env::temp_dir().join(format!("fixshade-sync-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&base);
        let (root, dest) = (base.join("root"), base.join("stage"));
        std::fs::create_dir_all(root.join("src/sub")).unwrap();
        std::fs::write(root.join("src/a.rs"), "a").unwrap();
        std::fs::write(root.join("src/sub/b.rs"), "b").unwrap();
        let files = [PathBuf::from("src/a.rs"), PathBuf::from("src/sub/b.rs")];
        sync_copy(&root, &files, &dest).unwrap();
        std::fs::write(dest.join("src/stale.rs"), "gone").unwrap();
        let time = |p: &str| std::fs::metadata(dest.join(p)).unwrap().modified().unwrap();
        let (a0, b0) = (time("src/a.rs"), time("src/sub/b.rs"));
        std::thread::sleep(std::time::Duration::from_millis(20));
        // b changes (as the generated scenes file does for a user's scene);
        // a does not.
        std::fs::write(root.join("src/sub/b.rs"), "b2").unwrap();
        sync_copy(&root, &files, &dest).unwrap();
        assert_eq!(time("src/a.rs"), a0, "an unchanged file keeps its time");
        assert!(time("src/sub/b.rs") > b0, "a changed file is written anew");
        assert_eq!(
            std::fs::read_to_string(dest.join("src/sub/b.rs")).unwrap(),
            "b2"
        );
        assert!(!dest.join("src/stale.rs").exists(), "files not staged go");
        // The staged file changed behind our back (same length, another
        // content): rewritten.
        std::fs::write(dest.join("src/a.rs"), "x").unwrap();
        sync_copy(&root, &files, &dest).unwrap();
        assert_eq!(std::fs::read_to_string(dest.join("src/a.rs")).unwrap(), "a");
        let _ = std::fs::remove_dir_all(&base);
    }

    #[test]
    fn soft_float_names_are_found() {
        for n in [
            "__aeabi_fmul",
            "__aeabi_dadd",
            "__addsf3",
            "__floatsisf",
            "__fixdfsi",
            "__powisf2",
        ] {
            assert!(is_softfloat(n), "{n}");
        }
        for n in [
            "__aeabi_lmul",
            "__aeabi_uidiv",
            "memset",
            "__udivsi3",
            "main",
        ] {
            assert!(!is_softfloat(n), "{n}");
        }
    }

    #[test]
    fn firmware_lines_are_read() {
        let l = "scene bunny-flat size=240x240 crc=0x48276f27 covered=14910 stack=11724";
        assert_eq!(kv(l, "crc"), Some("0x48276f27"));
        assert_eq!(num(l, "covered").unwrap(), 14910);
        assert!(num(l, "drawn").is_err());
        assert_eq!(kv(l, "size"), Some("240x240"));
    }

    #[test]
    fn span_lines_take_the_regions_after_the_scenes() {
        let out = "scene a size=8x8\nspan flat rows=16 long=200 short=1\nspan gouraud rows=16 long=200 short=1\n";
        // Two regions for the scene, then (long, short) per span line.
        let regions = vec![
            (10, None),
            (20, None),
            (16 * 199 * 9 + 500, None),
            (500, None),
            (16 * 199 * 12 + 700, None),
            (700, None),
        ];
        let spans = span_loops(out, &regions, 1).unwrap();
        assert_eq!(spans.len(), 2);
        assert_eq!(spans[0].kernel, "flat");
        assert_eq!(spans[0].insns_per_px(), 9.0);
        assert_eq!(spans[1].kernel, "gouraud");
        assert_eq!(spans[1].insns_per_px(), 12.0);
        // A span line without its regions is an error, not a zero.
        assert!(span_loops(out, &regions[..5].to_vec(), 1).is_err());
    }
}
