//! The GL enumerants the library uses (values from the Khronos registry).
#![allow(missing_docs)]

pub const GL_NONE: u32 = 0;
pub const GL_FRONT_LEFT: u32 = 0x0400;
pub const GL_FRONT_RIGHT: u32 = 0x0401;
pub const GL_BACK_LEFT: u32 = 0x0402;
pub const GL_BACK_RIGHT: u32 = 0x0403;
pub const GL_FRONT: u32 = 0x0404;
pub const GL_BACK: u32 = 0x0405;
pub const GL_LEFT: u32 = 0x0406;
pub const GL_RIGHT: u32 = 0x0407;
pub const GL_FRONT_AND_BACK: u32 = 0x0408;
pub const GL_AUX0: u32 = 0x0409;
pub const GL_AUX3: u32 = 0x040C;
pub const GL_COLOR_ATTACHMENT0: u32 = 0x8CE0;
pub const GL_COLOR_ATTACHMENT31: u32 = 0x8CFF;
pub const GL_DEPTH_ATTACHMENT: u32 = 0x8D00;
pub const GL_STENCIL_ATTACHMENT: u32 = 0x8D20;
pub const GL_DEPTH_STENCIL_ATTACHMENT: u32 = 0x821A;

pub const GL_NO_ERROR: u32 = 0;
pub const GL_INVALID_ENUM: u32 = 0x0500;
pub const GL_INVALID_VALUE: u32 = 0x0501;
pub const GL_INVALID_OPERATION: u32 = 0x0502;
pub const GL_OUT_OF_MEMORY: u32 = 0x0505;
pub const GL_INVALID_FRAMEBUFFER_OPERATION: u32 = 0x0506;

pub const GL_VENDOR: u32 = 0x1F00;
pub const GL_RENDERER: u32 = 0x1F01;
pub const GL_VERSION: u32 = 0x1F02;
pub const GL_EXTENSIONS: u32 = 0x1F03;
pub const GL_MAJOR_VERSION: u32 = 0x821B;
pub const GL_MINOR_VERSION: u32 = 0x821C;
pub const GL_NUM_EXTENSIONS: u32 = 0x821D;
pub const GL_CONTEXT_PROFILE_MASK: u32 = 0x9126;
pub const GL_CONTEXT_COMPATIBILITY_PROFILE_BIT: u32 = 0x2;

pub const GL_STEREO: u32 = 0x0C33;
pub const GL_DOUBLEBUFFER: u32 = 0x0C32;
pub const GL_DRAW_BUFFER: u32 = 0x0C01;
pub const GL_READ_BUFFER: u32 = 0x0C02;
pub const GL_DRAW_BUFFER0: u32 = 0x8825;
pub const GL_DRAW_BUFFER15: u32 = 0x8834;
pub const GL_MAX_DRAW_BUFFERS: u32 = 0x8824;
pub const GL_MAX_TEXTURE_SIZE: u32 = 0x0D33;
pub const GL_MAX_RENDERBUFFER_SIZE: u32 = 0x84E8;
pub const GL_MAX_VIEWPORT_DIMS: u32 = 0x0D3A;
pub const GL_VIEWPORT: u32 = 0x0BA2;
pub const GL_SCISSOR_BOX: u32 = 0x0C10;
pub const GL_MATRIX_MODE: u32 = 0x0BA0;
pub const GL_MODELVIEW: u32 = 0x1700;
pub const GL_PROJECTION: u32 = 0x1701;
pub const GL_PROJECTION_MATRIX: u32 = 0x0BA7;
pub const GL_RED_BITS: u32 = 0x0D52;
pub const GL_GREEN_BITS: u32 = 0x0D53;
pub const GL_BLUE_BITS: u32 = 0x0D54;
pub const GL_ALPHA_BITS: u32 = 0x0D55;
pub const GL_DEPTH_BITS: u32 = 0x0D56;
pub const GL_DEPTH_RANGE: u32 = 0x0B70;
pub const GL_DEPTH_CLEAR_VALUE: u32 = 0x0B73;
pub const GL_STENCIL_BITS: u32 = 0x0D57;

