//! Just enough of GLSL's lexical structure to edit a shader's source
//! safely: the `#version` line, preprocessor lines and `#line` numbering,
//! comments, and the identifiers outside them. Pure; no GL.
//!
//! The edits of [`crate::auto::vertex`] need four facts about a source:
//! which version and profile it is written for, where the `#version`
//! directive ends (directives we add go right after it: `#extension` must
//! precede every token that is not a preprocessor one), where the first
//! token that is not a preprocessor one starts (declarations we need early
//! go there, after every `#extension` the shader itself has), and which
//! identifiers it uses outside comments (`main`, `EmitVertex`,
//! `gl_PerVertex`…). A preprocessor line may continue over a backslash
//! newline; comments are `//` to the end of the line and `/* … */`.

/// The profile a `#version` line names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Profile {
    /// Desktop GLSL without a profile word, or `core` (the default from 1.50 on).
    Core,
    /// `compatibility`, or a desktop version before 1.50 (which has no
    /// profiles: every built-in of the compatibility profile is there).
    Compatibility,
    /// OpenGL ES GLSL: `#version 100`, or `es` after 300 and later.
    Es,
}

/// A shader's `#version`: 110 when it has none.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Version {
    /// 100, 110, 120, 130, 140, 150, 300, 310, 320, 330, 400 … 460.
    pub number: u32,
    /// The profile.
    pub profile: Profile,
}

impl Version {
    /// Whether a `#line N` directive makes the *next* line number N (GLSL
    /// 3.30 and newer, ES 3.00 and newer) rather than N + 1 (the older
    /// languages: "as if it is compiling at line number line + 1").
    pub fn line_directive_names_next_line(&self) -> bool {
        match self.profile {
            Profile::Es => self.number >= 300,
            _ => self.number >= 330,
        }
    }
}

/// What [`scan`] learned about a source.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Scan {
    /// The version (110 compatibility when there is no `#version`).
    pub version: Version,
    /// Byte offset just past the `#version` line and its newline (0 when
    /// there is none): where added directives go.
    pub after_version: usize,
    /// Whether the `#version` line ends the source without a newline.
    pub version_unterminated: bool,
    /// Byte offset of the start of the line holding the first token that
    /// is not part of a preprocessor line or comment (the source's length
    /// when there is none): where early declarations go.
    pub first_token_line: usize,
    /// The line number the compiler gives the line at `first_token_line`
    /// (1-based, following the shader's own `#line` directives before it).
    pub first_token_line_number: u32,
    /// The line number the compiler gives the line at `after_version`.
    pub after_version_line_number: u32,
}

/// Where comments are, as byte ranges, in `source`.
fn comment_ranges(source: &str) -> Vec<(usize, usize)> {
    let b = source.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i + 1 < b.len() {
        match (b[i], b[i + 1]) {
            (b'/', b'/') => {
                let start = i;
                // A backslash newline continues a `//` comment too.
                while i < b.len() && b[i] != b'\n' {
                    if b[i] == b'\\' && i + 1 < b.len() && b[i + 1] == b'\n' {
                        i += 1;
                    }
                    i += 1;
                }
                out.push((start, i));
            }
            (b'/', b'*') => {
                let start = i;
                i += 2;
                while i + 1 < b.len() && !(b[i] == b'*' && b[i + 1] == b'/') {
                    i += 1;
                }
                i = (i + 2).min(b.len());
                out.push((start, i));
            }
            _ => i += 1,
        }
    }
    out
}

/// `source` with every comment replaced by blanks (newlines kept), so byte
/// offsets and line numbers stay those of the source.
pub fn blank_comments(source: &str) -> String {
    let mut out = source.as_bytes().to_vec();
    for (start, end) in comment_ranges(source) {
        for c in &mut out[start..end] {
            if *c != b'\n' {
                *c = b' ';
            }
        }
    }
    // Only ASCII bytes inside comments were replaced by ASCII blanks; a
    // multi-byte character is replaced whole, so the result is UTF-8.
    String::from_utf8(out).unwrap_or_default()
}

/// The logical lines of a comment-free source: (start offset, end offset
/// past the newline, text). A line ending in a backslash continues.
fn logical_lines(text: &str) -> Vec<(usize, usize, String)> {
    let mut out = Vec::new();
    let mut start = 0;
    let mut joined = String::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        offset += line.len();
        let body = line.trim_end_matches(['\n', '\r']);
        if let Some(cont) = body.strip_suffix('\\') {
            joined.push_str(cont);
            continue;
        }
        joined.push_str(body);
        out.push((start, offset, std::mem::take(&mut joined)));
        start = offset;
    }
    if !joined.is_empty() {
        out.push((start, offset, joined));
    }
    out
}

