//! The picture on the GPU: one float texture holding the current image and the shader program
//! that tone maps it (picture.vert / picture.frag) onto the picture's rectangle.
//!
//! OpenGL through `glow` is an `unsafe` API (raw driver calls), so this module is the viewer's
//! one exception to the workspace's `unsafe_code = "deny"`: every call below only passes objects
//! this module created on the same context, sizes it checked, and slices whose lengths match.
#![allow(unsafe_code)]

use eframe::glow::{self, HasContext};
use pathtrace::film::ToneMap;

/// GPU objects of the picture; create and use them on the window's GL context only.
pub struct GlPicture {
    program: glow::Program,
    vertex_array: glow::VertexArray,
    texture: glow::Texture,
    u_image: Option<glow::UniformLocation>,
    u_scale: Option<glow::UniformLocation>,
    u_tonemap: Option<glow::UniformLocation>,
    size: (u32, u32),
}

impl GlPicture {
    /// Compiles the shaders and creates the (empty) texture.
    pub fn new(gl: &glow::Context) -> Result<Self, String> {
        // SAFETY: plain object creation on the current context; every handle is checked, and
        // shaders are deleted once linked (the program keeps them alive).
        unsafe {
            let program = gl.create_program()?;
            let sources = [
                (glow::VERTEX_SHADER, include_str!("picture.vert")),
                (glow::FRAGMENT_SHADER, include_str!("picture.frag")),
            ];
            let mut shaders = Vec::new();
            for (kind, source) in sources {
                let shader = gl.create_shader(kind)?;
                gl.shader_source(shader, source);
                gl.compile_shader(shader);
                if !gl.get_shader_compile_status(shader) {
                    return Err(format!("picture shader failed to compile: {}", gl.get_shader_info_log(shader)));
                }
                gl.attach_shader(program, shader);
                shaders.push(shader);
            }
            gl.link_program(program);
            if !gl.get_program_link_status(program) {
                return Err(format!("picture shader failed to link: {}", gl.get_program_info_log(program)));
            }
            for shader in shaders {
                gl.detach_shader(program, shader);
                gl.delete_shader(shader);
            }
            let texture = gl.create_texture()?;
            gl.bind_texture(glow::TEXTURE_2D, Some(texture));
            // Nearest-pixel magnification: zooming in shows individual pixels (and their noise).
            for (param, value) in [
                (glow::TEXTURE_MIN_FILTER, glow::NEAREST),
                (glow::TEXTURE_MAG_FILTER, glow::NEAREST),
                (glow::TEXTURE_WRAP_S, glow::CLAMP_TO_EDGE),
                (glow::TEXTURE_WRAP_T, glow::CLAMP_TO_EDGE),
            ] {
                gl.tex_parameter_i32(glow::TEXTURE_2D, param, value as i32);
            }
            gl.bind_texture(glow::TEXTURE_2D, None);
            Ok(Self {
                u_image: gl.get_uniform_location(program, "u_image"),
                u_scale: gl.get_uniform_location(program, "u_scale"),
                u_tonemap: gl.get_uniform_location(program, "u_tonemap"),
                vertex_array: gl.create_vertex_array()?,
                program,
                texture,
                size: (0, 0),
            })
        }
    }

    /// Replaces the texture's contents with `rgb` (3 floats per pixel, rows from the top).
    pub fn upload(&mut self, gl: &glow::Context, width: u32, height: u32, rgb: &[f32]) {
        if rgb.len() != width as usize * height as usize * 3 || width == 0 || height == 0 {
            return;
        }
        let bytes: Vec<u8> = rgb.iter().flat_map(|v| v.to_ne_bytes()).collect();
        // SAFETY: the texture is ours; `bytes` holds exactly width·height RGB32F texels, and rows
        // of 12·width bytes meet the default 4-byte unpack alignment.
        unsafe {
            gl.bind_texture(glow::TEXTURE_2D, Some(self.texture));
            if self.size == (width, height) {
                let data = glow::PixelUnpackData::Slice(Some(&bytes));
                gl.tex_sub_image_2d(
                    glow::TEXTURE_2D,
                    0,
                    0,
                    0,
                    width as i32,
                    height as i32,
                    glow::RGB,
                    glow::FLOAT,
                    data,
                );
            } else {
                let data = glow::PixelUnpackData::Slice(Some(&bytes));
                let (w, h) = (width as i32, height as i32);
                gl.tex_image_2d(glow::TEXTURE_2D, 0, glow::RGB32F as i32, w, h, 0, glow::RGB, glow::FLOAT, data);
                self.size = (width, height);
            }
            gl.bind_texture(glow::TEXTURE_2D, None);
        }
    }

    /// True once an image was uploaded.
    pub fn has_image(&self) -> bool {
        self.size != (0, 0)
    }

    /// Draws the picture over the current viewport: radiance × `scale`, then `tone_map`, then sRGB.
    pub fn draw(&self, gl: &glow::Context, scale: f32, tone_map: ToneMap) {
        if !self.has_image() {
            return;
        }
        let curve = match tone_map {
            ToneMap::Clamp => 0,
            ToneMap::Aces => 1,
        };
        // SAFETY: binds only objects created in `new`; four vertices from gl_VertexID need no
        // vertex buffer. egui_glow restores its own state after a paint callback.
        unsafe {
            gl.disable(glow::BLEND);
            gl.use_program(Some(self.program));
            gl.active_texture(glow::TEXTURE0);
            gl.bind_texture(glow::TEXTURE_2D, Some(self.texture));
            gl.uniform_1_i32(self.u_image.as_ref(), 0);
            gl.uniform_1_f32(self.u_scale.as_ref(), scale);
            gl.uniform_1_i32(self.u_tonemap.as_ref(), curve);
            gl.bind_vertex_array(Some(self.vertex_array));
            gl.draw_arrays(glow::TRIANGLE_STRIP, 0, 4);
            gl.bind_vertex_array(None);
            gl.bind_texture(glow::TEXTURE_2D, None);
            gl.use_program(None);
        }
    }

    /// Frees the GPU objects.
    pub fn destroy(&self, gl: &glow::Context) {
        // SAFETY: the objects are ours and no longer used after this.
        unsafe {
            gl.delete_program(self.program);
            gl.delete_vertex_array(self.vertex_array);
            gl.delete_texture(self.texture);
        }
    }
}

/// Reads an 8-bit RGB rectangle of the framebuffer being drawn (x, y from its bottom-left corner)
/// and returns its rows from the top, as images store them.
pub fn read_rgb8(gl: &glow::Context, x: i32, y: i32, width: u32, height: u32) -> Vec<u8> {
    let (w, h) = (width as usize, height as usize);
    let mut rgba = vec![0u8; w * h * 4];
    // SAFETY: `rgba` holds exactly width·height RGBA8 pixels with PACK_ALIGNMENT 1.
    unsafe {
        gl.pixel_store_i32(glow::PACK_ALIGNMENT, 1);
        let data = glow::PixelPackData::Slice(Some(&mut rgba));
        gl.read_pixels(x, y, width as i32, height as i32, glow::RGBA, glow::UNSIGNED_BYTE, data);
    }
    // GL rows run bottom-up.
    let mut rgb = Vec::with_capacity(w * h * 3);
    for row in rgba.chunks_exact(w * 4).rev() {
        for px in row.chunks_exact(4) {
            rgb.extend_from_slice(&px[..3]);
        }
    }
    rgb
}
