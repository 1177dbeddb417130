// The buffers of trace.comp; layouts from shared/gpu_types.h. Binding numbers match
// host/gpu/trace_pipeline.cpp (kBinding*).
#ifndef VITRUM_BINDINGS_GLSL
#define VITRUM_BINDINGS_GLSL

layout(std140, set = 0, binding = 0) uniform Params { RenderParams params; };
layout(std430, set = 0, binding = 1) readonly buffer Nodes { BvhNode nodes[]; };
layout(std430, set = 0, binding = 2) readonly buffer Vertices { TriangleVertices vertices[]; };
layout(std430, set = 0, binding = 3) readonly buffer Shading { TriangleShading shading[]; };
layout(std430, set = 0, binding = 4) readonly buffer Materials { GpuMaterial materials[]; };
layout(std430, set = 0, binding = 5) readonly buffer Lights { GpuLight lights[]; };
layout(std430, set = 0, binding = 6) readonly buffer Textures { TextureInfo textures[]; };
layout(std430, set = 0, binding = 7) readonly buffer Texels { float texels[]; };  // RGB, packed
layout(std430, set = 0, binding = 8) readonly buffer ObjectMaterials { uint objectMaterial[]; };
layout(std430, set = 0, binding = 9) writeonly buffer Pixels { vec4 pixels[]; };
layout(std430, set = 0, binding = 10) buffer States { TraceState states[]; };
layout(std430, set = 0, binding = 11) buffer Stats { uint stats[]; };
layout(std430, set = 0, binding = 12) buffer PendingRays { PendingRay pendingRays[]; };  // kPendingRayCapacity a pixel
layout(std430, set = 0, binding = 13) buffer TraversalStacks { uint traversalStacks[]; };  // kTraversalStackSize a pixel

#endif
