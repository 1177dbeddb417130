// The device self-check of the fast kernel's subgroup machinery, run when a device with full
// subgroups is opened (VulkanDevice): one small dispatch of shaders/subgroup_check.comp, checked
// on the host against the same computation. trace.comp's fast path (statistics summed by
// shuffles, ray sharing, persistent subgroups) relies on what that kernel does: full subgroups,
// lanes that loop together and read one another by shuffles, units taken by an elected lane's
// atomic. A device that fails gets the kernel without full subgroups (the same image, slower),
// with one warning naming the check (docs/gpu-design.md, "Two drivers").
#pragma once

#include <string>

namespace vitrum {

class VulkanDevice;

struct SubgroupSelfCheck {
    bool passed = false;
    std::string failure;  // what went wrong, when it did not pass
};

// Runs the check on `device`, whose subgroups must be full-capable. `subgroupBarrier`: with a
// subgroup barrier every round (the minimal kernel of the Mesa 25 lavapipe defect, for its test).
// `injectFault`: one lane behaves as a lost invocation (tests of the fallback; also taken from
// VITRUM_SELF_CHECK_FAULT=1 by VulkanDevice).
SubgroupSelfCheck checkSubgroupMachinery(VulkanDevice& device, bool subgroupBarrier = false,
                                         bool injectFault = false);

}  // namespace vitrum
