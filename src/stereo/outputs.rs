//! Fragment output 0 in every buffer a glDrawBuffer name selects.
//!
//! GL 4.5 §17.4.1: under glDrawBuffer(GL_BACK) on a stereo framebuffer,
//! fragment colour zero is written to back-left *and* back-right. The
//! emulated framebuffer is a framebuffer object, where output i goes to
//! draw buffer i only; fixed-function colour and gl_FragColor are
//! broadcast to every draw buffer, but a user-defined `out` variable and
//! `gl_FragData[0]` are not. So when a program with a user-defined output
//! at location 0, or writing `gl_FragData[0]`, is linked, it is linked a
//! second time with a fragment shader that also writes that output to the
//! locations of [`crate::stereo::emulated::COPY_LOCATIONS`], the
//! draw-buffer slots the emulated framebuffer gives the other selected
//! buffers.
//!
//! Why at link time and not a pass per eye: the shader runs once per
//! fragment as on a real stereo framebuffer, so atomic counters, image and
//! SSBO stores, transform feedback and queries count what they would (a
//! second pass would double them), every draw entry point is covered
//! without being interposed, and a draw costs what it did. The price is
//! paid once per link (the fragment shader is compiled and the program
//! linked again) and a program's introspection shows three more outputs
//! (`gls_stereo_copy5`…`7`, locations 5…7; see the README; none for
//! `gl_FragData`, whose elements 5…7 are the copies).
//!
//! How: the user's `main` is renamed by a `#define` after `#version`, and
//! a new `main` calling it then copying output 0 is appended; the copies'
//! locations are set with glBindFragDataLocation (GLSL 1.30 and newer).
//! Output 0 is the variable at location 0, or, when GL 4.4 `component`
//! qualifiers share the location among several, all of them, each copied
//! into its own components ([`copy_of`]); or `gl_FragData[0]`, copied to
//! `gl_FragData[5…7]` ([`Copies`]). The program keeps the user's shader
//! objects attached, and a failure at any step (no source: SPIR-V or
//! program binaries, which [`crate::interpose::binaries`] keeps from being
//! loaded without the copies; several fragment shaders; locations 5…7 or
//! dual-source outputs in use; `gl_FragData` elements other than 0
//! written; the rewritten shader not compiling) relinks the program as the
//! user linked it and says why ([`Outcome::Kept`]).

use std::ffi::{CStr, c_char, c_void};

use crate::stereo::emulated::COPY_LOCATIONS;

const GL_FRAGMENT_SHADER: u32 = 0x8B30;
const GL_SHADER_TYPE: u32 = 0x8B4F;
const GL_COMPILE_STATUS: u32 = 0x8B81;
const GL_LINK_STATUS: u32 = 0x8B82;
const GL_ATTACHED_SHADERS: u32 = 0x8B85;
const GL_SHADER_SOURCE_LENGTH: u32 = 0x8B88;
const GL_PROGRAM_OUTPUT: u32 = 0x92E4;
const GL_ACTIVE_RESOURCES: u32 = 0x92F5;
const GL_NAME_LENGTH: u32 = 0x92F9;
const GL_TYPE: u32 = 0x92FA;
const GL_ARRAY_SIZE: u32 = 0x92FB;
const GL_LOCATION: u32 = 0x930E;
const GL_LOCATION_INDEX: u32 = 0x930F;
const GL_LOCATION_COMPONENT: u32 = 0x934A;

/// Prefix of the copies' names (`gls_stereo_copy7` is location 7).
pub const COPY_PREFIX: &str = "gls_stereo_copy";
const USER_MAIN: &str = "gls_stereo_user_main";

/// The fragment output types, by GL type enum: the float, int and uint
/// scalars and vectors of 2, 3 and 4 components, in that order.
const OUTPUT_TYPES: [[(u32, &str); 4]; 3] = [
    [
        (0x1406, "float"),
        (0x8B50, "vec2"),
        (0x8B51, "vec3"),
        (0x8B52, "vec4"),
    ],
    [
        (0x1404, "int"),
        (0x8B53, "ivec2"),
        (0x8B54, "ivec3"),
        (0x8B55, "ivec4"),
    ],
    [
        (0x1405, "uint"),
        (0x8DC6, "uvec2"),
        (0x8DC7, "uvec3"),
        (0x8DC8, "uvec4"),
    ],
];