pub const GL_FRAMEBUFFER: u32 = 0x8D40;
pub const GL_READ_FRAMEBUFFER: u32 = 0x8CA8;
pub const GL_DRAW_FRAMEBUFFER: u32 = 0x8CA9;
pub const GL_FRAMEBUFFER_BINDING: u32 = 0x8CA6;
pub const GL_DRAW_FRAMEBUFFER_BINDING: u32 = 0x8CA6;
pub const GL_READ_FRAMEBUFFER_BINDING: u32 = 0x8CAA;
pub const GL_RENDERBUFFER: u32 = 0x8D41;
pub const GL_FRAMEBUFFER_COMPLETE: u32 = 0x8CD5;

pub const GL_TEXTURE_2D: u32 = 0x0DE1;
pub const GL_TEXTURE0: u32 = 0x84C0;
pub const GL_TEXTURE_MIN_FILTER: u32 = 0x2801;
pub const GL_TEXTURE_MAG_FILTER: u32 = 0x2800;
pub const GL_TEXTURE_WRAP_S: u32 = 0x2802;
pub const GL_TEXTURE_WRAP_T: u32 = 0x2803;
pub const GL_TEXTURE_MAX_LEVEL: u32 = 0x813D;
pub const GL_NEAREST: u32 = 0x2600;
pub const GL_LINEAR: u32 = 0x2601;
pub const GL_CLAMP_TO_EDGE: u32 = 0x812F;
pub const GL_RGBA: u32 = 0x1908;
pub const GL_RGBA8: u32 = 0x8058;
pub const GL_R8: u32 = 0x8229;
pub const GL_RED: u32 = 0x1903;
pub const GL_RGB8: u32 = 0x8051;
pub const GL_UNSIGNED_BYTE: u32 = 0x1401;
pub const GL_FLOAT: u32 = 0x1406;
pub const GL_DEPTH_COMPONENT: u32 = 0x1902;
pub const GL_DEPTH24_STENCIL8: u32 = 0x88F0;
pub const GL_DEPTH_COMPONENT24: u32 = 0x81A6;
pub const GL_STENCIL_INDEX8: u32 = 0x8D48;
pub const GL_PACK_ALIGNMENT: u32 = 0x0D05;
pub const GL_PACK_ROW_LENGTH: u32 = 0x0D02;
pub const GL_UNPACK_ALIGNMENT: u32 = 0x0CF5;
pub const GL_UNPACK_ROW_LENGTH: u32 = 0x0CF2;

pub const GL_COLOR_BUFFER_BIT: u32 = 0x4000;
pub const GL_DEPTH_BUFFER_BIT: u32 = 0x0100;
pub const GL_STENCIL_BUFFER_BIT: u32 = 0x0400;
pub const GL_SCISSOR_TEST: u32 = 0x0C11;
pub const GL_TRIANGLES: u32 = 0x0004;
pub const GL_BLEND: u32 = 0x0BE2;
pub const GL_DEPTH_TEST: u32 = 0x0B71;
pub const GL_STENCIL_TEST: u32 = 0x0B90;
pub const GL_CULL_FACE: u32 = 0x0B44;
pub const GL_DITHER: u32 = 0x0BD0;
pub const GL_FRAMEBUFFER_SRGB: u32 = 0x8DB9;
pub const GL_COLOR_LOGIC_OP: u32 = 0x0BF2;
pub const GL_RASTERIZER_DISCARD: u32 = 0x8C89;

pub const GL_VERTEX_SHADER: u32 = 0x8B31;
pub const GL_FRAGMENT_SHADER: u32 = 0x8B30;
pub const GL_COMPILE_STATUS: u32 = 0x8B81;
pub const GL_LINK_STATUS: u32 = 0x8B82;
pub const GL_INFO_LOG_LENGTH: u32 = 0x8B84;

pub const GL_PIXEL_PACK_BUFFER: u32 = 0x88EB;
pub const GL_STREAM_READ: u32 = 0x88E1;
pub const GL_MAP_READ_BIT: u32 = 0x0001;
pub const GL_SYNC_GPU_COMMANDS_COMPLETE: u32 = 0x9117;
pub const GL_SYNC_FLUSH_COMMANDS_BIT: u32 = 0x0001;
pub const GL_TIMEOUT_EXPIRED: u32 = 0x911B;
pub const GL_WAIT_FAILED: u32 = 0x911D;

pub const GL_TRUE: u8 = 1;
pub const GL_FALSE: u8 = 0;
