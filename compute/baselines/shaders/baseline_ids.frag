#version 460
// Graphics baseline (tests and benchmarks only): writes the triangle's id.
layout(location = 0) flat in uint triangle_id;
layout(location = 0) out uint id_out;

void main() {
  id_out = triangle_id;
}
