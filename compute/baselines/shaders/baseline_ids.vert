#version 460
// Graphics baseline (tests and benchmarks only): positions arrive already in clip space, three
// vertices per triangle (no index buffer), so a triangle's id is gl_VertexIndex / 3.
layout(location = 0) in vec4 clip_position;
layout(location = 0) flat out uint triangle_id;

void main() {
  gl_Position = clip_position;
  triangle_id = uint(gl_VertexIndex) / 3u;
}
