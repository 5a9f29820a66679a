#version 330 core
// A quad covering the viewport (the picture's rectangle), drawn as a 4-vertex triangle strip
// with no vertex buffer: corners come from gl_VertexID.
out vec2 v_uv;
void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1));
    // uv (0, 0) is the image's top-left pixel: texture row 0 is the image's top row.
    v_uv = vec2(corner.x, 1.0 - corner.y);
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