/// A fragment output type's row of [`OUTPUT_TYPES`] (its scalar type)
/// and its number of components.
fn output_type(gl_type: u32) -> Option<(usize, usize)> {
    OUTPUT_TYPES.iter().enumerate().find_map(|(base, row)| {
        let n = row.iter().position(|&(t, _)| t == gl_type)?;
        Some((base, n + 1))
    })
}

/// The GLSL type name of a fragment output type, or None for a type a
/// fragment output cannot have.
pub fn glsl_type(gl_type: u32) -> Option<&'static str> {
    output_type(gl_type).map(|(base, n)| OUTPUT_TYPES[base][n - 1].1)
}

/// One variable writing location 0: its name (`c[0]` for an array), GL
/// type and first component (GL 4.4 lets several variables share a
/// location, each in its own components).
#[derive(Clone, Copy, Debug)]
pub struct Part<'a> {
    /// The name program introspection gives.
    pub name: &'a str,
    /// Its GL type (GL_FLOAT_VEC2, …).
    pub gl_type: u32,
    /// Its first component (`layout(component = …)`; 0 without).
    pub component: u32,
}

/// The GLSL type and expression of the copies of location 0 written by
/// `parts`: the one variable itself when it starts at component 0, else
/// a vector with each variable in its components and 0 in the components
/// none writes (GL leaves those undefined).
///
/// # Errors
/// A message saying why no copy can be made: a type a fragment output
/// cannot have, variables of different scalar types, or components
/// overlapping or past the fourth.
pub fn copy_of(parts: &[Part]) -> Result<(&'static str, String), String> {
    let mut typed = Vec::with_capacity(parts.len());
    for p in parts {
        let Some((base, n)) = output_type(p.gl_type) else {
            return Err(format!("output {} has type {:#x}", p.name, p.gl_type));
        };
        typed.push((p.component as usize, n, base, p.name));
    }
    typed.sort_unstable();
    match typed[..] {
        [] => return Err("no output is at location 0".into()),
        [(0, n, base, name)] => return Ok((OUTPUT_TYPES[base][n - 1].1, name.to_owned())),
        _ => {}
    }
    let base = typed[0].2;
    let mut args = Vec::new();
    let mut at = 0;
    for &(component, n, b, name) in &typed {
        if b != base {
            return Err(format!(
                "the outputs at location 0 mix {} and {} components",
                OUTPUT_TYPES[base][0].1, OUTPUT_TYPES[b][0].1
            ));
        }
        if component < at {
            return Err(format!("output {name} overlaps another one's components"));
        }
        if component + n > 4 {
            return Err(format!("output {name} runs past the fourth component"));
        }
        while at < component {
            args.push(format!("{}(0)", OUTPUT_TYPES[base][0].1));
            at += 1;
        }
        args.push(name.to_owned());
        at += n;
    }
    let ty = OUTPUT_TYPES[base][at - 1].1;
    Ok((ty, format!("{ty}({})", args.join(", "))))
}

/// What the copies of output 0 are.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Copies {
    /// New outputs `gls_stereo_copyN` of GLSL type `ty`, bound to location
    /// N with glBindFragDataLocation, given `expr` ([`copy_of`]).
    Declared {
        /// Their GLSL type.
        ty: &'static str,
        /// What they are given.
        expr: String,
    },
    /// `gl_FragData[N] = gl_FragData[0]`: a shader writing the built-in
    /// array cannot declare outputs, and its element N is location N.
    FragData,
}

