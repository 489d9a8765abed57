//! Embedded figures: a reader for the firmware's machine-readable results.
//!
//! `fixshade report --firmware-results FILE` takes the results of the
//! firmware example (`examples/firmware`, run under QEMU with the
//! instruction-counting plugin) in either of two forms:
//!
//! * lines `RESULT key=value key=value ...` (other lines are ignored, so a
//!   whole QEMU log can be given):
//!
//!   ```text
//!   RESULT target=m0 scene=grid-gouraud profile=fast insns=9071024 cycles=14572144 covered=14400 stack=864 static_ram=15368
//!   ```
//!
//! * JSON: an array of objects with the same keys, or an object whose
//!   `results` member is such an array; values may be numbers or strings.
//!
//! Keys: `target` (`m0`, `cortex-m0`, `thumbv6m-none-eabi`, or `m4`, `m4f`,
//! `cortex-m4`, `thumbv7em-none-eabihf`) and `scene` are required, and at
//! least one of `insns` (instructions per frame) and `cycles` (estimated
//! cycles per frame; `est_m0_cycles` is accepted too). Optional: `profile`
//! (a core profile name), `mode` (`flat`, `gouraud`, `phong`; otherwise
//! taken from a `-flat`/`-gouraud`/`-phong` part of the scene name),
//! `covered`, `stack`, `static_ram`, `flash` (bytes), `crc`. Unknown keys
//! are ignored. Numbers are decimal or `0x` hexadecimal.
//!
//! Nothing is estimated here: the report shows what the file says, and
//! says so when there is no file.

use std::collections::BTreeMap;
use std::fmt;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::Error;
use crate::core_render::CoreProfile;

use super::Mode;

/// An embedded target of the firmware.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Target {
    /// Cortex-M0/M0+ (ARMv6-M, no FPU, no divider).
    M0,
    /// Cortex-M4F (ARMv7E-M with a single-precision FPU).
    M4f,
}

impl Target {
    /// Both targets.
    pub const ALL: [Self; 2] = [Self::M0, Self::M4f];

    /// Its short name.
    pub fn name(self) -> &'static str {
        match self {
            Self::M0 => "m0",
            Self::M4f => "m4f",
        }
    }

    /// Its name for people.
    pub fn title(self) -> &'static str {
        match self {
            Self::M0 => "Cortex-M0",
            Self::M4f => "Cortex-M4F",
        }
    }

    fn parse(s: &str) -> Option<Self> {
        match s.to_ascii_lowercase().as_str() {
            "m0" | "m0+" | "cortex-m0" | "cortex-m0+" | "thumbv6m" | "thumbv6m-none-eabi" => {
                Some(Self::M0)
            }
            "m4" | "m4f" | "cortex-m4" | "cortex-m4f" | "thumbv7em" | "thumbv7em-none-eabihf" => {
                Some(Self::M4f)
            }
            _ => None,
        }
    }
}

impl fmt::Display for Target {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.title())
    }
}

/// One scene measured on one target.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EmbeddedResult {
    /// The target.
    pub target: Target,
    /// The firmware's scene name.
    pub scene: String,
    /// The profile, when the file names it.
    pub profile: Option<String>,
    /// The shading mode, given or taken from the scene name.
    pub mode: Option<Mode>,
    /// Instructions per frame.
    pub insns: Option<u64>,
    /// Estimated cycles per frame.
    pub cycles: Option<u64>,
    /// Covered pixels.
    pub covered: Option<u64>,
    /// Stack high-water mark, bytes.
    pub stack: Option<u64>,
    /// Static RAM, bytes.
    pub static_ram: Option<u64>,
    /// Flash image size, bytes.
    pub flash: Option<u64>,
    /// The frame's CRC-32 as printed.
    pub crc: Option<String>,
}

impl EmbeddedResult {
    /// The cost figure: estimated cycles when present, else instructions.
    pub fn cost(&self) -> Option<(u64, &'static str)> {
        self.cycles
            .map(|c| (c, "est. cycles"))
            .or(self.insns.map(|i| (i, "instructions")))
    }

    /// The profile, parsed.
    pub fn core_profile(&self) -> Option<CoreProfile> {
        self.profile.as_deref().and_then(CoreProfile::parse)
    }
}

/// Reads a results file (see the module docs). Errors are bad input.
pub fn read_firmware_results(path: &Path) -> Result<Vec<EmbeddedResult>, Error> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path)
        .map_err(|e| Error::input(format!("{file}: cannot read firmware results: {e}")))?;
    parse_firmware_results(&text, &file)
}

