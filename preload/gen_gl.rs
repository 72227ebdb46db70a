//! The GL commands of the Khronos registry (gl.xml) as Rust signatures: the
//! build script's reader, for the wrappers it generates (STYLE.md item 19:
//! entry points come from the registry, not from hand-typed lists).

use std::collections::BTreeSet;

/// One command of gl.xml with Rust types.
pub struct Command {
    /// The name (`glDrawArrays`).
    pub name: String,
    /// The return type (None: void).
    pub ret: Option<String>,
    /// The parameters: (name, type).
    pub params: Vec<(String, String)>,
}

/// The desktop GL commands of `xml`: those a `gl` feature or an extension
/// supported by `gl` or `glcore` requires, with types this reader knows
/// (the others are left out: the caller generates nothing for them).
pub fn desktop_commands(xml: &str) -> Vec<Command> {
    let doc = roxmltree::Document::parse(xml).expect("gl.xml parses");
    let root = doc.root_element();
    let mut wanted = BTreeSet::new();
    for node in root.descendants() {
        let take = match node.tag_name().name() {
            "feature" => node.attribute("api") == Some("gl"),
            "extension" => node
                .attribute("supported")
                .is_some_and(|s| s.split('|').any(|a| a == "gl" || a == "glcore")),
            _ => false,
        };
        if !take {
            continue;
        }
        for req in node.children().filter(|c| c.has_tag_name("require")) {
            if req.attribute("api").is_some_and(|a| a != "gl") {
                continue;
            }
            for c in req.children().filter(|c| c.has_tag_name("command")) {
                if let Some(n) = c.attribute("name") {
                    wanted.insert(n.to_owned());
                }
            }
        }
    }
    let mut out = Vec::new();
    for cmd in root
        .descendants()
        .filter(|n| n.has_tag_name("commands"))
        .flat_map(|n| n.children().filter(|c| c.has_tag_name("command")))
    {
        let Some(proto) = cmd.children().find(|c| c.has_tag_name("proto")) else {
            continue;
        };
        let (name, ret) = split_decl(proto);
        if !wanted.contains(&name) {
            continue;
        }
        let Some(ret) = rust_type(&ret) else {
            continue;
        };
        let mut params = Vec::new();
        let mut known = true;
        for p in cmd.children().filter(|c| c.has_tag_name("param")) {
            let (pname, ty) = split_decl(p);
            match rust_type(&ty) {
                Some(Some(t)) => params.push((param_name(&pname), t)),
                _ => known = false,
            }
        }
        if known {
            out.push(Command { name, ret, params });
        }
    }
    out
}

/// A `<proto>` or `<param>`: the text of its `<name>`, and the C type (the
/// rest of its text).
fn split_decl(node: roxmltree::Node) -> (String, String) {
    let mut name = String::new();
    let mut ty = String::new();
    for d in node.descendants().filter(|d| d.is_text()) {
        let text = d.text().unwrap_or("");
        if d.parent().is_some_and(|p| p.has_tag_name("name")) {
            name.push_str(text);
        } else {
            ty.push_str(text);
            ty.push(' ');
        }
    }
    (name, ty)
}

/// A parameter name that is not a Rust keyword.
fn param_name(name: &str) -> String {
    match name {
        "type" | "ref" | "in" | "fn" | "mod" | "box" | "use" | "impl" | "gen" | "match"
        | "loop" | "move" | "self" | "where" | "yield" | "async" | "await" | "dyn" => {
            format!("{name}_")
        }
        n => n.to_owned(),
    }
}

/// The Rust type of a C type of gl.xml (`const GLint *`, `const void *const*`):
/// Some(None) for void, None for a type this reader does not know.
pub fn rust_type(c: &str) -> Option<Option<String>> {
    let spaced = c.replace('*', " * ");
    let tokens: Vec<&str> = spaced.split_whitespace().collect();
    // [const] base {* [const]}
    let mut i = 0;
    let mut consts = vec![false];
    if tokens.get(i) == Some(&"const") {
        consts[0] = true;
        i += 1;
    }
    let base = *tokens.get(i)?;
    i += 1;
    if tokens.get(i) == Some(&"const") {
        consts[0] = true;
        i += 1;
    }
    let mut stars = 0;
    while i < tokens.len() {
        match tokens[i] {
            "*" => {
                stars += 1;
                consts.push(false);
            }
            "const" => *consts.last_mut().expect("a level") = true,
            _ => return None,
        }
        i += 1;
    }
    let mut ty = match base {
        "void" | "GLvoid" if stars == 0 => return Some(None),
        "void" | "GLvoid" => "c_void",
        "GLenum" | "GLbitfield" | "GLuint" | "GLhandleARB" => "u32",
        "GLboolean" | "GLubyte" => "u8",
        "GLbyte" => "i8",
        "GLshort" => "i16",
        "GLushort" | "GLhalf" | "GLhalfARB" | "GLhalfNV" => "u16",
        "GLint" | "GLsizei" | "GLfixed" | "GLclampx" => "i32",
        "GLfloat" | "GLclampf" => "f32",
        "GLdouble" | "GLclampd" => "f64",
        "GLchar" | "GLcharARB" => "c_char",
        "GLintptr" | "GLintptrARB" | "GLsizeiptr" | "GLsizeiptrARB" | "GLvdpauSurfaceNV" => "isize",
        "GLint64" | "GLint64EXT" => "i64",
        "GLuint64" | "GLuint64EXT" => "u64",
        "GLsync" | "GLeglImageOES" | "GLeglClientBufferEXT" => "*mut c_void",
        _ => return None,
    }
    .to_owned();
    for &pointee_const in &consts[..stars] {
        ty = format!("{} {ty}", if pointee_const { "*const" } else { "*mut" });
    }
    Some(Some(ty))
}