/// The fragment shader source `source` with output 0 also written to
/// location N for each N of [`COPY_LOCATIONS`], as `copies` says. The
/// user's `main` becomes `gls_stereo_user_main` (a `#define` after the
/// `#version` line, which must stay first); the new `main` calls it and
/// copies the output, so early returns are covered and `discard` discards
/// the copies too.
pub fn duplicate_output(source: &str, copies: &Copies) -> String {
    let mut insert_at = 0;
    let mut offset = 0;
    for line in source.split_inclusive('\n') {
        offset += line.len();
        if is_version_directive(line) {
            insert_at = offset;
            break;
        }
    }
    let (head, tail) = source.split_at(insert_at);
    let newline = if head.is_empty() || head.ends_with('\n') {
        ""
    } else {
        "\n"
    };
    let mut out = String::with_capacity(source.len() + 400);
    out.push_str(head);
    out.push_str(newline);
    out.push_str(&format!("#define main {USER_MAIN}\n"));
    out.push_str(tail);
    out.push_str("\n#undef main\n");
    if let Copies::Declared { ty, .. } = copies {
        for loc in COPY_LOCATIONS {
            out.push_str(&format!("out {ty} {COPY_PREFIX}{loc};\n"));
        }
    }
    out.push_str(&format!("void main()\n{{\n    {USER_MAIN}();\n"));
    for loc in COPY_LOCATIONS {
        out.push_str(&match copies {
            Copies::Declared { expr, .. } => format!("    {COPY_PREFIX}{loc} = {expr};\n"),
            Copies::FragData => format!("    gl_FragData[{loc}] = gl_FragData[0];\n"),
        });
    }
    out.push_str("}\n");
    out
}

/// Whether every `gl_FragData` in `source` is `gl_FragData[0]` (blanks
/// allowed): then the copies to elements 5…7 overwrite nothing the shader
/// writes itself. An element by another number or by an expression, or the
/// name in a macro, is a no.
fn frag_data_only_element_zero(source: &str) -> bool {
    source.match_indices("gl_FragData").all(|(at, name)| {
        source[at + name.len()..]
            .trim_start()
            .strip_prefix('[')
            .and_then(|r| r.trim_start().strip_prefix('0'))
            .is_some_and(|r| r.trim_start().starts_with(']'))
    })
}

/// Whether `line` is a `#version` directive: GLSL lets blanks (spaces,
/// tabs) stand before the `#` and between it and the directive's name.
fn is_version_directive(line: &str) -> bool {
    let blanks: &[char] = &[' ', '\t'];
    line.trim_start_matches(blanks)
        .strip_prefix('#')
        .map(|rest| rest.trim_start_matches(blanks))
        .and_then(|rest| rest.strip_prefix("version"))
        .is_some_and(|rest| rest.starts_with(|c: char| c.is_ascii_whitespace()))
}

macro_rules! link_fns {
    ($( $field:ident = $sym:literal: fn($($ty:ty),*) $(-> $ret:ty)?; )*) => {
        /// The GL functions relinking needs (GL 2.0, 3.0's
        /// glBindFragDataLocation, 4.3's program interface queries), looked
        /// up once through the backend's GetProcAddress.
        #[allow(non_snake_case)]
        pub struct LinkFns {
            $( pub(crate) $field: unsafe extern "system" fn($($ty),*) $(-> $ret)?, )*
        }

        impl LinkFns {
            /// Looks every function up through `get`; None when one is
            /// missing (a driver before GL 4.3 without
            /// ARB_program_interface_query: programs are then linked once,
            /// as the user linked them).
            ///
            /// # Safety
            /// `get` must return the named GL function (its Khronos
            /// signature) or NULL.
            pub unsafe fn load(get: impl Fn(&CStr) -> *const c_void) -> Option<LinkFns> {
                Some(LinkFns {
                    $( $field: {
                        let p = get($sym);
                        if p.is_null() {
                            return None;
                        }
                        // SAFETY: the named function, with its Khronos signature.
                        unsafe { std::mem::transmute::<*const c_void, unsafe extern "system" fn($($ty),*) $(-> $ret)?>(p) }
                    }, )*
                })
            }
        }
    };
}

