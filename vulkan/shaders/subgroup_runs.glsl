// Work items walked in subgroup-contiguous runs: each subgroup takes a run of gl_SubgroupSize * per_invocation
// consecutive items, a subgroup-wide step at a time, then jumps past every other subgroup's run. A SIMD CPU
// device (lavapipe runs one subgroup as one 8-wide loop) then reads and writes memory in sequence, and push
// constants read before the loop are gathered once per run instead of once per item (on lavapipe keys.comp is
// 1.7x faster this way than with one item per invocation). With one worker thread the items are still visited
// in index order, a subgroup-wide step at a time, as with one item per invocation. Every item in
// [0, count) is visited exactly once for any dispatch size: Vulkan 1.2 (SPIR-V 1.5) subgroups are full and
// their size divides the workgroup size. The includer enables GL_KHR_shader_subgroup_basic.

struct SubgroupRuns {
  uint first;   // this subgroup's first run starts here
  uint size;    // items per run
  uint stride;  // from one of its runs to the next
};

SubgroupRuns ThisSubgroupsRuns(uint per_invocation) {
  SubgroupRuns runs;
  runs.size = gl_SubgroupSize * per_invocation;
  runs.first = (gl_WorkGroupID.x * gl_NumSubgroups + gl_SubgroupID) * runs.size;
  runs.stride = gl_NumWorkGroups.x * gl_NumSubgroups * runs.size;
  return runs;
}
