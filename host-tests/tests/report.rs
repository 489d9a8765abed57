//! `fixshade report --quick`, run as a real process in a temporary folder:
//! the three files, a record with finite figures for every scene × mode ×
//! profile of the quick sweep, the summary and the plots on the page, and
//! the errors for an unwritable folder and a bad firmware results file
//! (before any work, leaving existing files untouched). The embedded
//! figures' effect on the picks is checked on the same records through the
//! library.

use crate::support::{TempDir, EXE};
use std::collections::BTreeSet;
use std::path::Path;
use std::process::{Command, Output};

use fixshade_host::core_render::CoreProfile;
use fixshade_host::report::{
    parse_firmware_results, CostSource, Mode, ReportData, Summary, Target, QUICK_SCENES,
};

fn run(args: &[&str]) -> Output {
    Command::new(EXE).args(args).output().expect("run fixshade")
}

/// `fixshade report EXTRA... --quick --allow-stale --out OUT`, and its
/// standard error.
fn quick_report(out: &Path, extra: &[&str]) -> (Output, String) {
    let mut args = vec!["report"];
    args.extend_from_slice(extra);
    args.extend(["--quick", "--allow-stale", "--out", out.to_str().unwrap()]);
    let o = run(&args);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    (o, stderr)
}

/// `fixshade pick --chip m0 --fps FPS EXTRA... --allow-stale`: its exit
/// code and standard output.
fn pick_m0(fps: &str, extra: &[&str]) -> (Option<i32>, String) {
    let mut args = vec!["pick", "--chip", "m0", "--fps", fps];
    args.extend_from_slice(extra);
    args.push("--allow-stale");
    let o = run(&args);
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
    )
}

