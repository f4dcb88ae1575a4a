#version 460
// Between two bounces on one rank (one invocation): the queues the bounce appended become the ones the
// next consumes. Their lengths and the dispatch sizes that launch the next bounce's stages stay on the
// device, so a whole sample pass is one submission (core/render/PathTracerWaves.cpp).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "shared/path.h"

layout(local_size_x = 1) in;

layout(push_constant) uniform Push { QueueAdvanceParams params; };

layout(buffer_reference, std430, buffer_reference_align = 16) buffer CountersRef { PathCounters counters; };

DispatchSize groups(uint items, uint workgroup) { return DispatchSize((items + workgroup - 1u) / workgroup, 1u, 1u); }

void main() {
    CountersRef c = CountersRef(params.counters);
    c.counters.pathsTraced += c.counters.pathCount;
    c.counters.shadowsTraced += c.counters.shadowCount;
    uint paths = min(c.counters.nextPaths, params.capacity);
    uint shadows = min(c.counters.shadowRays, params.capacity);
    c.counters.nextPaths = 0u;
    c.counters.shadowRays = 0u;
    c.counters.pathCount = paths;
    c.counters.shadowCount = shadows;
    c.counters.pathGroups = groups(paths, params.stageWorkgroup);
    c.counters.shadowGroups = groups(shadows, params.stageWorkgroup);
    c.counters.pathTraceGroups = groups(paths, params.traceWorkgroup);
    c.counters.shadowTraceGroups = groups(shadows, params.traceWorkgroup);
}
