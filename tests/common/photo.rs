//! Reading stereo photos back with readers that are not glstereo's:
//! Pillow (python3-pil) for the pixels, exiftool for the MP Index and the
//! JPS descriptor.

use std::path::Path;
use std::process::Command;

use glstereo::image::Image;

/// Mean absolute difference per RGB channel between `want` and the block
/// of `got` of `want`'s size whose left column is `x0` (`got`: the RGB
/// bytes of an image `width` pixels wide, as [`pillow`] decodes it).
pub fn mean_error(got: &[u8], width: u32, x0: u32, want: &Image) -> f64 {
    let mut sum = 0u64;
    for y in 0..want.height() {
        for x in 0..want.width() {
            let g = &got[((y * width + x0 + x) * 3) as usize..][..3];
            let w = want.get(x, y);
            for c in 0..3 {
                sum += u64::from(g[c].abs_diff(w[c]));
            }
        }
    }
    sum as f64 / f64::from(want.width() * want.height() * 3)
}

/// One decoded frame: width, height, RGB bytes.
pub type Frame = (u32, u32, Vec<u8>);

/// Pillow's view of a file: format, frame count, and each frame's size and
/// RGB pixels (written to `<file>.frameN.rgb`).
pub fn pillow(file: &Path) -> (String, usize, Vec<Frame>) {
    let script = r#"
import sys
from PIL import Image
im = Image.open(sys.argv[1])
n = getattr(im, "n_frames", 1)
print(im.format, n)
for i in range(n):
    im.seek(i)
    f = im.convert("RGB")
    open("%s.frame%d.rgb" % (sys.argv[1], i), "wb").write(f.tobytes())
    print(f.size[0], f.size[1])
"#;
    // Debian's interpreter, which python3-pil is installed for (a python3
    // earlier in PATH, e.g. pyenv's, may not have it).
    let out = super::run_ok(
        Command::new("/usr/bin/python3")
            .arg("-c")
            .arg(script)
            .arg(file),
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    let mut head = lines.next().unwrap().split(' ');
    let format = head.next().unwrap().to_owned();
    let n: usize = head.next().unwrap().parse().unwrap();
    let frames = (0..n)
        .map(|i| {
            let mut wh = lines.next().unwrap().split(' ');
            let w = wh.next().unwrap().parse().unwrap();
            let h = wh.next().unwrap().parse().unwrap();
            let rgb = std::fs::read(format!("{}.frame{i}.rgb", file.display())).unwrap();
            (w, h, rgb)
        })
        .collect();
    (format, n, frames)
}

/// exiftool's tags of a file, as `[Group] Tag : value` lines (numbers raw).
pub fn exiftool(file: &Path) -> String {
    let out = super::run_ok(
        Command::new("exiftool")
            .args(["-a", "-G1", "-n", "-s"])
            .arg(file),
    );
    String::from_utf8(out.stdout).unwrap()
}

/// The value of `group:tag` in exiftool's `-G1 -s` output.
pub fn tag(tags: &str, group: &str, name: &str) -> String {
    let key = format!("[{group}]");
    tags.lines()
        .find_map(|l| {
            let l = l.trim();
            let rest = l.strip_prefix(&key)?.trim_start();
            let (n, v) = rest.split_once(':')?;
            (n.trim() == name).then(|| v.trim().to_owned())
        })
        .unwrap_or_else(|| panic!("exiftool shows no {group}:{name} in\n{tags}"))
}
