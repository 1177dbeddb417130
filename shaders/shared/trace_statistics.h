// The statistics of a render, written once: trace.comp counts them (shaders/statistics.glsl), the
// host adds up the dispatches' counters and writes them to --stats (host/stats/trace_counts.h),
// and the CPU reference counts those it can measure.
//
// X(index, name, combine, group, key, measured):
//   index    the counter's place in the statistics buffer (host/gpu/vulkan_renderer.cpp zeroes it
//            before a dispatch and reads it after; the host sums in 64 bits)
//   name     the counter in GLSL's TraceCounters and C++'s TraceCounts
//   combine  Sum over invocations and dispatches, or Max (all of these come last, from
//            kStatFirstMax on)
//   group    where --stats writes it: rays.KEY, limits.KEY, KEY (top), or not at all (none: the
//            host's own use)
//   measured Both backends, or Gpu only (the CPU reference writes no value for it)
#ifndef VITRUM_TRACE_STATISTICS_H
#define VITRUM_TRACE_STATISTICS_H

#include "language.h"

#define VITRUM_TRACE_STATISTICS(X)                                                        \
    X(0, primaryRays, Sum, rays, primary, Both)                                           \
    X(1, shadowRays, Sum, rays, shadow, Both)                                             \
    X(2, reflectionRays, Sum, rays, reflection, Both)                                     \
    X(3, refractionRays, Sum, rays, refraction, Both)                                     \
    /* pixels of this tile that need another dispatch (after the first: to restart) */    \
    X(4, unfinishedPixels, Sum, none, unfinished_pixels, Gpu)                             \
    /* the main loop ended without a reason of the kernel's: the driver's loop limit */   \
    X(5, loopLimitSuspected, Sum, limits, loop_limit_suspected, Both)                     \
    X(6, traversalStackOverflows, Sum, limits, traversal_stack_overflow, Both)            \
    X(7, depthLimitHits, Sum, limits, depth_limit, Both)                                  \
    X(8, nodeVisits, Sum, top, node_visits, Both)                                         \
    /* steps of trace.comp's loop that each lane ran, all pixels */                       \
    X(9, loopSteps, Sum, top, loop_steps, Gpu)                                            \
    /* branches dropped: the pending-ray stack is full */                                 \
    X(10, rayStackOverflows, Sum, limits, ray_stack_overflow, Both)                       \
    X(11, mediumStackOverflows, Sum, limits, medium_stack_overflow, Both)                 \
    /* branches skipped by min_weight */                                                  \
    X(12, weightCuts, Sum, limits, weight_cuts, Both)                                     \
    X(13, totalInternalReflections, Sum, top, total_internal_reflections, Both)           \
    /* rays leaving the scene inside an absorbing medium */                               \
    X(14, absorbedEscapes, Sum, top, absorbed_escapes, Both)                              \
    /* glass hits where surfaces of other objects touch */                                \
    X(15, touchingInterfaces, Sum, top, touching_interfaces, Both)                        \
    /* a ray left an object it was not inside, or entered one it was */                   \
    X(16, inconsistentMedia, Sum, limits, inconsistent_media, Both)                       \
    /* glass hits whose touching surfaces were looked for */                              \
    X(17, touchingProbes, Sum, top, touching_probes, Both)                                \
    /* steps of first attempts given up (the resumable kernel restarts them) */           \
    X(18, restartedSteps, Sum, top, restarted_steps, Gpu)                                 \
    /* steps the SIMD groups ran, as the budget counts them: each group once */           \
    X(19, groupLoopSteps, Sum, top, group_loop_steps, Gpu)                                \
    /* surfaces of a medium inside one of higher priority, passed without an interface */ \
    X(20, falseHits, Sum, top, false_hits, Both)                                          \
    /* white rays replaced by their wavelength samples at a dispersive glass */           \
    X(21, dispersionSplits, Sum, top, dispersion_splits, Both)                            \
    /* rays going on through a partly covered surface (Material::coverage) */             \
    X(22, passThroughRays, Sum, rays, pass_through, Both)                                 \
    /* most loop steps one pixel needed, over all its dispatches */                       \
    X(23, maxPixelLoopSteps, Max, top, max_pixel_loop_steps, Gpu)                         \
    /* deepest ray traced (primary: 0) */                                                 \
    X(24, maxRayDepth, Max, top, max_ray_depth, Both)                                     \
    /* most media one ray was inside */                                                   \
    X(25, maxMediumDepth, Max, top, max_medium_depth, Both)

VITRUM_GPU_BEGIN
VITRUM_CONST uint kStatFirstMax = 23u;  // the first Max
VITRUM_CONST uint kStatCount = 26u;
// Not a statistic, but zeroed with them: the dispatch's next unit of work, which each subgroup
// takes as it starts (schedule.glsl's takeUnit).
VITRUM_CONST uint kWorkCursor = 26u;
VITRUM_CONST uint kDispatchCounterCount = 27u;  // the buffer's uints: the statistics and the cursor
VITRUM_GPU_END

#endif