/// A preprocessor directive's name and the rest of its line, when `line`
/// is one (blanks may stand before and after the `#`).
pub fn directive(line: &str) -> Option<(&str, &str)> {
    let rest = line.trim_start_matches([' ', '\t']).strip_prefix('#')?;
    let rest = rest.trim_start_matches([' ', '\t']);
    let end = rest
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(rest.len());
    Some((&rest[..end], rest[end..].trim()))
}

/// Reads a `#version` directive's argument ("330 core", "300 es").
fn parse_version(arg: &str) -> Version {
    let mut words = arg.split_whitespace();
    let number = words.next().and_then(|n| n.parse().ok()).unwrap_or(110);
    let profile = match words.next() {
        Some("es") => Profile::Es,
        Some("compatibility") => Profile::Compatibility,
        Some(_) => Profile::Core,
        None if number == 100 => Profile::Es,
        None if number < 150 => Profile::Compatibility,
        None => Profile::Core,
    };
    Version { number, profile }
}

/// Scans `source` (see [`Scan`]).
pub fn scan(source: &str) -> Scan {
    let text = blank_comments(source);
    let mut version = Version {
        number: 110,
        profile: Profile::Compatibility,
    };
    let mut after_version = 0;
    let mut version_unterminated = false;
    let mut after_version_line_number = 1;
    let mut first_token_line = source.len();
    let mut first_token_line_number = 0;
    // The first token inside a conditional block, where none comes
    // outside one (a shader wholly inside `#ifndef`).
    let mut conditional_token: Option<(usize, u32)> = None;
    let mut depth = 0u32;
    // The number the compiler gives the next physical line.
    let mut number: u32 = 1;
    for (start, end, line) in logical_lines(&text) {
        let physical = text[start..end].matches('\n').count().max(1) as u32;
        match directive(&line) {
            Some(("if" | "ifdef" | "ifndef", _)) => {
                depth += 1;
                number += physical;
            }
            Some(("endif", _)) => {
                depth = depth.saturating_sub(1);
                number += physical;
            }
            Some(("version", arg)) if after_version == 0 => {
                version = parse_version(arg);
                after_version = end;
                version_unterminated = !text[start..end].ends_with('\n');
                number += physical;
                after_version_line_number = number;
            }
            Some(("line", arg)) => {
                let n = arg
                    .split_whitespace()
                    .next()
                    .and_then(|n| n.parse::<u32>().ok());
                match n {
                    Some(n) if version.line_directive_names_next_line() => number = n,
                    Some(n) => number = n + 1,
                    None => number += physical,
                }
            }
            Some(_) => number += physical,
            None if line.trim().is_empty() => number += physical,
            // A declaration in a conditional block may not be compiled: what
            // must come before the shader's code goes before its first
            // token outside one.
            None if depth > 0 => {
                conditional_token.get_or_insert((start, number));
                number += physical;
            }
            None => {
                first_token_line = start;
                first_token_line_number = number;
                break;
            }
        }
    }
    if first_token_line == source.len() {
        match conditional_token {
            Some((start, n)) => (first_token_line, first_token_line_number) = (start, n),
            None => first_token_line_number = number,
        }
    }
    Scan {
        version,
        after_version,
        version_unterminated,
        first_token_line,
        first_token_line_number,
        after_version_line_number,
    }
}

/// The identifiers of a comment-free source outside preprocessor lines,
/// each with its byte offset.
pub fn identifiers(text: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    for (start, end, line) in logical_lines(text) {
        if directive(&line).is_some() {
            continue;
        }
        let s = &text[start..end];
        let b = s.as_bytes();
        let mut i = 0;
        while i < b.len() {
            let c = b[i];
            if c.is_ascii_alphabetic() || c == b'_' {
                let from = i;
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                    i += 1;
                }
                out.push((start + from, &s[from..i]));
            } else if c.is_ascii_digit() {
                // A number (and its suffix: 1.0f, 0x1Fu) is no identifier.
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'.') {
                    i += 1;
                }
            } else {
                i += 1;
            }
        }
    }
    out
}

