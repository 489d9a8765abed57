//! `fixshade animate`, run as a real process: a turn of a scene as an
//! animated GIF, and exit status 2 with no file for bad input.

use crate::support::{TempDir, EXE};
use std::process::Command;

use fixshade_host::builtin::load_builtin;
use fixshade_host::cli::animate::turned;
use fixshade_host::core_render::{render_core, CoreProfile};

fn run(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(EXE).args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn a_turn_is_written_as_a_looping_gif() {
    let dir = TempDir::new("animate-ok");
    let gif = dir.join("spin.gif");
    let (code, stdout, stderr) = run(&[
        "animate",
        "--scene",
        "dodeca-gouraud-n100",
        "--frames",
        "6",
        "--profile",
        "fast",
        "--out",
        gif.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.starts_with(&format!("wrote {}: 6 frames of 160x160", gif.display())));
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::RGBA);
    let mut dec = opts.read_info(std::fs::File::open(&gif).unwrap()).unwrap();
    assert_eq!((dec.width(), dec.height()), (160, 160));
    let desc = load_builtin("dodeca-gouraud-n100").unwrap();
    let mut frames = 0;
    while let Some(f) = dec.read_next_frame().unwrap() {
        assert_eq!((f.width, f.height, f.delay), (160, 160, 4));
        // Each frame is the core's frame of that angle up to the palette:
        // the same covered pixels lit, within 16 levels (a 256-colour
        // palette of a Gouraud frame), the background black.
        let core = render_core(&turned(&desc, frames, 6), Some(CoreProfile::Fast)).unwrap();
        let mut worst = 0;
        for (i, px) in f.buffer.chunks(4).enumerate() {
            let want = core.rgb[i];
            let d = (0..3).map(|k| px[k].abs_diff(want[k])).max().unwrap();
            worst = worst.max(d);
            if !core.covered[i] {
                assert!(px[..3].iter().all(|&c| c < 8), "background at {i}: {px:?}");
            }
        }
        assert!(worst <= 16, "frame {frames}: {worst}");
        frames += 1;
    }
    assert_eq!(frames, 6);
    // The frames differ: the object turns.
    let a = render_core(&turned(&desc, 0, 6), Some(CoreProfile::Fast)).unwrap();
    let b = render_core(&turned(&desc, 1, 6), Some(CoreProfile::Fast)).unwrap();
    assert_ne!(a.rgb, b.rgb);
    // A full turn is the first frame again.
    let c = render_core(&turned(&desc, 6, 6), Some(CoreProfile::Fast)).unwrap();
    assert_eq!(a.covered, c.covered);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_input_is_status_2_and_no_file() {
    let dir = TempDir::new("animate-bad");
    let gif = dir.join("spin.gif");
    let g = gif.to_str().unwrap();
    let missing = dir.join("no-such-folder").join("spin.gif");
    let cases: [(Vec<&str>, &str); 4] = [
        (
            vec!["--scene", "dodeca-flat-n100", "--frames", "0", "--out", g],
            "error: --frames: must be in 1..=720, got 0\n",
        ),
        (
            vec!["--scene", "dodeca-flat-n100", "--frames", "721", "--out", g],
            "error: --frames: must be in 1..=720, got 721\n",
        ),
        (
            vec!["--scene", "dodeca-flat-n100", "--delay-cs", "0", "--out", g],
            "error: --delay-cs: must be at least 1\n",
        ),
        (
            vec!["--scene", "no-such-scene", "--frames", "3", "--out", g],
            "",
        ),
    ];
    for (args, want) in cases {
        let mut all = vec!["animate"];
        all.extend(args.iter().copied());
        let (code, _, stderr) = run(&all);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        if !want.is_empty() {
            assert_eq!(stderr, want);
        }
        assert!(!gif.exists(), "{args:?} wrote a file");
    }
    // An unwritable output: a missing folder, or a folder as the output.
    for out in [missing.to_str().unwrap(), dir.to_str().unwrap()] {
        let (code, _, stderr) = run(&[
            "animate",
            "--scene",
            "dodeca-flat-n100",
            "--frames",
            "2",
            "--out",
            out,
        ]);
        assert_eq!(code, 2, "{out}: {stderr}");
        assert!(
            stderr.starts_with(&format!("error: {out}: cannot write: ")),
            "{stderr}"
        );
    }
    let names: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert!(names.is_empty(), "left behind: {names:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}
