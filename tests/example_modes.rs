//! The examples' `--modes` option (what `make demo` uses to write
//! composite-<mode>.png): one composite per listed mode, each in its mode,
//! after the images of --mode; a bad name is a clear error.

mod common;

use std::process::Command;

#[test]
fn modes_writes_one_composite_per_listed_mode_in_that_mode() {
    let out = common::scratch("redblue_modes");
    let exe = common::build_example("redblue", false);
    let o = common::run_ok(
        Command::new(exe)
            .args(["--out", out.to_str().unwrap(), "--size", "40x30"])
            .args([
                "--mode",
                "left",
                "--modes",
                "side-by-side,RC,rows,top-bottom",
            ])
            .env("GLSTEREO_BACKEND", "egl")
            .env_remove("GLSTEREO_MODE"),
    );
    let stdout = String::from_utf8_lossy(&o.stdout);
    let left = common::png(&out.join("left.png"));
    let right = common::png(&out.join("right.png"));
    // RedBlue: at (20, 15) the left eye is blue, the right red, so the
    // placement checks below would catch swapped eyes.
    assert_eq!(left.get(20, 15), [1, 1, 255, 255], "left eye: blue");
    assert_eq!(right.get(20, 15), [255, 1, 1, 255], "right eye: red");
    // composite.png is written first, in --mode.
    assert_eq!(common::png(&out.join("composite.png")), left, "--mode left");
    // Aliases are written under their canonical name.
    assert!(
        stdout.contains("composite-anaglyph-red-cyan.png"),
        "{stdout}"
    );
    let sbs = common::png(&out.join("composite-side-by-side.png"));
    assert_eq!((sbs.width(), sbs.height()), (80, 30));
    assert_eq!(sbs.get(45, 20), right.get(5, 20), "right eye on the right");
    assert_eq!(sbs.get(20, 15), left.get(20, 15), "left eye on the left");
    assert_eq!(sbs.get(60, 15), right.get(20, 15), "right eye on the right");
    let tb = common::png(&out.join("composite-top-bottom.png"));
    assert_eq!((tb.width(), tb.height()), (40, 60));
    assert_eq!(tb.get(10, 35), right.get(10, 5), "right eye below");
    // (10, 5) is grey in both eyes: where they differ, too.
    assert_eq!(tb.get(20, 15), left.get(20, 15), "left eye above");
    assert_eq!(tb.get(20, 45), right.get(20, 15), "right eye below");
    let rows = common::png(&out.join("composite-rows.png"));
    for y in 0..30 {
        let eye = if y % 2 == 0 { &left } else { &right };
        assert_eq!(rows.get(20, y), eye.get(20, y), "row {y}");
    }
    let rc = common::png(&out.join("composite-anaglyph-red-cyan.png"));
    let (l, r) = (left.get(20, 15), right.get(20, 15));
    assert_eq!(rc.get(20, 15), [l[0], r[1], r[2], 255]);
}

#[test]
fn a_bad_name_in_modes_is_a_clear_error() {
    let out = common::scratch("redblue_bad_modes");
    let exe = common::build_example("redblue", false);
    let o = Command::new(exe)
        .args(["--out", out.to_str().unwrap(), "--size", "8x8"])
        .args(["--modes", "rows,sideways"])
        .env("GLSTEREO_BACKEND", "egl")
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("sideways") && err.contains("side-by-side"),
        "{err}"
    );
}