/// Parses results text (JSON or `RESULT` lines); `file` names it in
/// errors.
pub fn parse_firmware_results(text: &str, file: &str) -> Result<Vec<EmbeddedResult>, Error> {
    let trimmed = text.trim_start();
    let entries: Vec<Entry> = if trimmed.starts_with('[') || trimmed.starts_with('{') {
        json_entries(text, file)?
    } else {
        text.lines()
            .enumerate()
            .filter_map(|(i, line)| {
                let rest = line.trim().strip_prefix("RESULT ")?;
                Some((i, rest))
            })
            .map(|(i, rest)| {
                let mut map = BTreeMap::new();
                for pair in rest.split_whitespace() {
                    let (k, v) = pair.split_once('=').ok_or_else(|| {
                        Error::input(format!("{file}: line {}: `{pair}` is not key=value", i + 1))
                    })?;
                    map.insert(k.to_ascii_lowercase(), v.to_string());
                }
                Ok((format!("line {}", i + 1), map))
            })
            .collect::<Result<_, Error>>()?
    };
    if entries.is_empty() {
        return Err(Error::input(format!(
            "{file}: no firmware results (expected `RESULT key=value ...` lines or JSON)"
        )));
    }
    entries
        .into_iter()
        .map(|(at, map)| to_result(&map).map_err(|e| Error::input(format!("{file}: {at}: {e}"))))
        .collect()
}

/// Where an entry was (`line 3`, `results[0]`) and its keys and values.
type Entry = (String, BTreeMap<String, String>);

fn json_entries(text: &str, file: &str) -> Result<Vec<Entry>, Error> {
    let bad = |m: String| Error::input(format!("{file}: {m}"));
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| bad(format!("not JSON: {e}")))?;
    // `examples/firmware/target/results.json` (written by `.ci/firmware`)
    // holds its records under `scenes`, all rendered with the fast profile.
    let firmware = matches!(&value, serde_json::Value::Object(o) if o.contains_key("scenes"));
    let list = match &value {
        serde_json::Value::Array(a) => a,
        serde_json::Value::Object(o) => match o.get("results").or_else(|| o.get("scenes")) {
            Some(serde_json::Value::Array(a)) => a,
            _ => {
                return Err(bad(
                    "expected an array or an object with a `results` array".into()
                ))
            }
        },
        _ => {
            return Err(bad(
                "expected an array or an object with a `results` array".into()
            ))
        }
    };
    list.iter()
        .enumerate()
        .map(|(i, v)| {
            let at = format!("results[{i}]");
            let obj = v
                .as_object()
                .ok_or_else(|| bad(format!("{at}: not an object")))?;
            let mut map: BTreeMap<String, String> = obj
                .iter()
                .filter_map(|(k, v)| {
                    let s = match v {
                        serde_json::Value::String(s) => s.clone(),
                        serde_json::Value::Number(n) => n.to_string(),
                        serde_json::Value::Bool(b) => b.to_string(),
                        _ => return None,
                    };
                    Some((k.to_ascii_lowercase(), s))
                })
                .collect();
            if firmware {
                // The firmware's key names.
                for (from, to) in [
                    ("insns_frame", "insns"),
                    ("est_m0_cycles_frame", "cycles"),
                    ("covered_px", "covered"),
                    ("stack_bytes", "stack"),
                    ("static_ram_bytes", "static_ram"),
                ] {
                    if let Some(v) = map.remove(from) {
                        map.entry(to.to_string()).or_insert(v);
                    }
                }
                map.entry("profile".to_string())
                    .or_insert_with(|| "fast".to_string());
            }
            Ok((at, map))
        })
        .collect()
}

fn number(map: &BTreeMap<String, String>, key: &str) -> Result<Option<u64>, String> {
    let Some(v) = map.get(key) else {
        return Ok(None);
    };
    let parsed = match v.strip_prefix("0x").or_else(|| v.strip_prefix("0X")) {
        Some(hex) => u64::from_str_radix(hex, 16).ok(),
        None => v.parse::<u64>().ok(),
    };
    parsed
        .map(Some)
        .ok_or_else(|| format!("{key}: `{v}` is not a whole number"))
}