link_fns! {
    link_program = c"glLinkProgram": fn(u32);
    create_program = c"glCreateProgram": fn() -> u32;
    delete_program = c"glDeleteProgram": fn(u32);
    get_programiv = c"glGetProgramiv": fn(u32, u32, *mut i32);
    get_attached_shaders = c"glGetAttachedShaders": fn(u32, i32, *mut i32, *mut u32);
    get_shaderiv = c"glGetShaderiv": fn(u32, u32, *mut i32);
    get_shader_source = c"glGetShaderSource": fn(u32, i32, *mut i32, *mut c_char);
    create_shader = c"glCreateShader": fn(u32) -> u32;
    shader_source = c"glShaderSource": fn(u32, i32, *const *const c_char, *const i32);
    compile_shader = c"glCompileShader": fn(u32);
    delete_shader = c"glDeleteShader": fn(u32);
    attach_shader = c"glAttachShader": fn(u32, u32);
    detach_shader = c"glDetachShader": fn(u32, u32);
    bind_frag_data_location = c"glBindFragDataLocation": fn(u32, u32, *const c_char);
    get_frag_data_location = c"glGetFragDataLocation": fn(u32, *const c_char) -> i32;
    get_program_interfaceiv = c"glGetProgramInterfaceiv": fn(u32, u32, u32, *mut i32);
    get_program_resourceiv = c"glGetProgramResourceiv": fn(u32, u32, u32, i32, *const u32, i32, *mut i32, *mut i32);
    get_program_resource_name = c"glGetProgramResourceName": fn(u32, u32, u32, i32, *mut i32, *mut c_char);
}

/// What [`LinkFns::duplicate_output_zero`] did.
#[derive(Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Relinked: output 0 reaches every buffer a glDrawBuffer name selects.
    Duplicated,
    /// Nothing to do: the link failed, or neither a user-defined output at
    /// location 0 nor `gl_FragData` is written (fixed function,
    /// gl_FragColor, no fragment shader, or already rewritten).
    NotNeeded,
    /// Linked as the user linked it, for this reason: output 0 reaches
    /// only the first selected buffer.
    Kept(String),
}

/// Where a linked program's fragment output 0 goes under a glDrawBuffer
/// name selecting several buffers, as its interface shows
/// ([`LinkFns::reach`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reach {
    /// Every selected buffer: it carries the copies, or has nothing to
    /// copy (fixed function, gl_FragColor, no output at location 0).
    Every,
    /// The first selected buffer only: a user-defined output at location
    /// 0 without copies.
    First,
    /// Not shown: it writes `gl_FragData`, whose copies (elements 5…7)
    /// its interface does not tell apart.
    Unknown,
}

/// One fragment output of a linked program.
struct Output {
    name: String,
    location: i32,
    index: i32,
    component: i32,
    ty: u32,
    size: i32,
}