/// The names gl_Position is computed from in a comment-free vertex-stage
/// source: the identifiers on the right of its assignments, and of the
/// assignments to those (`vec4 eye = ModelView * p; gl_Position =
/// Projection * eye;` gives Projection, eye, ModelView and p), in order
/// of first appearance. Functions are not followed (their names are
/// listed, not their bodies). Automatic convergence takes the matrices a
/// program uploads to these names as its camera: a light's or a shadow
/// map's matrix uploaded beside it (glmark2's refract) is not.
pub fn position_names(text: &str) -> Vec<String> {
    // Statements: the text between ; { and }, outside preprocessor lines.
    let mut code = String::with_capacity(text.len());
    for (start, end, line) in logical_lines(text) {
        if directive(&line).is_none() {
            code.push_str(&text[start..end]);
        }
        code.push('\n');
    }
    let statements: Vec<(Vec<&str>, Vec<&str>)> = code
        .split([';', '{', '}'])
        .filter_map(|st| {
            let b = st.as_bytes();
            // The first plain or compound assignment: an '=' that is not
            // part of ==, <=, >= or !=.
            let eq = (0..b.len()).find(|&i| {
                b[i] == b'='
                    && b.get(i + 1) != Some(&b'=')
                    && (i == 0 || !matches!(b[i - 1], b'=' | b'<' | b'>' | b'!'))
            })?;
            fn ids(t: &str) -> Vec<&str> {
                identifiers(t).into_iter().map(|(_, id)| id).collect()
            }
            Some((ids(&st[..eq]), ids(&st[eq + 1..])))
        })
        .collect();
    let mut names: Vec<String> = vec!["gl_Position".to_owned()];
    loop {
        let before = names.len();
        for (lhs, rhs) in &statements {
            if lhs.iter().any(|l| names.iter().any(|n| n == l)) {
                for r in rhs {
                    if !names.iter().any(|n| n == r) {
                        names.push((*r).to_owned());
                    }
                }
            }
        }
        if names.len() == before {
            break;
        }
    }
    names.remove(0);
    names
}

/// The text of a comment-free source after byte `at`, blanks skipped.
pub fn after(text: &str, at: usize) -> &str {
    text[at..].trim_start()
}

/// Whether the comment-free `text` defines a function `main` (the token
/// `main`, its parameter list and a `{`), rather than only declaring it.
pub fn defines_main(text: &str) -> bool {
    identifiers(text).into_iter().any(|(at, id)| {
        id == "main"
            && after(text, at + 4)
                .strip_prefix('(')
                .and_then(|r| r.find(')').map(|close| &r[close + 1..]))
                .is_some_and(|r| r.trim_start().starts_with('{'))
    })
}

/// Whether the comment-free `text` uses the identifier `name` outside
/// preprocessor lines.
pub fn uses(text: &str, name: &str) -> bool {
    identifiers(text).into_iter().any(|(_, id)| id == name)
}

/// An `out gl_PerVertex { … }` redeclaration in the comment-free `text`:
/// the byte offset just past its `{`, and its members' text. None when
/// the text has none.
pub fn out_per_vertex(text: &str) -> Option<(usize, String)> {
    let ids = identifiers(text);
    ids.windows(2).find_map(|w| {
        let ((_, q), (at, name)) = (w[0], w[1]);
        if q != "out" || name != "gl_PerVertex" {
            return None;
        }
        let rest = &text[at + name.len()..];
        let brace = rest.find(|c: char| !c.is_whitespace())?;
        if !rest[brace..].starts_with('{') {
            return None;
        }
        let body = &rest[brace + 1..];
        let close = body.find('}')?;
        Some((at + name.len() + brace + 1, body[..close].to_owned()))
    })
}