fn text(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn quick_report_has_every_record_the_summary_and_the_plots() {
    let tmp = TempDir::new("report-quick");
    let out = tmp.0.join("out");
    let (o, stderr) = quick_report(&out, &[]);
    assert!(o.status.success(), "{stderr}");
    // No progress bar when stderr is not a terminal.
    assert!(stderr.is_empty(), "{stderr}");

    // results.json: one record per scene × mode × profile, finite figures.
    let data: ReportData = serde_json::from_str(&text(&out.join("results.json"))).unwrap();
    assert!(data.meta.quick);
    assert_eq!(data.meta.debug_build, cfg!(debug_assertions));
    let scenes: Vec<&str> = data.meta.scenes.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(scenes, QUICK_SCENES);
    let keys: BTreeSet<(String, Mode, String)> = data
        .records
        .iter()
        .map(|r| (r.scene.clone(), r.mode, r.profile.clone()))
        .collect();
    assert_eq!(data.records.len(), keys.len(), "duplicate records");
    for scene in QUICK_SCENES {
        for mode in Mode::ALL {
            for p in CoreProfile::ALL {
                let key = (scene.to_string(), mode, p.name().to_string());
                assert!(keys.contains(&key), "missing {key:?}");
            }
        }
    }
    assert_eq!(data.records.len(), 3 * 3 * 8);
    for r in &data.records {
        let at = format!("{} {} {}", r.scene, r.mode.name(), r.profile);
        for m in [&r.vs_ideal, &r.vs_twin, &r.vs_ideal_phong] {
            assert!(
                m.mean_abs_error.is_finite() && m.mean_abs_error >= 0.0,
                "{at}"
            );
            assert!((0.0..=1.0).contains(&m.share_over_1), "{at}");
        }
        assert!(
            r.host.median_ms.is_finite() && r.host.median_ms > 0.0,
            "{at}"
        );
        assert!(r.host.min_ms <= r.host.median_ms && r.host.median_ms <= r.host.max_ms);
        assert!(
            r.host.pixels_per_s.is_finite() && r.host.pixels_per_s > 0.0,
            "{at}"
        );
        assert_eq!(r.host.runs, 3, "{at}");
        // Half-size frames of RGB565 scenes: 16-row bands.
        assert_eq!(r.memory.band_bytes, r.width as usize * 16 * 2, "{at}");
        assert_eq!(r.memory.depth_band_bytes, r.width as usize * 16 * 2, "{at}");
        assert_eq!(
            r.memory.ram_bytes,
            r.memory.prepared_bytes + r.memory.band_bytes + r.memory.depth_band_bytes
        );
        assert!(
            r.memory.prepared_bytes > 0 && r.memory.mesh_flash_bytes > 0,
            "{at}"
        );
        assert_eq!(r.memory.triangles_bytes, r.triangles * 6, "{at}");
        // The twin against itself; the budgets of tests/budgets.rs.
        if r.profile == r.twin {
            assert_eq!(r.vs_twin.max_abs_error, 0, "{at}");
            assert_eq!(r.vs_twin.coverage_mismatch, 0, "{at}");
            assert!(r.vs_twin.psnr_db.is_infinite(), "{at}");
        }
        if r.profile.starts_with("precise") {
            assert!(r.vs_twin.max_abs_error <= 2, "{at}");
            assert_eq!(r.vs_twin.coverage_mismatch, 0, "{at}");
        }
        assert!(r.vs_ideal.mean_abs_error < 1.0, "{at}");
        assert!(
            r.places_vs_twin.at_silhouette + r.places_vs_twin.at_edge <= r.places_vs_twin.pixels
        );
    }
    // Flat shading is one colour per triangle: Phong is further from the
    // ideal Phong frame; perspective correction brings Phong closer to the
    // ideal on the bent grid.
    let get = |scene: &str, mode: Mode, p: &str| {
        data.records
            .iter()
            .find(|r| r.scene == scene && r.mode == mode && r.profile == p)
            .unwrap()
    };
    assert!(
        get("bunny", Mode::Flat, "fast")
            .vs_ideal_phong
            .mean_abs_error
            > 2.0
                * get("bunny", Mode::Phong, "fast")
                    .vs_ideal_phong
                    .mean_abs_error
    );
    assert!(
        get("grid-hotspot", Mode::Phong, "fast-pc")
            .vs_ideal
            .mean_abs_error
            < get("grid-hotspot", Mode::Phong, "fast")
                .vs_ideal
                .mean_abs_error
    );
    // The committed chip measurements: every profile on both chips.
    assert!(data.embedded_available);
    assert_eq!(data.embedded.len(), 2 * 8 * 6);
    let chips = data.chips.as_ref().unwrap();
    assert_eq!(chips.picks.rows.len(), 4);
    assert_eq!(chips.fps.rows.len(), 6 * 8);
    assert_eq!(chips.builds.rows.len(), 16);
    // The Cortex-M0 at 48 MHz and 32 KiB picks a fixed profile that fits.
    let m0 = &chips.picks.rows[0];
    assert!(m0[0].starts_with("Cortex-M0/M0+ at 48 MHz"), "{m0:?}");
    assert!(m0[2].starts_with("fast"), "{m0:?}");
    // Every fixed profile's frame is the host's, bit for bit.
    for n in &chips.crc_notes {
        if n.contains("(required)") {
            assert!(n.contains(": 6 of 6 frames"), "{n}");
        }
    }

    // The knob sweeps: band rows trade RAM for cycles (the same frame),
    // 32-bit depth costs RAM, subpixel bits move coverage.
    let knobs = data.knobs.as_ref().unwrap();
    assert_eq!(knobs.scene, "bunny-gouraud");
    assert_eq!(knobs.rows.rows.len(), 6);
    let setups: Vec<u64> = knobs
        .rows
        .rows
        .iter()
        .map(|r| r[2].parse().unwrap())
        .collect();
    // With the active triangle list each prepared triangle is set up once
    // (1 498 on the bunny); only bands so short that more triangles are
    // active at a border than the pool holds set a few up again.
    assert!(setups.windows(2).all(|w| w[0] >= w[1]), "{setups:?}");
    assert_eq!(setups[2..], [1498; 4], "{setups:?}");
    let ram: Vec<u64> = knobs
        .rows
        .rows
        .iter()
        .map(|r| r[1].parse().unwrap())
        .collect();
    assert_eq!(ram[0], 240 * 4 * 2 * 2);
    assert!(ram.windows(2).all(|w| w[0] < w[1]), "{ram:?}");
    assert_eq!(knobs.depth.rows.len(), 2);
    assert_eq!(knobs.depth.rows[1][1], (240 * 16 * 4).to_string());
    assert_eq!(knobs.subpixel.rows.len(), 5);
    assert_eq!(knobs.perspective.rows.len(), 5);

    // index.html: the chip section first, the summary, the plots, the
    // frames.
    let html = text(&out.join("index.html"));
    assert!(html.to_ascii_lowercase().starts_with("<!doctype html>"));
    assert!(html.trim_end().ends_with("</html>"));
    assert!(html.contains("<h2 id=\"summary\">Summary</h2>"));
    let chips_at = html.find("<h2 id=\"chips\">").unwrap();
    assert!(chips_at < html.find("<h2 id=\"summary\">").unwrap());
    assert!(!html.contains("host time as a proxy"));
    for line in &data.summary {
        assert!(
            html.contains(
                &line
                    .replace('&', "&amp;")
                    .replace('<', "&lt;")
                    .replace('>', "&gt;")
                    .replace('"', "&quot;")
            ),
            "{line}"
        );
    }
    assert!(data.summary[0].starts_with("host (every profile): pick "));
    assert!(data.summary[1].starts_with("Cortex-M0 (no FPU"));
    assert!(data.summary[2].starts_with("Cortex-M4F"));
    // M0: a fixed profile; M4F: fixed or f32.
    let picked = |line: &str| {
        let rest = line.split(": pick ").nth(1).unwrap();
        rest.split(' ').next().unwrap().to_string()
    };
    let m0 = CoreProfile::parse(&picked(&data.summary[1])).unwrap();
    assert!(m0.is_fixed(), "{m0:?}");
    let m4 = CoreProfile::parse(&picked(&data.summary[2])).unwrap();
    assert!(m4.is_fixed() || matches!(m4, CoreProfile::F32 | CoreProfile::F32Pc));
    assert!(data
        .summary
        .iter()
        .any(|l| l.starts_with("Largest departures")));
    assert!(data.summary.iter().any(|l| l.starts_with("Which pixels")));
    assert_eq!(
        html.matches("<svg").count(),
        3 + 2 * 3 + 2 * 2 + 2 + 4 + 1,
        "three plots for the host and per chip (errors vs ideal, twin, ideal Phong against mean cost), the chip section's error vs cycles and vs RAM per chip, M0 fixed point and soft-float side by side, one per knob, the Phong kernel's table sizes"
    );
    assert!(html.contains("Phong kernel: table sizes against error"));
    assert!(html.contains("Pareto front"));
    assert!(!html.contains("Embedded figures are not available"));
    assert_eq!(html.contains("in a debug build"), cfg!(debug_assertions));
    assert!(
        !html.contains("http://")
            || html.matches("http://").count()
                == html.matches("xmlns=\"http://www.w3.org/2000/svg\"").count(),
        "no links out but the SVG namespace"
    );
    let images: Vec<&str> = html
        .split("src=\"")
        .skip(1)
        .map(|s| s.split('"').next().unwrap())
        .collect();
    assert_eq!(images.len(), 3 * 3 * 5);
    for img in images {
        assert!(img.starts_with("img/") && out.join(img).is_file(), "{img}");
    }

    // report.md: the same summary and tables.
    let md = text(&out.join("report.md"));
    assert!(md.contains("## Summary"));
    assert!(md.contains(&data.summary[1]));
    assert!(md.contains("| Phong | fast-pc |"));
    assert!(md.contains("| 64 (shipped) |") && md.contains("| 128 (shipped) |"));
    let tables = data.tables.as_ref().expect("the table-size sweep");
    assert_eq!(tables.rsqrt.len(), 7);
    assert_eq!(tables.spec.len(), 7);
    // No temporary files left.
    let leftovers: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");

    // Embedded figures change the M0 pick's cost (library, same records):
    // cycles make precise / Gouraud the cheapest and the only measured.
    let embedded = parse_firmware_results(
        "RESULT target=m0 scene=bunny-gouraud profile=precise mode=gouraud insns=900 cycles=1000\n",
        "fw",
    )
    .unwrap();
    let s = Summary::new(&data.records, &embedded);
    let m0 = &s.picks[1];
    assert_eq!(m0.target, Some(Target::M0));
    assert_eq!(m0.source, CostSource::Embedded("est. cycles", 1));
    assert_eq!(m0.points.len(), 1);
    let p = &m0.points[m0.chosen.unwrap()];
    assert_eq!(
        (p.profile, p.mode, p.cost),
        (CoreProfile::Precise, Mode::Gouraud, 1000.0)
    );
    // No figures for the M4F: no candidates (host time never stands in).
    assert!(s.picks[2].points.is_empty());
    assert!(s.picks[2].sentence().ends_with("no candidates measured."));
    assert_eq!(s.embedded_points.len(), 1);
}

#[test]
fn unwritable_folder_and_bad_firmware_results_fail_before_any_work() {
    let tmp = TempDir::new("report-bad");
    let file = tmp.0.join("a-file");
    std::fs::write(&file, "x").unwrap();
    let under_file = file.join("out");
    let start = std::time::Instant::now();
    let (o, stderr) = quick_report(&under_file, &[]);
    assert_eq!(o.status.code(), Some(1), "{stderr}");
    assert!(stderr.starts_with("error: "), "{stderr}");
    assert!(stderr.contains("a-file"), "{stderr}");
    assert!(stderr.contains("cannot write"), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    // Before the sweep (a quick sweep takes seconds even in release).
    assert!(start.elapsed().as_secs_f64() < 2.0, "{:?}", start.elapsed());
    assert_eq!(text(&file), "x");

    // A bad firmware results file: bad input, checked first; an existing
    // page is left untouched.
    let out = tmp.0.join("out");
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("index.html"), "old").unwrap();
    let fw = tmp.0.join("fw.txt");
    std::fs::write(&fw, "RESULT target=m7 scene=x insns=1\n").unwrap();
    let (o, stderr) = quick_report(&out, &["--firmware-results", fw.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("fw.txt: line 1: target: unknown target `m7`"),
        "{stderr}"
    );
    assert_eq!(text(&out.join("index.html")), "old");
    assert!(!out.join("results.json").exists());
}

#[test]
fn missing_malformed_and_stale_measurements_are_refused_before_any_output() {
    let tmp = TempDir::new("report-measurements");
    let out = tmp.0.join("out");
    let committed =
        text(&fixshade_host::report::chips::repo_root().join("docs/measurements/firmware.json"));
    let stale = tmp.0.join("stale.json");
    std::fs::write(
        &stale,
        committed.replacen(
            "\"source_fingerprint\": \"fnv1a64:",
            "\"source_fingerprint\": \"fnv1a64:0",
            1,
        ),
    )
    .unwrap();
    let malformed = tmp.0.join("malformed.json");
    std::fs::write(
        &malformed,
        committed.replacen("\"insns\": ", "\"insns\": -", 1),
    )
    .unwrap();
    let cases = [
        (
            tmp.0.join("missing.json"),
            "cannot read the firmware measurements",
        ),
        (
            malformed,
            "malformed firmware measurements at `results[0].insns`",
        ),
        (stale, "stale firmware measurements"),
    ];
    for (file, want) in cases {
        for args in [
            vec!["report", "--quick", "--out", out.to_str().unwrap()],
            vec!["pick", "--chip", "cortex-m0", "--fps", "10"],
        ] {
            let mut args = args.clone();
            args.extend(["--measurements", file.to_str().unwrap()]);
            let o = run(&args);
            let stderr = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
            assert!(stderr.contains(want), "{args:?}: {stderr}");
            assert_eq!(stderr.lines().count(), 1, "{stderr}");
            assert!(o.stdout.is_empty(), "{args:?}");
            assert!(!out.exists(), "{args:?}: no partial output");
        }
    }
}

#[test]
fn pick_fits_a_budget_or_says_how_far_off_it_is() {
    let o = run(&[
        "pick",
        "--chip",
        "cortex-m0",
        "--mhz",
        "48",
        "--fps",
        "10",
        "--ram-kb",
        "32",
        "--allow-stale",
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(0), "{stdout}");
    let pick = stdout.lines().find(|l| l.starts_with("pick: ")).unwrap();
    // The most accurate within 4.8 M est. cycles and 32 KiB on the
    // dodecahedron: Phong costs 16.3 M cycles, so Gouraud with `fast`.
    assert!(pick.starts_with("pick: fast / Gouraud"), "{pick}");
    assert!(
        stdout.lines().any(|l| l.starts_with("runner-up: ")),
        "{stdout}"
    );
    // 60 fps in 8 KiB: nothing fits, exit 1 with the closest.
    let (code, stdout) = pick_m0("60", &["--ram-kb", "8"]);
    assert_eq!(code, Some(1), "{stdout}");
    assert!(stdout.contains("nothing fits. closest: "), "{stdout}");
    assert!(stdout.contains("bytes over the RAM"), "{stdout}");
    // Bad input: exit 2, nothing on stdout.
    for (args, want) in [
        (
            vec!["--chip", "cortex-m7", "--fps", "10"],
            "unknown chip `cortex-m7`",
        ),
        (
            vec!["--chip", "m0", "--fps", "0"],
            "--fps: 0 is not a positive number",
        ),
        (
            vec!["--chip", "m0", "--fps", "10", "--mhz", "-48"],
            "--mhz: -48 is not a positive number",
        ),
        (
            vec!["--chip", "m0", "--fps", "10", "--ram-kb", "NaN"],
            "--ram-kb: NaN is not a positive number",
        ),
        (
            vec!["--chip", "m0", "--fps", "10", "--scene", "teapot"],
            "no firmware measurements for `teapot`",
        ),
    ] {
        let mut a = vec!["pick", "--allow-stale"];
        a.extend(args);
        let o = run(&a);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{a:?}: {stderr}");
        assert!(stderr.contains(want), "{a:?}: {stderr}");
        assert!(o.stdout.is_empty(), "{a:?}");
    }
}

#[test]
fn the_users_scene_files_are_swept_and_picked_by_ram() {
    let scenes = fixshade_host::report::chips::repo_root().join("host-tests/scenes");
    let bunny = scenes.join("bunny-gouraud.toml");
    let bunny = bunny.to_str().unwrap();
    // The bunny needs more than 32 KiB in every configuration: exit 1,
    // with the bytes it needs.
    let (code, stdout) = pick_m0("10", &["--scene", bunny]);
    assert_eq!(code, Some(1), "{stdout}");
    assert!(
        stdout.contains("cycles: not measured for your scene"),
        "{stdout}"
    );
    assert!(
        stdout.contains("your scene is too big for 32768 bytes of RAM"),
        "{stdout}"
    );
    // 50 KB: room for the affine profiles' bunny (about 44 KB with
    // `fast`), not for the perspective-correct ones' (one more value per
    // vertex, 7 356 bytes: 57 862 bytes for `fast-pc`).
    let (code, stdout) = pick_m0("10", &["--ram-kb", "50", "--scene", bunny]);
    assert_eq!(code, Some(0), "{stdout}");
    assert!(stdout.contains("pick: fast / Gouraud"), "{stdout}");

    // `report SCENE.toml...`: the files instead of the built-ins, with
    // the RAM each needs against the parts.
    let tmp = TempDir::new("report-user");
    let out = tmp.0.join("out");
    let dodeca = scenes.join("dodeca-phong-n100.toml");
    let (o, stderr) = quick_report(&out, &[dodeca.to_str().unwrap(), bunny]);
    assert!(o.status.success(), "{stderr}");
    let data: ReportData = serde_json::from_str(&text(&out.join("results.json"))).unwrap();
    let names: Vec<&str> = data.meta.scenes.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["dodeca-phong-n100", "bunny-gouraud"]);
    assert_eq!(data.records.len(), 2 * 3 * 8);
    let ram = data.chips.as_ref().unwrap().user_ram.as_ref().unwrap();
    assert_eq!(ram.rows.len(), 2 * 3 * 8);
    assert!(
        ram.rows.iter().any(|r| r[4].starts_with("too big: needs ")),
        "{ram:?}"
    );
    assert!(
        ram.rows.iter().any(|r| r[4].starts_with("fits (")),
        "{ram:?}"
    );
    // A missing file: bad input, no output.
    let out2 = tmp.0.join("out2");
    let (o, stderr) = quick_report(&out2, &["/nonexistent/scene.toml"]);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(!out2.exists());
}

/// The lines of `help` that document `--firmware-profiles`: its own line
/// and the help text under it, up to the next option.
fn firmware_profiles_help(help: &str) -> Vec<String> {
    let mut lines = help
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("--firmware-profiles"));
    let first = lines.next().map(str::to_string);
    first
        .into_iter()
        .chain(
            lines
                .take_while(|l| !l.trim_start().starts_with('-') && !l.trim().is_empty())
                .map(str::to_string),
        )
        .collect()
}

#[test]
fn firmware_profiles_is_one_option_of_report_and_pick() {
    let report = run(&["report", "--help"]);
    let pick = run(&["pick", "--help"]);
    assert_eq!(report.status.code(), Some(0));
    assert_eq!(pick.status.code(), Some(0));
    let report = firmware_profiles_help(&String::from_utf8_lossy(&report.stdout));
    let pick = firmware_profiles_help(&String::from_utf8_lossy(&pick.stdout));
    assert!(
        report
            .first()
            .is_some_and(|l| l.contains("--firmware-profiles <NAMES>")),
        "{report:?}"
    );
    assert!(
        report
            .iter()
            .any(|l| l.contains("--measure-firmware measures")),
        "{report:?}"
    );
    assert_eq!(report, pick);
    // Only with --measure-firmware (a usage error), and unknown names are
    // refused before any measurement starts, with the same message.
    let o = run(&["report", "--out", "unused", "--firmware-profiles", "fast"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("--measure-firmware"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(!Path::new("unused").exists());
    let dir = std::env::temp_dir().join(format!("fixshade-fwprofiles-{}", std::process::id()));
    let out = dir.join("out");
    for args in [
        vec![
            "report",
            "--out",
            out.to_str().unwrap(),
            "--measure-firmware",
            "--firmware-profiles",
            "fast,teapot",
        ],
        vec![
            "pick",
            "--chip",
            "m0",
            "--fps",
            "10",
            "--allow-stale",
            "--scene",
            "mine.toml",
            "--measure-firmware",
            "--firmware-profiles",
            "fast,teapot",
        ],
    ] {
        let o = run(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        assert_eq!(
            stderr, "error: --firmware-profiles: unknown profile `teapot`\n",
            "{args:?}"
        );
        assert!(o.stdout.is_empty(), "{args:?}");
    }
    assert!(!out.exists());
}
