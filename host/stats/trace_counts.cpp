#include "stats/trace_counts.h"

#include <algorithm>
#include <array>

#include <nlohmann/json.hpp>

namespace vitrum {
namespace {

// The list's indices are its positions, and its maxima come last, from kStatFirstMax on: the
// shaders pack the counters by index (shaders/statistics.glsl).
struct ListEntry {
    std::uint32_t index;
    bool max;
};
#define VITRUM_LIST_ENTRY(index, name, combine, group, key, measured) ListEntry{index, kIs##combine},
constexpr bool kIsSum = false, kIsMax = true;
constexpr std::array kList{VITRUM_TRACE_STATISTICS(VITRUM_LIST_ENTRY)};
#undef VITRUM_LIST_ENTRY

constexpr bool listIsInOrder() {
    for (std::uint32_t i = 0; i < kList.size(); ++i)
        if (kList[i].index != i || kList[i].max != (i >= gpu::kStatFirstMax)) return false;
    return kList.size() == gpu::kStatCount && gpu::kWorkCursor == gpu::kStatCount;
}
static_assert(listIsInOrder(), "shaders/shared/trace_statistics.h: indices 0, 1, ... in order, the maxima last");

void combineSum(std::uint64_t& total, std::uint64_t value) { total += value; }
void combineMax(std::uint64_t& total, std::uint64_t value) { total = std::max(total, value); }

constexpr bool kMeasuredBoth = true, kMeasuredGpu = false;

nlohmann::json* groupIn(nlohmann::json& json, const char* group) {
    const std::string name = group;
    if (name == "none") return nullptr;
    if (name == "top") return &json;
    return &json[name];
}

}  // namespace

TraceCounts& TraceCounts::operator+=(const TraceCounts& other) {
#define VITRUM_COMBINE(index, name, how, group, key, measured) combine##how(name, other.name);
    VITRUM_TRACE_STATISTICS(VITRUM_COMBINE)
#undef VITRUM_COMBINE
    return *this;
}

void TraceCounts::addDispatch(const std::uint32_t* counters) {
#define VITRUM_ADD_COUNTER(index, name, how, group, key, measured) combine##how(name, counters[index]);
    VITRUM_TRACE_STATISTICS(VITRUM_ADD_COUNTER)
#undef VITRUM_ADD_COUNTER
}

void addToJson(const TraceCounts& counts, bool gpuOnlyToo, nlohmann::json& json) {
#define VITRUM_TO_JSON(index, name, combine, group, key, measured)                       \
    if (gpuOnlyToo || kMeasured##measured)                                              \
        if (nlohmann::json* place = groupIn(json, #group)) (*place)[#key] = counts.name;
    VITRUM_TRACE_STATISTICS(VITRUM_TO_JSON)
#undef VITRUM_TO_JSON
    json["rays"]["total"] = counts.totalRays();
}

}  // namespace vitrum
