//! `glstereo-run [-m MODE] [--swap-eyes] [--capture DIR] [--capture-format
//! LIST] [--jpeg-quality N] program args…`: runs an unmodified OpenGL
//! program with glstereo's stereo layer (`libglstereo_preload.so`)
//! preloaded, like VirtualGL's `vglrun`. It checks its options with the
//! library first (a bad mode is refused before the program starts), sets
//! LD_PRELOAD, GLSTEREO_MODE, GLSTEREO_SWAP_EYES, GLSTEREO_CAPTURE_DIR,
//! GLSTEREO_CAPTURE_FORMAT and GLSTEREO_JPEG_QUALITY, and replaces itself
//! with the program.

use std::ffi::{OsStr, OsString};
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

use glstereo::interpose::capture::{
    CaptureSettings, ENV_CAPTURE_DIR, ENV_CAPTURE_FORMAT, ENV_JPEG_QUALITY,
};
use glstereo::interpose::live;
use glstereo::output::mode::{ALIASES, AliasSource};
use glstereo::output::options::{ENV_MODE, ENV_SWAP_EYES, OutputSettings};
use glstereo::output::{AnaglyphColors, AnaglyphMethod, OutputMode};

/// Where the preload library is (`locate.rs`: by where glstereo-run is
/// installed, for the program's word size).
#[path = "glstereo-run/locate.rs"]
mod locate;
/// Exit status for a usage or set-up error (the program never ran).
const USAGE_ERROR: u8 = 2;

fn describe(mode: OutputMode) -> String {
    let colors = |c: AnaglyphColors| match c {
        AnaglyphColors::RedCyan => "red (left) / cyan (right)",
        AnaglyphColors::GreenMagenta => "green (left) / magenta (right)",
        AnaglyphColors::AmberBlue => "amber (left) / blue (right)",
    };
    match mode {
        OutputMode::Quad => "the driver's own quad buffer where the server has stereo visuals; \
                             elsewhere anaglyph-red-cyan"
            .into(),
        OutputMode::Left => "the left eye only".into(),
        OutputMode::Right => "the right eye only".into(),
        OutputMode::Anaglyph(c, m) => {
            let how = match m {
                AnaglyphMethod::FullColor => "full colour",
                AnaglyphMethod::HalfColor => "half colour (left eye grey)",
                AnaglyphMethod::Monochrome => "monochrome",
                AnaglyphMethod::Dubois => "Dubois least-squares",
            };
            format!("anaglyph, {} glasses, {how}", colors(c))
        }
        OutputMode::AnaglyphRedBlue => "anaglyph, red (left) / blue (right), grey eyes".into(),
        OutputMode::SideBySide => {
            "both eyes at full size side by side (2W x H), left on the left".into()
        }
        OutputMode::TopBottom => "both eyes at full size, left on top (W x 2H)".into(),
        OutputMode::SideBySideHalf => {
            "each eye squeezed to half width, left on the left (3D TVs)".into()
        }
        OutputMode::TopBottomHalf => {
            "each eye squeezed to half height, left on top (3D TVs)".into()
        }
        OutputMode::Rows => "row-interleaved, top row from the left eye (passive monitors)".into(),
        OutputMode::Columns => "column-interleaved, leftmost column from the left eye".into(),
        OutputMode::Checkerboard => "checkerboard, top-left pixel from the left eye (DLP)".into(),
        OutputMode::FrameSequential => {
            "one eye per presented frame, left first (shutter glasses)".into()
        }
        OutputMode::HdmiFramePacking => {
            "HDMI 1.4 frame packing: left on top, gap, right below".into()
        }
        OutputMode::Starbase => {
            "HP Starbase sync-doubled: left squashed into the upper half".into()
        }
        OutputMode::StrRect => "SGI STR_RECT: each eye squashed to 492 rows, left on top".into(),
    }
}

