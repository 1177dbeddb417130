#include "gpu/spirv_float_semantics.h"

#include <map>
#include <set>
#include <stdexcept>
#include <unordered_set>

namespace vitrum {
namespace {

// From the SPIR-V specification, section 3.
constexpr std::uint32_t kMagic = 0x07230203;
constexpr std::uint32_t kHeaderWords = 5;
constexpr std::uint32_t kOpCapability = 17;
constexpr std::uint32_t kOpEntryPoint = 15;
constexpr std::uint32_t kOpExecutionMode = 16;
constexpr std::uint32_t kOpExecutionModeId = 331;
constexpr std::uint32_t kOpDecorate = 71;
constexpr std::uint32_t kNoContraction = 42;
constexpr std::uint32_t kSignedZeroInfNanPreserve = 4461;            // the execution mode
constexpr std::uint32_t kSignedZeroInfNanPreserveCapability = 4466;  // its capability

// What comes before the types in a module's logical layout (section 2.4): capabilities,
// extensions, imports, memory model, entry points, execution modes, debug names and annotations.
bool isPreamble(std::uint32_t opcode) {
    switch (opcode) {
        case 2: case 3: case 4: case 5: case 6: case 7:  // OpSourceContinued .. OpString
        case 10: case 11: case 14: case 15: case 16: case 17:  // OpExtension .. OpCapability
        case 71: case 72: case 73: case 74: case 75:  // OpDecorate .. OpGroupMemberDecorate
        case 330: case 331: case 332:  // OpModuleProcessed, OpExecutionModeId, OpDecorateId
        case 5632: case 5633:  // OpDecorateString, OpMemberDecorateString
            return true;
        default:
            return false;
    }
}

// The instructions a driver could fuse into a multiply-add: each has its result id in word 2.
bool isContractible(std::uint32_t opcode) {
    switch (opcode) {
        case 129: case 131: case 133:  // OpFAdd, OpFSub, OpFMul
        case 142: case 143: case 144: case 145: case 146: case 147: case 148:  // OpVectorTimesScalar .. OpDot
            return true;
        default:
            return false;
    }
}

std::uint32_t instructionHead(std::uint32_t words, std::uint32_t opcode) { return (words << 16) | opcode; }

}  // namespace

std::vector<std::uint32_t> withCpuFloatSemantics(std::span<const std::uint32_t> spirv, FloatSemantics semantics) {
    if (spirv.size() < kHeaderWords || spirv[0] != kMagic)
        throw std::invalid_argument("withCpuFloatSemantics: not a SPIR-V module");
    std::size_t capabilitiesEnd = kHeaderWords, modesEnd = 0, typesBegin = 0;
    bool hasInfNanCapability = false;
    std::vector<std::uint32_t> entryPoints;
    std::set<std::uint32_t> preservingEntryPoints;
    std::unordered_set<std::uint32_t> decorated;
    std::vector<std::uint32_t> contractible;
    for (std::size_t at = kHeaderWords; at < spirv.size();) {
        const std::uint32_t words = spirv[at] >> 16, opcode = spirv[at] & 0xffffu;
        if (words == 0 || at + words > spirv.size())
            throw std::invalid_argument("withCpuFloatSemantics: an instruction runs past the module's end");
        const std::size_t next = at + words;
        if (typesBegin == 0 && !isPreamble(opcode)) typesBegin = at;
        if (opcode == kOpCapability) {
            capabilitiesEnd = next;
            if (words >= 2 && spirv[at + 1] == kSignedZeroInfNanPreserveCapability) hasInfNanCapability = true;
        }
        if (opcode == kOpEntryPoint || opcode == kOpExecutionMode || opcode == kOpExecutionModeId) modesEnd = next;
        if (opcode == kOpEntryPoint && words >= 3) entryPoints.push_back(spirv[at + 2]);
        if (opcode == kOpExecutionMode && words >= 4 && spirv[at + 2] == kSignedZeroInfNanPreserve && spirv[at + 3] == 32)
            preservingEntryPoints.insert(spirv[at + 1]);
        if (opcode == kOpDecorate && words >= 3 && spirv[at + 2] == kNoContraction) decorated.insert(spirv[at + 1]);
        if (isContractible(opcode) && words >= 3) contractible.push_back(spirv[at + 2]);
        at = next;
    }
    if (typesBegin == 0) typesBegin = spirv.size();

    // What goes in where; the three places come in this order in every valid module.
    std::map<std::size_t, std::vector<std::uint32_t>> inserted;
    if (semantics.preserveInfNan) {
        if (!hasInfNanCapability)
            inserted[capabilitiesEnd] = {instructionHead(2, kOpCapability), kSignedZeroInfNanPreserveCapability};
        for (std::uint32_t entry : entryPoints)
            if (preservingEntryPoints.insert(entry).second)
                inserted[modesEnd].insert(inserted[modesEnd].end(),
                                          {instructionHead(4, kOpExecutionMode), entry, kSignedZeroInfNanPreserve, 32});
    }
    for (std::uint32_t id : contractible)
        if (decorated.insert(id).second)
            inserted[typesBegin].insert(inserted[typesBegin].end(), {instructionHead(3, kOpDecorate), id, kNoContraction});

    std::vector<std::uint32_t> result;
    result.reserve(spirv.size() + 3 * contractible.size() + 16);
    std::size_t copied = 0;
    for (const auto& [offset, words] : inserted) {
        result.insert(result.end(), spirv.begin() + std::ptrdiff_t(copied), spirv.begin() + std::ptrdiff_t(offset));
        result.insert(result.end(), words.begin(), words.end());
        copied = offset;
    }
    result.insert(result.end(), spirv.begin() + std::ptrdiff_t(copied), spirv.end());
    return result;
}

}  // namespace vitrum