/// The members of an `out gl_PerVertex { … }` redeclaration, or None.
pub fn out_per_vertex_members(text: &str) -> Option<String> {
    out_per_vertex(text).map(|(_, members)| members)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_names_gl_position_comes_from_leave_out_a_lights_matrix() {
        // glmark2's light-refract.vert, shortened.
        let src = "attribute vec3 position;\nuniform mat4 ModelViewProjectionMatrix;\n\
                   uniform mat4 LightMatrix;\nvarying vec4 MapCoord;\nvoid main(void)\n{\n\
                   vec4 current_position = vec4(position, 1.0);\n\
                   MapCoord = LightMatrix * current_position;\n\
                   gl_Position = ModelViewProjectionMatrix * current_position;\n}\n";
        assert_eq!(
            position_names(src),
            [
                "ModelViewProjectionMatrix",
                "current_position",
                "vec4",
                "position"
            ]
        );
    }

    #[test]
    fn the_names_gl_position_comes_from_through_locals_and_compound_assignments() {
        let src = "#version 330\n#define X (a == b)\nuniform mat4 P, MV, Shadow;\n\
                   void main() {\n  vec4 eye = MV * vec4(pos, 1.0);\n  if (k <= 2) {\n\
                   shadow = Shadow * eye; }\n  gl_Position = P * eye;\n  gl_Position.xy *= scale;\n}\n";
        assert_eq!(
            position_names(src),
            ["P", "eye", "scale", "MV", "vec4", "pos"]
        );
        // Nothing assigned to gl_Position: nothing.
        assert!(position_names("void main() { x = y; }").is_empty());
    }

    #[test]
    fn early_declarations_go_before_the_first_token_outside_conditionals() {
        let src = "#version 330\n#if SHADOWS\nuniform mat4 light;\n#endif\nlayout(points) in;\n";
        let s = scan(src);
        assert_eq!(&src[s.first_token_line..], "layout(points) in;\n");
        assert_eq!(s.first_token_line_number, 5);
        // Wholly inside one: its first token.
        let src = "#version 150\n#ifndef NO_GS\nlayout(points) in;\n#endif\n";
        let s = scan(src);
        assert_eq!(&src[s.first_token_line..], "layout(points) in;\n#endif\n");
        assert_eq!(s.first_token_line_number, 3);
    }

    #[test]
    fn versions_and_profiles() {
        let v = |s: &str| scan(s).version;
        assert_eq!(
            v("void main(){}"),
            Version {
                number: 110,
                profile: Profile::Compatibility
            }
        );
        assert_eq!(v("#version 120\n").profile, Profile::Compatibility);
        assert_eq!(v("#version 150\n").profile, Profile::Core);
        assert_eq!(
            v("#version 150 compatibility\n").profile,
            Profile::Compatibility
        );
        assert_eq!(v("  #  version 330 core\n").number, 330);
        assert_eq!(v("#version 100\n").profile, Profile::Es);
        assert_eq!(
            v("#version 310 es\n"),
            Version {
                number: 310,
                profile: Profile::Es
            }
        );
        // A #version in a comment is no directive.
        assert_eq!(v("// #version 450\nvoid main(){}").number, 110);
        assert_eq!(v("/* a\n */ #version 450\n").number, 450);
    }

    #[test]
    fn where_directives_and_declarations_go() {
        let src = "// head\n#version 330 core\n#extension GL_ARB_x : enable\n\n/* c */\n#define A 1\nin vec3 p;\nvoid main(){}\n";
        let s = scan(src);
        assert_eq!(
            &src[s.after_version..],
            &src[src.find("#extension").unwrap()..]
        );
        assert_eq!(s.after_version_line_number, 3);
        assert_eq!(&src[s.first_token_line..], "in vec3 p;\nvoid main(){}\n");
        assert_eq!(s.first_token_line_number, 7);
        assert!(!s.version_unterminated);
        let s = scan("#version 130");
        assert!(s.version_unterminated);
        assert_eq!(s.first_token_line, "#version 130".len());
    }

    #[test]
    fn line_directives_renumber_by_the_version_rule() {
        // GLSL 1.10: "#line 10" makes the next line 11.
        let s = scan("#version 110\n#line 10\nattribute vec4 p;\n");
        assert_eq!(s.first_token_line_number, 11);
        // GLSL 3.30: the next line is 10.
        let s = scan("#version 330\n#line 10\nin vec4 p;\n");
        assert_eq!(s.first_token_line_number, 10);
        // A continued directive counts all its physical lines.
        let s = scan("#version 330\n#define A \\\n  1\nin vec4 p;\n");
        assert_eq!(s.first_token_line_number, 4);
    }

    #[test]
    fn main_in_comments_and_declarations_is_not_a_definition() {
        let t = blank_comments("// void main() {}\nvoid main();\n/* main() { */");
        assert!(!defines_main(&t));
        let t = blank_comments("void main ( void )\n{\n}\n");
        assert!(defines_main(&t));
        let t = blank_comments("void main_color() {}\n");
        assert!(!defines_main(&t));
        assert!(uses(&t, "main_color"));
        assert!(!uses("#define EmitVertex() x\n", "EmitVertex"));
        assert!(!uses("float x = 1.0e5f;", "e5f"));
    }

    #[test]
    fn per_vertex_redeclarations() {
        let t = "out gl_PerVertex {\n vec4 gl_Position;\n float gl_PointSize;\n};\n";
        assert!(out_per_vertex_members(t).unwrap().contains("gl_Position"));
        let t = "out gl_PerVertex { float gl_PointSize; };";
        assert!(!out_per_vertex_members(t).unwrap().contains("gl_Position"));
        assert_eq!(
            out_per_vertex_members("in gl_PerVertex { vec4 gl_Position; } gl_in[];"),
            None
        );
    }
}