fn help() -> String {
    let mut s = String::from(
        "Usage: glstereo-run [-m MODE] [-s] [-a|--auto=depth [--separation S] [--convergence C]]\n\
         \x20                   [-v]\
         \x20                   [-c DIR [-f FORMATS] [-q N]] [--] PROGRAM [ARGS...]\n\
         \n\
         Runs PROGRAM, an unmodified OpenGL (GLX) program, with glstereo's stereo\n\
         layer preloaded. A program that asks for a stereo visual (GLX_STEREO,\n\
         GLUT_STEREO) gets one even where the X server has none, draws both eyes\n\
         (glDrawBuffer(GL_BACK_LEFT / GL_BACK_RIGHT)), and each glXSwapBuffers shows\n\
         them in its window in MODE. Programs that do not ask for stereo run as\n\
         they would without the layer, unless --auto is given.\n\
         \n\
         Options:\n\
         \x20 -m, --mode MODE     how the window shows the eyes (sets GLSTEREO_MODE;\n\
         \x20                     default: $GLSTEREO_MODE, else anaglyph-red-cyan;\n\
         \x20                     -st MODE as in vglrun). A format other than quad\n\
         \x20                     also emulates the stereo a driver or a GL layer\n\
         \x20                     below (VirtualGL) offers; without one, that\n\
         \x20                     native stereo is used as it is\n\
         \x20 -s, --swap-eyes     exchange left and right (GLSTEREO_SWAP_EYES=1)\n\
         \x20 -a, --auto          automatic stereo: a program that never asks for stereo\n\
         \x20                     is shown in stereo all the same, every vertex moved\n\
         \x20                     per eye as NVIDIA 3D Vision Automatic moved it\n\
         \x20                     (GLSTEREO_AUTO=1)\n\
         \x20     --auto=depth    automatic stereo from one render: each frame drawn\n\
         \x20                     once, both eyes made from its colour and depth (faster;\n\
         \x20                     what depth cannot hold is flat: GLSTEREO_AUTO=depth)\n\
         \x20     --auto=geometry the same as --auto\n\
         \x20     --separation S  automatic stereo's separation, percent 0..100: far\n\
         \x20                     geometry S% of 7% of the width apart (default 15;\n\
         \x20                     GLSTEREO_SEPARATION)\n\
         \x20     --convergence C automatic stereo's convergence: the distance (clip w)\n\
         \x20                     at the screen, > 0, or auto (default; GLSTEREO_CONVERGENCE)\n\
         \x20 -v, --verbose       say on stderr which stereo the program got (native or\n\
         \x20                     emulated, in which format) and how frames are\n\
         \x20                     presented (GLSTEREO_VERBOSE=1)\n\
         \x20 -c, --capture DIR   write every presented frame to DIR as left-NNNNNN.png,\n\
         \x20                     right-NNNNNN.png and composite-NNNNNN.png (made if\n\
         \x20                     missing; sets GLSTEREO_CAPTURE_DIR)\n\
         \x20 -f, --capture-format FORMATS\n\
         \x20                     what --capture writes per frame: png (the three\n\
         \x20                     PNGs, default), mpo (stereo-NNNNNN.mpo, CIPA\n\
         \x20                     multi-picture), jps (stereo-NNNNNN.jps, right eye\n\
         \x20                     on the left), or a list: png,mpo (sets\n\
         \x20                     GLSTEREO_CAPTURE_FORMAT)\n\
         \x20 -q, --jpeg-quality N  JPEG quality of mpo and jps captures, 1..100\n\
         \x20                     (default 90; sets GLSTEREO_JPEG_QUALITY)\n\
         \x20 -h, --help          this text\n\
         \x20 -V, --version       the glstereo version\n\
         \n\
         Modes:\n",
    );
    for m in OutputMode::all() {
        s.push_str(&format!("  {:<30}{}\n", m.canonical_name(), describe(m)));
    }
    s.push_str("\nAliases (VirtualGL vglrun -st, OpenSceneGraph OSG_STEREO_MODE):\n");
    for a in ALIASES {
        let from = match a.source {
            AliasSource::VirtualGl => "VirtualGL",
            AliasSource::OpenSceneGraph => "OpenSceneGraph",
        };
        let same = if a.differs.is_empty() {
            ""
        } else {
            " (placement differs; see glstereo-run(1))"
        };
        s.push_str(&format!(
            "  {:<22}= {} ({from}){same}\n",
            a.name,
            a.mode.canonical_name()
        ));
    }
    s.push_str(
        "\nKeys in the program's window (never passed to it; GLSTEREO_KEYS=0: off):\n\
         \x20 Ctrl+F7, Ctrl+Shift+F7  next, previous format      Ctrl+F8  exchange the eyes\n\
         \x20 automatic stereo: Ctrl+F3/F4 separation, Ctrl+F5/F6 convergence, Ctrl+T on/off,\n\
         \x20                    Ctrl+F2 geometry or depth\n",
    );
    s.push_str(
        "\nEnvironment: GLSTEREO_MODE, GLSTEREO_SWAP_EYES, GLSTEREO_AUTO, GLSTEREO_SEPARATION,\n\
         GLSTEREO_CONVERGENCE, GLSTEREO_VERBOSE, GLSTEREO_CROSSTALK (0..1),\n\
         GLSTEREO_SATURATION (0..1), GLSTEREO_CAPTURE_DIR, GLSTEREO_CAPTURE_FORMAT,\n\
         GLSTEREO_JPEG_QUALITY (1..100), GLSTEREO_KEYS; GLSTEREO_PRELOAD_LIB names\n\
         the preload library when it is not installed beside glstereo-run.\n\
         \n\
         Exit status: PROGRAM's; 2 for a usage error; 126/127 when PROGRAM cannot be run.\n",
    );
    s
}

