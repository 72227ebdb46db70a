//! Which `libglstereo_preload.so` glstereo-run preloads: the one built for
//! the program's word size and processor, found from where glstereo-run
//! itself lies, so a Debian package, a `make install PREFIX=…` tree and
//! the build tree each work without a path set by hand.
//!
//! The preload library is a private, plugin-like object (nothing links
//! against it; `src/interpose/next.rs` opens its stubs from its own
//! directory), so the packages put it and the stubs in a directory of
//! their own, `/usr/lib/<multiarch>/glstereo/`; `make install` keeps them
//! in `PREFIX/lib`. A program of another word size (a 32-bit program on a
//! 64-bit system) needs that word size's layer: the loader would refuse
//! ours with "wrong ELF class" and run the program without stereo, so the
//! program's ELF header is read first and the matching layer looked for;
//! where it is missing, one line says what to install.

use std::ffi::OsStr;
use std::io::Read;
use std::path::{Path, PathBuf};

/// The preload library's file name.
pub const PRELOAD: &str = "libglstereo_preload.so";
/// Overrides where the preload library is looked for.
pub const ENV_PRELOAD_LIB: &str = "GLSTEREO_PRELOAD_LIB";

/// A processor and word size, as Debian and Rust name it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Arch {
    /// ELF `e_machine`.
    machine: u16,
    /// ELFCLASS64 (else ELFCLASS32).
    wide: bool,
    /// Debian's architecture name (`apt-get install PKG:NAME`).
    pub debian: &'static str,
    /// The multiarch directory under `lib/`.
    triplet: &'static str,
    /// Rust's target (the build tree keeps a cross build in `target/<it>/`).
    rust: &'static str,
}

impl Arch {
    /// "64-bit" or "32-bit".
    pub fn bits(&self) -> &'static str {
        if self.wide { "64-bit" } else { "32-bit" }
    }
}

/// The architectures glstereo-run knows by their ELF header.
const ARCHES: [Arch; 4] = [
    Arch {
        machine: 62, // EM_X86_64
        wide: true,
        debian: "amd64",
        triplet: "x86_64-linux-gnu",
        rust: "x86_64-unknown-linux-gnu",
    },
    Arch {
        machine: 3, // EM_386
        wide: false,
        debian: "i386",
        triplet: "i386-linux-gnu",
        rust: "i686-unknown-linux-gnu",
    },
    Arch {
        machine: 183, // EM_AARCH64
        wide: true,
        debian: "arm64",
        triplet: "aarch64-linux-gnu",
        rust: "aarch64-unknown-linux-gnu",
    },
    Arch {
        machine: 40, // EM_ARM
        wide: false,
        debian: "armhf",
        triplet: "arm-linux-gnueabihf",
        rust: "armv7-unknown-linux-gnueabihf",
    },
];

/// The architecture glstereo-run (and so the layer beside it) was built for.
pub fn own() -> Option<Arch> {
    let machine = match std::env::consts::ARCH {
        "x86_64" => 62,
        "x86" => 3,
        "aarch64" => 183,
        "arm" => 40,
        _ => return None,
    };
    ARCHES.iter().copied().find(|a| a.machine == machine)
}

/// What an ELF file's header says it runs on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ElfId {
    /// ELFCLASS64 (else ELFCLASS32).
    pub wide: bool,
    /// `e_machine`.
    pub machine: u16,
}

impl ElfId {
    /// The header at the start of `bytes`, or None when it is not ELF.
    pub fn parse(bytes: &[u8]) -> Option<ElfId> {
        if bytes.len() < 20 || &bytes[..4] != b"\x7fELF" {
            return None;
        }
        let wide = match bytes[4] {
            1 => false,
            2 => true,
            _ => return None,
        };
        let m = [bytes[18], bytes[19]];
        let machine = match bytes[5] {
            1 => u16::from_le_bytes(m),
            2 => u16::from_be_bytes(m),
            _ => return None,
        };
        Some(ElfId { wide, machine })
    }

    /// The known architecture this header names.
    pub fn arch(&self) -> Option<Arch> {
        ARCHES
            .iter()
            .copied()
            .find(|a| a.machine == self.machine && a.wide == self.wide)
    }
}

/// The file `program` names as exec would run it (PATH searched when it
/// has no '/'), or None when there is none.
fn resolve(program: &OsStr) -> Option<PathBuf> {
    let p = Path::new(program);
    if program.as_encoded_bytes().contains(&b'/') {
        return Some(p.to_path_buf());
    }
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|d| d.join(p))
        .find(|c| c.is_file())
}

/// The ELF header of the program exec will run; None for a script, a
/// missing file or anything else exec judges by itself.
pub fn program_elf(program: &OsStr) -> Option<ElfId> {
    let mut head = [0u8; 20];
    std::fs::File::open(resolve(program)?)
        .ok()?
        .read_exact(&mut head)
        .ok()?;
    ElfId::parse(&head)
}