fn to_result(map: &BTreeMap<String, String>) -> Result<EmbeddedResult, String> {
    let target = map.get("target").ok_or("missing `target`")?;
    let target = Target::parse(target)
        .ok_or_else(|| format!("target: unknown target `{target}` (m0 or m4f)"))?;
    let scene = map.get("scene").ok_or("missing `scene`")?.clone();
    let profile = match map.get("profile") {
        Some(p) if CoreProfile::parse(p).is_none() => {
            return Err(format!("profile: unknown profile `{p}`"))
        }
        p => p.cloned(),
    };
    let mode = match map.get("mode") {
        Some(m) => Some(Mode::parse(m).ok_or_else(|| format!("mode: unknown mode `{m}`"))?),
        None => scene.split('-').find_map(Mode::parse),
    };
    let insns = number(map, "insns")?;
    let cycles = match number(map, "cycles")? {
        Some(c) => Some(c),
        None => number(map, "est_m0_cycles")?,
    };
    if insns.is_none() && cycles.is_none() {
        return Err("needs `insns` or `cycles`".into());
    }
    Ok(EmbeddedResult {
        target,
        scene,
        profile,
        mode,
        insns,
        cycles,
        covered: number(map, "covered")?,
        stack: number(map, "stack")?,
        static_ram: number(map, "static_ram")?,
        flash: number(map, "flash")?,
        crc: map.get("crc").cloned(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_result_lines_among_other_output() {
        let text = "booting\nscene grid-gouraud crc=0x44f69d18\n\
            RESULT target=thumbv6m-none-eabi scene=grid-gouraud profile=fast insns=9071024 cycles=14572144 covered=14400 stack=864\n\
            RESULT target=m4f scene=fan-flat insns=0x10 crc=0x1234\n";
        let r = parse_firmware_results(text, "f").unwrap();
        assert_eq!(r.len(), 2);
        assert_eq!(r[0].target, Target::M0);
        assert_eq!(r[0].mode, Some(Mode::Gouraud));
        assert_eq!(r[0].core_profile(), Some(CoreProfile::Fast));
        assert_eq!(r[0].cost(), Some((14_572_144, "est. cycles")));
        assert_eq!(r[0].stack, Some(864));
        assert_eq!(r[1].target, Target::M4f);
        assert_eq!(r[1].mode, Some(Mode::Flat));
        assert_eq!(r[1].cost(), Some((16, "instructions")));
        assert_eq!(r[1].profile, None);
    }

    #[test]
    fn reads_json_in_both_shapes() {
        let a =
            r#"[{"target":"m0","scene":"bunny","profile":"fast-pc","mode":"phong","insns":100}]"#;
        let b = r#"{"results":[{"target":"m0","scene":"bunny","profile":"fast-pc","mode":"phong","insns":"100"}]}"#;
        let (ra, rb) = (
            parse_firmware_results(a, "a").unwrap(),
            parse_firmware_results(b, "b").unwrap(),
        );
        assert_eq!(ra, rb);
        assert_eq!(ra[0].mode, Some(Mode::Phong));
        assert_eq!(ra[0].insns, Some(100));
    }

    #[test]
    fn rejects_bad_results_naming_the_place() {
        let cases = [
            ("nothing here\n", "no firmware results"),
            (
                "RESULT target=m7 scene=x insns=1\n",
                "line 1: target: unknown target `m7`",
            ),
            (
                "RESULT target=m0 scene=x\n",
                "line 1: needs `insns` or `cycles`",
            ),
            (
                "RESULT target=m0 scene=x insns=12k\n",
                "insns: `12k` is not a whole number",
            ),
            (
                "RESULT target=m0 scene=x insns=1 profile=slow\n",
                "unknown profile `slow`",
            ),
            ("RESULT target=m0 insns=1\n", "missing `scene`"),
            ("[{\"target\":\"m0\"}]", "results[0]: missing `scene`"),
            ("{\"x\":1}", "`results` array"),
        ];
        for (text, want) in cases {
            let e = parse_firmware_results(text, "fw.txt").unwrap_err();
            assert!(e.to_string().contains(want), "{text}: {}", e);
            assert!(e.to_string().starts_with("fw.txt: "), "{}", e);
            assert!(e.is_input(), "{e:?}");
        }
    }

    #[test]
    fn reads_the_firmware_results_file() {
        let text = r#"{"commit": "x", "targets": [],
            "scenes": [
              {"scene": "bunny-gouraud", "target": "thumbv6m-none-eabi", "insns_frame": 18650000,
               "est_m0_cycles_frame": 29550000, "covered_px": 14907, "stack_bytes": 7100, "crc": "0x1234"},
              {"scene": "bunny-gouraud", "target": "thumbv7em-none-eabihf", "insns_frame": 8540000,
               "est_m0_cycles_frame": null, "covered_px": 14907}
            ], "crcs_agree": true}"#;
        let r = parse_firmware_results(text, "results.json").unwrap();
        assert_eq!(r.len(), 2);
        assert_eq!(r[0].target, Target::M0);
        assert_eq!(r[0].insns, Some(18_650_000));
        assert_eq!(r[0].cycles, Some(29_550_000));
        assert_eq!(r[0].profile.as_deref(), Some("fast"));
        assert_eq!(r[1].target, Target::M4f);
        assert_eq!(r[1].cycles, None);
    }
}