/// What the command line asks for.
struct Request {
    mode: Option<OutputMode>,
    swap_eyes: bool,
    auto: Option<live::AutoMode>,
    separation: Option<String>,
    convergence: Option<String>,
    capture: Option<PathBuf>,
    capture_format: Option<String>,
    jpeg_quality: Option<String>,
    verbose: bool,
    program: Vec<OsString>,
}

enum Parsed {
    Run(Request),
    Help,
    Version,
}

fn parse(args: &[OsString]) -> Result<Parsed, String> {
    let mut req = Request {
        mode: None,
        swap_eyes: false,
        auto: None,
        separation: None,
        convergence: None,
        capture: None,
        capture_format: None,
        jpeg_quality: None,
        verbose: false,
        program: Vec::new(),
    };
    let mut i = 0;
    while i < args.len() {
        let arg = args[i].to_string_lossy().into_owned();
        // --opt=value
        let (flag, inline) = match arg.split_once('=') {
            Some((f, v)) if f.starts_with("--") => (f.to_owned(), Some(OsString::from(v))),
            _ => (arg.clone(), None),
        };
        let mut value = |name: &str| -> Result<OsString, String> {
            if let Some(v) = inline.clone() {
                return Ok(v);
            }
            i += 1;
            args.get(i)
                .cloned()
                .ok_or_else(|| format!("{name} needs a value"))
        };
        // An option that takes no value refuses one given with `=` (a
        // typo, or an option of a newer version, must not pass silently).
        let plain = |name: &str| -> Result<(), String> {
            match &inline {
                Some(v) => Err(format!(
                    "{name} takes no value (given {name}={}; see glstereo-run --help)",
                    v.to_string_lossy()
                )),
                None => Ok(()),
            }
        };
        match flag.as_str() {
            "-h" | "--help" | "-V" | "--version" | "-s" | "--swap-eyes" | "-v" | "--verbose"
            | "-a" => plain(&flag)?,
            _ => {}
        }
        match flag.as_str() {
            "-h" | "--help" => return Ok(Parsed::Help),
            "-V" | "--version" => return Ok(Parsed::Version),
            "-m" | "--mode" | "-st" => {
                let v = value(&flag)?;
                let name = v.to_string_lossy();
                let mode = OutputMode::from_name(&name).map_err(|e| e.to_string())?;
                req.mode = Some(mode);
            }
            "-s" | "--swap-eyes" => req.swap_eyes = true,
            "-a" => req.auto = Some(live::AutoMode::Geometry),
            "--auto" => {
                req.auto = Some(match &inline {
                    None => live::AutoMode::Geometry,
                    Some(v) => live::parse_auto(&v.to_string_lossy())
                        .ok()
                        .flatten()
                        .ok_or_else(|| {
                            format!(
                                "--auto={} is not a kind of automatic stereo: --auto, \
                                 --auto=geometry or --auto=depth",
                                v.to_string_lossy()
                            )
                        })?,
                })
            }
            "--separation" => {
                let v = value(&flag)?.to_string_lossy().into_owned();
                live::parse_separation(&v).map_err(|e| format!("--separation: {e}"))?;
                req.separation = Some(v);
            }
            "--convergence" => {
                let v = value(&flag)?.to_string_lossy().into_owned();
                live::parse_convergence(&v).map_err(|e| format!("--convergence: {e}"))?;
                req.convergence = Some(v);
            }
            "-v" | "--verbose" => req.verbose = true,
            "-c" | "--capture" => req.capture = Some(PathBuf::from(value(&flag)?)),
            "-f" | "--capture-format" => {
                req.capture_format = Some(value(&flag)?.to_string_lossy().into_owned());
            }
            "-q" | "--jpeg-quality" => {
                req.jpeg_quality = Some(value(&flag)?.to_string_lossy().into_owned());
            }
            "--" => {
                req.program = args[i + 1..].to_vec();
                break;
            }
            f if f.starts_with('-') && f.len() > 1 => {
                return Err(format!("unknown option {f} (see glstereo-run --help)"));
            }
            _ => {
                req.program = args[i..].to_vec();
                break;
            }
        }
        i += 1;
    }
    if req.program.is_empty() {
        return Err("no program to run (see glstereo-run --help)".into());
    }
    Ok(Parsed::Run(req))
}

fn prepend_preload(lib: &Path) -> OsString {
    let mut v = OsString::from(lib.as_os_str());
    if let Some(old) = std::env::var_os("LD_PRELOAD").filter(|o| !o.is_empty()) {
        v.push(":");
        v.push(old);
    }
    v
}