impl LinkFns {
    /// After a successful glLinkProgram (or glCreateShaderProgramv) of
    /// `program`: relinks it with output 0 copied to the copy locations
    /// when it has a user-defined output at location 0 or writes
    /// `gl_FragData`. `source` is the fragment shader's source when the
    /// program has no attached fragment shader (glCreateShaderProgramv),
    /// None to read it from the attached one. May raise GL errors: through
    /// a misuse the link itself would have reported, and GL_INVALID_ENUM
    /// from the GL_LOCATION_COMPONENT query on a driver before GL 4.4;
    /// callers keep the program's error state apart.
    ///
    /// # Safety
    /// A GL context must be current on this thread, `program` a program
    /// object of it.
    pub unsafe fn duplicate_output_zero(&self, program: u32, source: Option<&str>) -> Outcome {
        // SAFETY: contract.
        unsafe {
            if self.program_int(program, GL_LINK_STATUS) == 0 {
                return Outcome::NotNeeded;
            }
            let outputs = self.outputs(program);
            if outputs.iter().any(|o| o.name.starts_with(COPY_PREFIX)) {
                return Outcome::NotNeeded;
            }
            let zero: Vec<&Output> = outputs
                .iter()
                .filter(|o| o.location == 0 && o.index == 0 && !o.name.starts_with("gl_"))
                .collect();
            let frag_data = outputs.iter().find(|o| o.name.starts_with("gl_FragData"));
            if zero.is_empty() && frag_data.is_none() {
                return Outcome::NotNeeded;
            }
            if outputs.iter().any(|o| o.index > 0) {
                return Outcome::Kept(
                    "the fragment shader has a dual-source output (index 1)".into(),
                );
            }
            if let Some(o) = outputs.iter().find(|o| {
                o.location >= 0
                    && COPY_LOCATIONS
                        .iter()
                        .any(|&l| (o.location..o.location + o.size.max(1)).contains(&(l as i32)))
            }) {
                return Outcome::Kept(format!(
                    "output {} uses location {}, one of 5…7 the copies need",
                    o.name, o.location
                ));
            }
            let copies = match (zero.first(), frag_data) {
                (Some(_), _) => {
                    let parts: Vec<Part> = zero
                        .iter()
                        .map(|o| Part {
                            name: &o.name,
                            gl_type: o.ty,
                            component: o.component.max(0) as u32,
                        })
                        .collect();
                    match copy_of(&parts) {
                        Ok((ty, expr)) => Copies::Declared { ty, expr },
                        Err(why) => return Outcome::Kept(why),
                    }
                }
                (None, Some(fd)) if COPY_LOCATIONS.iter().any(|&l| l as i32 >= fd.size) => {
                    return Outcome::Kept(format!(
                        "gl_FragData has {} elements, and the copies need 8",
                        fd.size
                    ));
                }
                (None, Some(_)) => Copies::FragData,
                (None, None) => return Outcome::NotNeeded,
            };
            let attached = match source {
                Some(_) => None,
                None => match self.fragment_shader(program) {
                    Ok(s) => Some(s),
                    Err(why) => return Outcome::Kept(why),
                },
            };
            let original = match (source, attached) {
                (Some(s), _) => s.to_owned(),
                (None, Some(fs)) => match self.shader_source(fs) {
                    Some(s) => s,
                    None => {
                        return Outcome::Kept(
                            "the fragment shader has no GLSL source (SPIR-V)".into(),
                        );
                    }
                },
                (None, None) => return Outcome::NotNeeded,
            };
            if copies == Copies::FragData && !frag_data_only_element_zero(&original) {
                return Outcome::Kept(
                    "the fragment shader writes gl_FragData elements other than [0]".into(),
                );
            }
            let rewritten = duplicate_output(&original, &copies);
            let Some(copy) = self.compile(&rewritten) else {
                return Outcome::Kept("the rewritten fragment shader does not compile".into());
            };
            // While the user's shader is detached, a scratch program holds
            // it: a shader the user already deleted would otherwise go away
            // (its name with it, which the user may still detach).
            let holder = match attached {
                Some(fs) => {
                    let h = (self.create_program)();
                    (self.attach_shader)(h, fs);
                    (self.detach_shader)(program, fs);
                    Some((h, fs))
                }
                None => None,
            };
            (self.attach_shader)(program, copy);
            if let Copies::Declared { .. } = copies {
                for loc in COPY_LOCATIONS {
                    let name = std::ffi::CString::new(format!("{COPY_PREFIX}{loc}")).unwrap();
                    (self.bind_frag_data_location)(program, loc, name.as_ptr());
                }
            }
            (self.link_program)(program);
            let ok = self.program_int(program, GL_LINK_STATUS) != 0
                && zero.first().is_none_or(|first| {
                    let name = std::ffi::CString::new(first.name.trim_end_matches("[0]")).unwrap();
                    (self.get_frag_data_location)(program, name.as_ptr()) == 0
                });
            (self.detach_shader)(program, copy);
            (self.delete_shader)(copy);
            // The user's shader attached again, as after the user's link.
            if let Some((h, fs)) = holder {
                (self.attach_shader)(program, fs);
                (self.delete_program)(h);
            }
            if ok {
                return Outcome::Duplicated;
            }
            // Linked again as the user linked it.
            match attached {
                Some(_) => (self.link_program)(program),
                None => {
                    if let Some(fs) = self.compile(&original) {
                        (self.attach_shader)(program, fs);
                        (self.link_program)(program);
                        (self.detach_shader)(program, fs);
                        (self.delete_shader)(fs);
                    }
                }
            }
            Outcome::Kept("the rewritten program does not link".into())
        }
    }

