//! A stereo program that forks under glstereo-run: its child ends in every
//! way a process can (exit, _exit, a return from main, exec) as it would
//! without the layer, with captures on and off, and the parent's captures
//! are all written (tests/c/fork_exit.c on a private Xvfb).

mod common;

use std::path::PathBuf;
use std::process::Command;

use common::preload::{built, compile_plain};
use common::xvfb::Xvfb;

fn program() -> PathBuf {
    let dir = common::scratch("fork_exit");
    let exe = dir.join("fork_exit");
    compile_plain(
        &common::root().join("tests/c/fork_exit.c"),
        &exe,
        &["-lGL", "-lX11"],
    );
    exe
}

#[test]
fn a_forked_child_ends_every_way_cleanly_and_the_parent_captures_every_frame() {
    let x = Xvfb::start(320, 240);
    let exe = program();
    for way in ["exit", "_exit", "return", "exec"] {
        for capturing in [false, true] {
            let what = format!(
                "child {way}, captures {}",
                if capturing { "on" } else { "off" }
            );
            let dir = common::scratch(&format!("fork_capture_{way}"));
            let mut cmd = Command::new(&built().run);
            if capturing {
                cmd.arg("--capture").arg(&dir);
            }
            cmd.arg(&exe)
                .arg(way)
                .env("DISPLAY", &x.display)
                .env_remove("GLSTEREO_CAPTURE_DIR");
            let out = cmd.output().expect("glstereo-run starts");
            let stdout = String::from_utf8_lossy(&out.stdout);
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert!(
                out.status.success() && stdout.contains(&format!("child {way}: exited 0")),
                "{what}: {} (stdout {stdout:?})\nstderr:\n{stderr}",
                out.status
            );
            assert!(!stderr.contains("panicked"), "{what}: {stderr}");
            let mut names: Vec<String> = std::fs::read_dir(&dir)
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect();
            names.sort();
            if !capturing {
                assert!(names.is_empty(), "{what}: {names:?}");
                continue;
            }
            // Six frames, three before the fork (still being written when
            // the child ended) and three after, and nothing else.
            let mut want: Vec<String> = (1..=6)
                .flat_map(|n| ["composite", "left", "right"].map(|k| format!("{k}-{n:06}.png")))
                .collect();
            want.sort();
            assert_eq!(names, want, "{what}");
            for n in 1..=6 {
                let left = common::png(&dir.join(format!("left-{n:06}.png")));
                let right = common::png(&dir.join(format!("right-{n:06}.png")));
                assert_eq!(left.get(10, 10), [255, 0, 0, 255], "{what}: frame {n} left");
                assert_eq!(
                    right.get(10, 10),
                    [0, 0, 255, 255],
                    "{what}: frame {n} right"
                );
            }
        }
    }
}