fn run(req: Request) -> Result<std::io::Error, String> {
    let lib = locate::find_preload(&req.program[0])?;
    let mut cmd = Command::new(&req.program[0]);
    cmd.args(&req.program[1..]);
    cmd.env("LD_PRELOAD", prepend_preload(&lib));
    if let Some(m) = req.mode {
        cmd.env(ENV_MODE, m.canonical_name());
    }
    if req.swap_eyes {
        cmd.env(ENV_SWAP_EYES, "1");
    }
    if let Some(mode) = req.auto {
        cmd.env(live::ENV_AUTO, mode.name());
    }
    if let Some(s) = &req.separation {
        cmd.env(live::ENV_SEPARATION, s);
    }
    if let Some(c) = &req.convergence {
        cmd.env(live::ENV_CONVERGENCE, c);
    }
    // Automatic stereo's settings from the environment are checked too.
    if req.separation.is_none() {
        if let Some(v) = std::env::var(live::ENV_SEPARATION)
            .ok()
            .filter(|v| !v.trim().is_empty())
        {
            live::parse_separation(&v).map_err(|e| e.to_string())?;
        }
    }
    if req.convergence.is_none() {
        if let Some(v) = std::env::var(live::ENV_CONVERGENCE)
            .ok()
            .filter(|v| !v.trim().is_empty())
        {
            live::parse_convergence(&v).map_err(|e| e.to_string())?;
        }
    }
    if req.verbose {
        cmd.env(glstereo::interpose::settings::ENV_VERBOSE, "1");
    }
    if let Some(f) = &req.capture_format {
        cmd.env(ENV_CAPTURE_FORMAT, f);
    }
    if let Some(q) = &req.jpeg_quality {
        cmd.env(ENV_JPEG_QUALITY, q);
    }
    let capturing =
        req.capture.is_some() || std::env::var_os(ENV_CAPTURE_DIR).is_some_and(|d| !d.is_empty());
    if !capturing && (req.capture_format.is_some() || req.jpeg_quality.is_some()) {
        return Err(
            "--capture-format and --jpeg-quality say how --capture writes frames: \
             give --capture DIR too"
                .into(),
        );
    }
    if let Some(dir) = &req.capture {
        std::fs::create_dir_all(dir).map_err(|e| {
            format!(
                "--capture {}: cannot create the directory: {e}",
                dir.display()
            )
        })?;
        let abs = dir.canonicalize().unwrap_or_else(|_| dir.clone());
        cmd.env(ENV_CAPTURE_DIR, abs);
    }
    // The settings the layer will read, checked now so a bad value stops
    // here with a message instead of inside the program.
    let overrides = |name: &str| -> Option<String> {
        match name {
            n if n == ENV_MODE && req.mode.is_some() => req.mode.map(|m| m.canonical_name().into()),
            n if n == ENV_SWAP_EYES && req.swap_eyes => Some("1".into()),
            n => std::env::var(n).ok(),
        }
    };
    OutputSettings::from_env_with(overrides).map_err(|e| e.to_string())?;
    CaptureSettings::from_env_with(|name| match name {
        n if n == ENV_CAPTURE_FORMAT && req.capture_format.is_some() => req.capture_format.clone(),
        n if n == ENV_JPEG_QUALITY && req.jpeg_quality.is_some() => req.jpeg_quality.clone(),
        n => std::env::var(n).ok(),
    })
    .map_err(|e| e.to_string())?;
    // Only returns on failure.
    Ok(cmd.exec())
}

fn main() -> ExitCode {
    let args: Vec<OsString> = std::env::args_os().skip(1).collect();
    match parse(&args) {
        Ok(Parsed::Help) => {
            print!("{}", help());
            ExitCode::SUCCESS
        }
        Ok(Parsed::Version) => {
            println!("glstereo-run {}", env!("CARGO_PKG_VERSION"));
            ExitCode::SUCCESS
        }
        Ok(Parsed::Run(req)) => {
            let program = req.program[0].clone();
            match run(req) {
                Ok(e) => {
                    eprintln!(
                        "glstereo-run: cannot run {}: {e}",
                        OsStr::new(&program).to_string_lossy()
                    );
                    ExitCode::from(if e.kind() == std::io::ErrorKind::NotFound {
                        127
                    } else {
                        126
                    })
                }
                Err(msg) => {
                    eprintln!("glstereo-run: {msg}");
                    ExitCode::from(USAGE_ERROR)
                }
            }
        }
        Err(msg) => {
            eprintln!("glstereo-run: {msg}");
            ExitCode::from(USAGE_ERROR)
        }
    }
}
