#include "gpu/trace_kernel_cache.h"

#include <stdexcept>

namespace vitrum {

TraceKernelCache::TraceKernelCache(std::size_t capacity) : capacity_(capacity) {
    if (capacity_ < 2)
        throw std::logic_error("TraceKernelCache: a render may take two kernels, so it holds at least two");
}

TraceKernelCache::Kernel TraceKernelCache::get(const VulkanDevice& device, const TraceSpecialization& specialization,
                                               bool resumable, StatisticsSums sums, bool persistent) {
    if (device_ == VK_NULL_HANDLE) device_ = device.device();
    if (device.device() != device_) throw std::logic_error("TraceKernelCache: used with a second device");
    const TraceKernelConstants constants = traceKernelConstants(specialization, resumable, sums, persistent);
    auto found = entries_.begin();
    while (found != entries_.end() && !(found->constants == constants && found->sums == sums)) ++found;
    if (found != entries_.end()) {
        entries_.splice(entries_.begin(), entries_, found);
    } else {
        if (entries_.size() == capacity_) entries_.pop_back();
        entries_.push_front(
            Entry{constants, sums, makeTracePipeline(device, specialization, resumable, sums, persistent)});
        ++created_;
    }
    return {entries_.front().pipeline, entries_.front().compiled};
}

}  // namespace vitrum