    /// Where the fragment output 0 of `program` (linked, or loaded from a
    /// binary) goes, from its interface alone. May raise GL errors (the
    /// GL_LOCATION_COMPONENT query before GL 4.4); callers keep the
    /// program's error state apart.
    ///
    /// # Safety
    /// A GL context must be current on this thread, `program` a program
    /// object of it.
    pub unsafe fn reach(&self, program: u32) -> Reach {
        // SAFETY: contract.
        let outputs = unsafe { self.outputs(program) };
        if outputs.iter().any(|o| o.name.starts_with(COPY_PREFIX)) {
            Reach::Every
        } else if outputs
            .iter()
            .any(|o| o.location == 0 && !o.name.starts_with("gl_"))
        {
            Reach::First
        } else if outputs.iter().any(|o| o.name.starts_with("gl_FragData")) {
            Reach::Unknown
        } else {
            Reach::Every
        }
    }

    pub(crate) unsafe fn program_int(&self, program: u32, pname: u32) -> i32 {
        let mut v = 0;
        // SAFETY: contract of the callers; one value.
        unsafe { (self.get_programiv)(program, pname, &mut v) };
        v
    }

    pub(crate) unsafe fn shader_int(&self, shader: u32, pname: u32) -> i32 {
        let mut v = 0;
        // SAFETY: contract of the callers; one value.
        unsafe { (self.get_shaderiv)(shader, pname, &mut v) };
        v
    }

    unsafe fn outputs(&self, program: u32) -> Vec<Output> {
        let mut n = 0;
        // SAFETY: contract of the callers; buffers sized as GL is told.
        unsafe {
            (self.get_program_interfaceiv)(program, GL_PROGRAM_OUTPUT, GL_ACTIVE_RESOURCES, &mut n);
            (0..n.max(0) as u32)
                .map(|i| {
                    let props = [
                        GL_LOCATION,
                        GL_LOCATION_INDEX,
                        GL_TYPE,
                        GL_ARRAY_SIZE,
                        GL_NAME_LENGTH,
                    ];
                    let mut v = [0i32; 5];
                    (self.get_program_resourceiv)(
                        program,
                        GL_PROGRAM_OUTPUT,
                        i,
                        props.len() as i32,
                        props.as_ptr(),
                        v.len() as i32,
                        std::ptr::null_mut(),
                        v.as_mut_ptr(),
                    );
                    // GL 4.4 (ARB_enhanced_layouts); an older driver
                    // raises GL_INVALID_ENUM, which the callers drop, and
                    // every output is in its location's first component.
                    let mut component = 0;
                    (self.get_program_resourceiv)(
                        program,
                        GL_PROGRAM_OUTPUT,
                        i,
                        1,
                        &GL_LOCATION_COMPONENT,
                        1,
                        std::ptr::null_mut(),
                        &mut component,
                    );
                    // GL_NAME_LENGTH counts the terminating NUL.
                    let mut buf = vec![0 as c_char; v[4].max(1) as usize];
                    let mut len = 0;
                    (self.get_program_resource_name)(
                        program,
                        GL_PROGRAM_OUTPUT,
                        i,
                        buf.len() as i32,
                        &mut len,
                        buf.as_mut_ptr(),
                    );
                    Output {
                        name: CStr::from_ptr(buf.as_ptr()).to_string_lossy().into_owned(),
                        location: v[0],
                        index: v[1],
                        component,
                        ty: v[2] as u32,
                        size: v[3],
                    }
                })
                .collect()
        }
    }

