// The CPU reference's float arithmetic asked of a GPU kernel, by rewriting its SPIR-V before the
// driver sees it. Left to themselves, drivers may fuse a multiply and an add into one FMA (NVIDIA's
// does; lavapipe does not) and may assume that no value is infinite or NaN. The reference is
// built with -ffp-contract=off on IEEE floats, the triangle test is watertight only when its edge
// functions round alike on both sides of an edge, and the hard cases rely on infinities and NaNs
// being what IEEE says (docs/gpu-design.md, "Arithmetic as the CPU does it").
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace vitrum {

struct FloatSemantics {
    // Adds the SignedZeroInfNanPreserve execution mode (32-bit) to every entry point: only where
    // the device reports shaderSignedZeroInfNanPreserveFloat32. Core in SPIR-V 1.4, so no
    // extension is declared: the kernels are built for Vulkan 1.2, SPIR-V 1.5.
    bool preserveInfNan = false;
};

// A copy of `spirv` with an OpDecorate ... NoContraction for each result of OpFAdd, OpFSub,
// OpFMul, OpDot and the vector and matrix products that lacks one, after the module's other
// annotations; and with `semantics`. Throws std::invalid_argument where the words are not a
// SPIR-V module.
std::vector<std::uint32_t> withCpuFloatSemantics(std::span<const std::uint32_t> spirv, FloatSemantics semantics);

}  // namespace vitrum
