//! What the library says on stderr from places with no caller to return
//! an error to (the layer inside someone else's program, automatic
//! stereo): each message once, so that a frame loop does not flood the
//! terminal, and what only `GLSTEREO_VERBOSE` asks for.

use std::collections::HashSet;
use std::sync::{Mutex, OnceLock};

/// GLSTEREO_VERBOSE (`glstereo-run -v`): the layer says on stderr, once
/// per kind, which stereo each program got (native or emulated, and in
/// which format) and how its frames are presented.
pub const ENV_VERBOSE: &str = "GLSTEREO_VERBOSE";

/// Writes `glstereo: <message>` to stderr, once per distinct message.
pub fn warn(message: &str) {
    static SEEN: Mutex<Option<HashSet<String>>> = Mutex::new(None);
    let mut seen = SEEN.lock().unwrap_or_else(|e| e.into_inner());
    if seen
        .get_or_insert_with(HashSet::new)
        .insert(message.to_owned())
    {
        eprintln!("glstereo: {message}");
    }
}

/// Whether GLSTEREO_VERBOSE is set to anything but "" or "0".
pub fn verbose() -> bool {
    static VERBOSE: OnceLock<bool> = OnceLock::new();
    *VERBOSE
        .get_or_init(|| std::env::var_os(ENV_VERBOSE).is_some_and(|v| !v.is_empty() && v != "0"))
}

/// Says `message` on stderr (once) when GLSTEREO_VERBOSE is set.
pub fn tell(message: &str) {
    if verbose() {
        warn(message);
    }
}