    /// The shader objects attached to `program`.
    pub(crate) unsafe fn attached_shaders(&self, program: u32) -> Vec<u32> {
        // SAFETY: contract of the callers; the list is sized as GL is told.
        unsafe {
            let n = self.program_int(program, GL_ATTACHED_SHADERS).max(0);
            let mut list = vec![0u32; n as usize];
            let mut count = 0;
            (self.get_attached_shaders)(program, n, &mut count, list.as_mut_ptr());
            list.truncate(count.max(0) as usize);
            list
        }
    }

    unsafe fn fragment_shader(&self, program: u32) -> Result<u32, String> {
        // SAFETY: contract of the callers.
        unsafe {
            let fragment: Vec<u32> = self
                .attached_shaders(program)
                .into_iter()
                .filter(|&s| self.shader_int(s, GL_SHADER_TYPE) == GL_FRAGMENT_SHADER as i32)
                .collect();
            match fragment[..] {
                [fs] => Ok(fs),
                [] => Err("the program has no attached fragment shader".into()),
                _ => Err("the program links several fragment shaders".into()),
            }
        }
    }

    pub(crate) unsafe fn shader_source(&self, shader: u32) -> Option<String> {
        // SAFETY: contract of the callers; the buffer is sized as GL is told.
        unsafe {
            let len = self.shader_int(shader, GL_SHADER_SOURCE_LENGTH);
            if len <= 1 {
                return None;
            }
            let mut buf = vec![0 as c_char; len as usize];
            let mut got = 0;
            (self.get_shader_source)(shader, len, &mut got, buf.as_mut_ptr());
            Some(CStr::from_ptr(buf.as_ptr()).to_string_lossy().into_owned())
        }
    }

    /// A compiled fragment shader of `source`, or None (deleted) when it
    /// does not compile.
    unsafe fn compile(&self, source: &str) -> Option<u32> {
        // SAFETY: contract of the callers.
        unsafe { self.compile_as(GL_FRAGMENT_SHADER, source) }
    }