/// Where the layer for `arch` may be, for a glstereo-run in `dir`, most
/// likely first. `native`: `arch` is glstereo-run's own.
fn candidates(dir: &Path, arch: Arch, native: bool) -> Vec<PathBuf> {
    let lib = dir.join("..").join("lib");
    let mut c = Vec::new();
    if native {
        // The build tree: target/<profile>/, beside glstereo-run.
        c.push(dir.join(PRELOAD));
    } else if let Some(profile) = dir.file_name().filter(|_| dir.join(PRELOAD).is_file()) {
        // In a build tree (the native layer beside glstereo-run), a cross
        // build of the layer: target/<rust target>/<profile>/.
        c.push(dir.join("..").join(arch.rust).join(profile).join(PRELOAD));
    }
    // The Debian packages: /usr/lib/<multiarch>/glstereo/.
    c.push(lib.join(arch.triplet).join("glstereo").join(PRELOAD));
    c.push(lib.join(arch.triplet).join(PRELOAD));
    if native {
        // make install PREFIX=…: PREFIX/lib (or lib64).
        if arch.wide {
            c.push(dir.join("..").join("lib64").join(PRELOAD));
        }
        c.push(lib.join(PRELOAD));
    } else if !arch.wide {
        c.push(dir.join("..").join("lib32").join(PRELOAD));
    }
    c
}

fn list(paths: &[PathBuf]) -> String {
    paths
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

/// The preload library for `program`: $GLSTEREO_PRELOAD_LIB, else the one
/// of the program's architecture found from glstereo-run's own place
/// ([`candidates`]). Err: one line saying what is missing and what to
/// install.
pub fn find_preload(program: &OsStr) -> Result<PathBuf, String> {
    if let Some(p) = std::env::var_os(ENV_PRELOAD_LIB).filter(|p| !p.is_empty()) {
        let p = PathBuf::from(p);
        return if p.is_file() {
            Ok(std::path::absolute(&p).unwrap_or(p))
        } else {
            Err(format!("{ENV_PRELOAD_LIB}={} is not a file", p.display()))
        };
    }
    let exe = std::env::current_exe()
        .and_then(|e| e.canonicalize())
        .map_err(|e| format!("cannot locate glstereo-run itself: {e}"))?;
    let dir = exe.parent().unwrap_or(Path::new("/"));
    let own = own();
    let elf = program_elf(program);
    let wanted = match (elf, own) {
        (Some(id), Some(own)) if id.arch() != Some(own) => {
            let Some(arch) = id.arch() else {
                return Err(format!(
                    "{} is a {} program for another processor (ELF machine {}); \
                     glstereo's stereo layer here is for {} {} programs",
                    program.to_string_lossy(),
                    if id.wide { "64-bit" } else { "32-bit" },
                    id.machine,
                    own.bits(),
                    own.debian
                ));
            };
            let found = candidates(dir, arch, false);
            return first_file(&found).ok_or_else(|| {
                format!(
                    "{prog} is a {bits} program ({d}) and the stereo layer installed here \
                     is for {own_bits} ({own_d}) programs: install the {d} layer too (Debian: \
                     dpkg --add-architecture {d}; apt-get update; apt-get install \
                     libglstereo-preload:{d}; from source: the README's \"Install\") \
                     (looked in {looked})",
                    prog = program.to_string_lossy(),
                    bits = arch.bits(),
                    d = arch.debian,
                    own_bits = own.bits(),
                    own_d = own.debian,
                    looked = list(&found)
                )
            });
        }
        (_, Some(own)) => own,
        // An architecture without a Debian name here: the layer beside
        // glstereo-run or in ../lib, as before.
        (_, None) => {
            let c = [dir.join(PRELOAD), dir.join("../lib").join(PRELOAD)];
            return first_file(&c).ok_or_else(|| not_found(&c));
        }
    };
    let found = candidates(dir, wanted, true);
    first_file(&found).ok_or_else(|| not_found(&found))
}

/// The first of `paths` that is a file, resolved.
fn first_file(paths: &[PathBuf]) -> Option<PathBuf> {
    paths
        .iter()
        .find(|c| c.is_file())
        .map(|c| c.canonicalize().unwrap_or_else(|_| c.clone()))
}

fn not_found(looked: &[PathBuf]) -> String {
    format!(
        "cannot find {PRELOAD} (looked in {}): reinstall glstereo (Debian: apt-get install \
         --reinstall libglstereo-preload), or set {ENV_PRELOAD_LIB}",
        list(looked)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header(class: u8, data: u8, machine: u16) -> Vec<u8> {
        let mut h = vec![0u8; 52];
        h[..4].copy_from_slice(b"\x7fELF");
        h[4] = class;
        h[5] = data;
        h[6] = 1;
        let m = if data == 1 {
            machine.to_le_bytes()
        } else {
            machine.to_be_bytes()
        };
        h[18..20].copy_from_slice(&m);
        h
    }

    #[test]
    fn elf_headers_name_their_architecture() {
        let i386 = ElfId::parse(&header(1, 1, 3)).unwrap();
        assert_eq!(i386.arch().map(|a| a.debian), Some("i386"));
        let amd64 = ElfId::parse(&header(2, 1, 62)).unwrap();
        assert_eq!(amd64.arch().map(|a| a.debian), Some("amd64"));
        // x32: 32-bit class, x86-64 machine: no Debian layer of its own here.
        assert_eq!(ElfId::parse(&header(1, 1, 62)).unwrap().arch(), None);
        // Big-endian machine field.
        assert_eq!(ElfId::parse(&header(2, 2, 22)).unwrap().machine, 22);
        assert_eq!(ElfId::parse(b"#!/bin/sh\necho hello\n"), None);
        assert_eq!(ElfId::parse(b"\x7fELF"), None);
    }

    #[test]
    fn the_own_architecture_reads_its_own_header() {
        let exe = std::env::current_exe().unwrap();
        let id = program_elf(exe.as_os_str()).expect("the test binary is ELF");
        assert_eq!(id.arch(), own());
    }
}
