#version 460
// The depth pass: one triangle over the whole image (its vertices from gl_VertexIndex, no
// vertex buffer); the fragment shader writes each pixel's depth.

void main() {
  const vec2 corner = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);  // (0,0), (2,0), (0,2)
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
