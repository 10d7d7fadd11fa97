#version 450
// Work that takes a while on lavapipe and cannot be optimized away: each workgroup adds 1 to a
// counter 60,000 times (lavapipe ends an invocation's loops after about 65,535 iterations in
// all, so a dispatch's length is set by its number of workgroups). For
// tests/frame_timing_test.cpp, which checks that timestamps around it are taken when reached.
layout(local_size_x = 1) in;

layout(set = 0, binding = 0) buffer Counter {
  uint count;
} counter;

void main() {
  for (uint i = 0u; i < 60000u; ++i) atomicAdd(counter.count, 1u);
}
