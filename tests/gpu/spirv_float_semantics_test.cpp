// withCpuFloatSemantics (host/gpu/spirv_float_semantics.h) read back from the words it writes:
// every multiply and add of the real kernels decorated once, infinities and NaNs kept where asked,
// nothing else changed. That a driver then computes what the CPU does is for the GPU tests to see
// (GlslOptics.RandomCasesMatchCpuReferenceAndPhysics holds the reflected direction to the bit).
#include <cstdint>
#include <map>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "gpu/spirv_float_semantics.h"
#include "gpu/trace_pipeline.h"

namespace vitrum::testing {
namespace {

// From the SPIR-V specification, section 3.
constexpr std::uint32_t kOpEntryPoint = 15, kOpExecutionMode = 16, kOpCapability = 17;
constexpr std::uint32_t kOpTypeVoid = 19;
constexpr std::uint32_t kOpDecorate = 71;
constexpr std::uint32_t kOpFAdd = 129, kOpFSub = 131, kOpFMul = 133;
constexpr std::uint32_t kOpVectorTimesScalar = 142, kOpDot = 148;  // and the matrix products between

bool multipliesOrAdds(std::uint32_t opcode) {
    return opcode == kOpFAdd || opcode == kOpFSub || opcode == kOpFMul ||
           (opcode >= kOpVectorTimesScalar && opcode <= kOpDot);
}
constexpr std::uint32_t kNoContraction = 42;
constexpr std::uint32_t kSignedZeroInfNanPreserve = 4461, kSignedZeroInfNanPreserveCapability = 4466;

struct Instruction {
    std::uint32_t opcode;
    std::vector<std::uint32_t> operands;
};

std::vector<Instruction> instructions(const std::vector<std::uint32_t>& code) {
    std::vector<Instruction> list;
    for (std::size_t i = 5; i < code.size();) {
        const std::uint32_t words = code[i] >> 16;
        if (words == 0 || i + words > code.size()) {
            ADD_FAILURE() << "malformed instruction at word " << i;
            break;
        }
        list.push_back({code[i] & 0xFFFFu, std::vector<std::uint32_t>(code.begin() + i + 1, code.begin() + i + words)});
        i += words;
    }
    return list;
}

bool isNoContraction(const Instruction& in) {
    return in.opcode == kOpDecorate && in.operands.size() == 2 && in.operands[1] == kNoContraction;
}
bool isInfNanCapability(const Instruction& in) {
    return in.opcode == kOpCapability && in.operands == std::vector<std::uint32_t>{kSignedZeroInfNanPreserveCapability};
}
bool isInfNanMode(const Instruction& in) {
    return in.opcode == kOpExecutionMode && in.operands.size() == 3 && in.operands[1] == kSignedZeroInfNanPreserve &&
           in.operands[2] == 32;
}
bool isAdded(const Instruction& in) { return isNoContraction(in) || isInfNanCapability(in) || isInfNanMode(in); }

std::vector<std::uint32_t> traceKernel(StatisticsSums sums) {
    const auto code = traceKernelCode(sums);
    return {code.begin(), code.end()};
}

TEST(SpirvFloatSemantics, EveryMultiplyAndAddIsDecoratedOnceInfinitiesKeptAndNothingElseChanges) {
    for (StatisticsSums sums : {StatisticsSums::atomics, StatisticsSums::subgroupAdd}) {
        const std::vector<std::uint32_t> before = traceKernel(sums);
        const std::vector<std::uint32_t> after = withCpuFloatSemantics(before, {.preserveInfNan = true});
        ASSERT_EQ(std::vector<std::uint32_t>(after.begin(), after.begin() + 5),
                  std::vector<std::uint32_t>(before.begin(), before.begin() + 5))
            << "the header, its id bound too, stays";

        std::map<std::uint32_t, int> decorations, modes;
        std::vector<std::uint32_t> entryPoints;
        std::vector<Instruction> rest;
        bool typesSeen = false, entryPointSeen = false;
        int capabilities = 0;
        for (const Instruction& in : instructions(after)) {
            if (in.opcode == kOpTypeVoid) typesSeen = true;
            if (in.opcode == kOpEntryPoint) {
                entryPointSeen = true;
                entryPoints.push_back(in.operands[1]);
            }
            if (isNoContraction(in)) {
                EXPECT_FALSE(typesSeen) << "a decoration after the types";
                ++decorations[in.operands[0]];
            } else if (isInfNanCapability(in)) {
                EXPECT_FALSE(entryPointSeen) << "a capability after the entry points";
                ++capabilities;
            } else if (isInfNanMode(in)) {
                EXPECT_TRUE(entryPointSeen) << "an execution mode before its entry point";
                ++modes[in.operands[0]];
            } else {
                rest.push_back(in);
            }
        }
        EXPECT_EQ(capabilities, 1);
        ASSERT_EQ(entryPoints.size(), 1u);
        EXPECT_EQ(modes, (std::map<std::uint32_t, int>{{entryPoints[0], 1}}));
        std::vector<Instruction> original;
        for (const Instruction& in : instructions(before))
            if (!isAdded(in)) original.push_back(in);
        ASSERT_EQ(rest.size(), original.size());
        for (std::size_t i = 0; i < rest.size(); ++i) {
            ASSERT_EQ(rest[i].opcode, original[i].opcode) << "instruction " << i;
            ASSERT_EQ(rest[i].operands, original[i].operands) << "instruction " << i;
        }

        std::size_t arithmetic = 0;
        for (const Instruction& in : rest) {
            if (!multipliesOrAdds(in.opcode)) continue;
            ++arithmetic;
            EXPECT_EQ(decorations[in.operands[1]], 1) << "result %" << in.operands[1] << " of opcode " << in.opcode;
        }
        EXPECT_GT(arithmetic, 100u) << "the trace kernel does more float arithmetic than that";
        EXPECT_EQ(decorations.size(), arithmetic) << "only multiplies and adds are decorated";
        EXPECT_EQ(withCpuFloatSemantics(after, {.preserveInfNan = true}), after) << "a second pass adds nothing";

        // Where the device cannot keep them, only the decorations are added.
        const std::vector<std::uint32_t> decoratedOnly = withCpuFloatSemantics(before, {.preserveInfNan = false});
        EXPECT_EQ(decoratedOnly.size(), before.size() + 3 * arithmetic);
        for (const Instruction& in : instructions(decoratedOnly)) EXPECT_FALSE(isInfNanCapability(in) || isInfNanMode(in));
    }
}

TEST(SpirvFloatSemantics, RefusesWordsThatAreNoModule) {
    EXPECT_THROW(withCpuFloatSemantics(std::vector<std::uint32_t>{1, 2, 3, 4, 5}, {}), std::invalid_argument);
    std::vector<std::uint32_t> overrun = traceKernel(StatisticsSums::atomics);
    overrun.push_back((9u << 16) | kOpFAdd);  // claims more words than are left
    EXPECT_THROW(withCpuFloatSemantics(overrun, {}), std::invalid_argument);
}

}  // namespace
}  // namespace vitrum::testing