    /// A compiled shader of type `shader_type` from `source`, or None
    /// (deleted) when it does not compile.
    pub(crate) unsafe fn compile_as(&self, shader_type: u32, source: &str) -> Option<u32> {
        // SAFETY: contract of the callers; one string of the given length.
        unsafe {
            let s = (self.create_shader)(shader_type);
            if s == 0 {
                return None;
            }
            let ptr = source.as_ptr() as *const c_char;
            let len = source.len() as i32;
            (self.shader_source)(s, 1, &ptr, &len);
            (self.compile_shader)(s);
            if self.shader_int(s, GL_COMPILE_STATUS) == 0 {
                (self.delete_shader)(s);
                return None;
            }
            Some(s)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn declared(expr: &str, ty: &'static str) -> Copies {
        Copies::Declared {
            ty,
            expr: expr.to_owned(),
        }
    }

    #[test]
    fn gl_frag_data_0_is_copied_to_its_elements_5_to_7() {
        let src = "#version 130\nvoid main() { gl_FragData[0] = vec4(1.0); }\n";
        let out = duplicate_output(src, &Copies::FragData);
        assert!(
            out.contains("    gl_FragData[7] = gl_FragData[0];\n"),
            "{out}"
        );
        assert!(
            out.contains("    gl_FragData[5] = gl_FragData[0];\n"),
            "{out}"
        );
        assert!(!out.contains(COPY_PREFIX), "{out}");
        assert!(frag_data_only_element_zero(src));
        assert!(frag_data_only_element_zero("gl_FragData [ 0 ] = c;"));
        assert!(!frag_data_only_element_zero(
            "gl_FragData[0] = c; gl_FragData[1] = d;"
        ));
        assert!(!frag_data_only_element_zero("gl_FragData[i] = c;"));
        assert!(!frag_data_only_element_zero(
            "#define OUT gl_FragData\nOUT[6] = c;"
        ));
    }

    #[test]
    fn main_is_renamed_after_the_version_line_and_the_copies_appended() {
        let src = "// a comment\n#version 330 core\nlayout(location = 0) out vec4 color;\nvoid main() { color = vec4(1.0); }\n";
        let out = duplicate_output(src, &declared("color", "vec4"));
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines[1], "#version 330 core");
        assert_eq!(lines[2], "#define main gls_stereo_user_main");
        assert!(out.contains("out vec4 gls_stereo_copy7;"));
        assert!(out.contains("out vec4 gls_stereo_copy5;"));
        assert!(out.contains("gls_stereo_copy6 = color;"));
        assert!(out.contains("#undef main\n"));
        assert!(out.ends_with("}\n"));
    }

    #[test]
    fn a_source_without_version_gets_the_define_first() {
        let out = duplicate_output(
            "out ivec4 c[2];\nvoid main(){c[0]=ivec4(1);}",
            &declared("c[0]", "ivec4"),
        );
        assert!(out.starts_with("#define main gls_stereo_user_main\nout ivec4 c[2];"));
        assert!(out.contains("gls_stereo_copy7 = c[0];"));
        assert!(out.contains("out ivec4 gls_stereo_copy7;"));
    }

    #[test]
    fn a_version_line_without_newline_keeps_the_define_on_its_own_line() {
        let out = duplicate_output("#version 130", &declared("c", "vec4"));
        assert!(out.starts_with("#version 130\n#define main gls_stereo_user_main\n"));
    }

    #[test]
    fn a_version_directive_may_have_blanks_around_the_hash() {
        let src = "// c\n  #  version 330 core\nout vec4 c;\nvoid main(){c=vec4(1.0);}\n";
        let out = duplicate_output(src, &declared("c", "vec4"));
        assert!(
            out.starts_with("// c\n  #  version 330 core\n#define main gls_stereo_user_main\n"),
            "{out}"
        );
        assert!(is_version_directive("#\tversion 450\r\n"));
        assert!(!is_version_directive("#versions 450\n"));
        assert!(!is_version_directive("// #version 450\n"));
    }

    #[test]
    fn outputs_sharing_location_0_are_copied_in_their_components() {
        let part = |name, gl_type, component| Part {
            name,
            gl_type,
            component,
        };
        // One variable from component 0: itself, as before.
        assert_eq!(
            copy_of(&[part("c[0]", 0x8B52, 0)]),
            Ok(("vec4", "c[0]".to_owned()))
        );
        // Two halves, listed in either order.
        let halves = [part("ba", 0x8B50, 2), part("rg", 0x8B50, 0)];
        assert_eq!(copy_of(&halves), Ok(("vec4", "vec4(rg, ba)".to_owned())));
        // A gap before (and after) a variable in component 1.
        assert_eq!(
            copy_of(&[part("g", 0x1405, 1)]),
            Ok(("uvec2", "uvec2(uint(0), g)".to_owned()))
        );
        assert_eq!(
            copy_of(&[part("r", 0x1404, 0), part("b", 0x1404, 2)]),
            Ok(("ivec3", "ivec3(r, int(0), b)".to_owned()))
        );
        // What GLSL would not link anyway is refused with a reason.
        let mixed = copy_of(&[part("r", 0x1406, 0), part("g", 0x1404, 1)]);
        assert!(mixed.unwrap_err().contains("mix float and int"));
        let past = copy_of(&[part("v", 0x8B51, 2)]);
        assert!(past.unwrap_err().contains("past the fourth"));
        let overlap = copy_of(&[part("a", 0x8B50, 0), part("b", 0x1406, 1)]);
        assert!(overlap.unwrap_err().contains("b overlaps"));
        let mat = copy_of(&[part("m", 0x8B5C, 0)]);
        assert!(mat.unwrap_err().contains("type 0x8b5c"));
    }

    #[test]
    fn output_types_map_to_glsl() {
        assert_eq!(glsl_type(0x8B52), Some("vec4"));
        assert_eq!(glsl_type(0x8DC8), Some("uvec4"));
        assert_eq!(glsl_type(0x1406), Some("float"));
        assert_eq!(glsl_type(0x8B5C), None); // mat4
    }
}
