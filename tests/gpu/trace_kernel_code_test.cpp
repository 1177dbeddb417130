// What the trace kernel's SPIR-V may and may not declare, read from the code itself.
#include <algorithm>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "gpu/trace_pipeline.h"

namespace vitrum::testing {
namespace {

// From the SPIR-V specification (section 3): the magic number, OpVariable's opcode and the
// storage classes checked below.
constexpr std::uint32_t kSpirvMagic = 0x07230203u;
constexpr std::uint32_t kOpVariable = 59;
constexpr std::uint32_t kUniformConstant = 0;  // images, texel buffers
constexpr std::uint32_t kUniform = 2;          // uniform buffers
constexpr std::uint32_t kPushConstant = 9;
constexpr std::uint32_t kStorageBuffer = 12;

// The storage class of every OpVariable in `code`.
std::vector<std::uint32_t> variableStorageClasses(std::span<const std::uint32_t> code) {
    std::vector<std::uint32_t> classes;
    for (std::size_t i = 5; i < code.size();) {  // after the 5-word header
        const std::uint32_t words = code[i] >> 16, opcode = code[i] & 0xFFFFu;
        if (words == 0 || i + words > code.size()) {
            ADD_FAILURE() << "malformed instruction at word " << i;
            break;
        }
        if (opcode == kOpVariable) classes.push_back(code[i + 3]);  // result type, result id, class
        i += words;
    }
    return classes;
}

// lavapipe 22.3 folds the values of uniform-buffer words that decide branches into a kernel and
// compiles that variant when a dispatch is recorded, every dispatch: 5 ms each from Mesa's disk
// cache, over 0.5 s without one (docs/gpu-design.md, "Uniform inlining"). So trace.comp reads its
// render parameters from a texel buffer. Every build of it must keep to that: no uniform buffer,
// no push constants.
TEST(TraceKernelCode, DeclaresNoUniformBufferOrPushConstantsForLavapipeToInline) {
    for (StatisticsSums sums : {StatisticsSums::atomics, StatisticsSums::subgroupAdd}) {
        SCOPED_TRACE(sums == StatisticsSums::atomics ? "without subgroup operations" : "with subgroup operations");
        const auto code = traceKernelCode(sums);
        ASSERT_GT(code.size(), 5u);
        ASSERT_EQ(code[0], kSpirvMagic);
        const auto classes = variableStorageClasses(code);
        auto has = [&](std::uint32_t storageClass) {
            return std::find(classes.begin(), classes.end(), storageClass) != classes.end();
        };
        EXPECT_FALSE(has(kUniform));
        EXPECT_FALSE(has(kPushConstant));
        // The scan sees the kernel's buffers: its texel buffers and its storage buffers.
        EXPECT_TRUE(has(kUniformConstant));
        EXPECT_TRUE(has(kStorageBuffer));
    }
}

}  // namespace
}  // namespace vitrum::testing
