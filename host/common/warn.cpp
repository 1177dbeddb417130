#include "common/error.h"

#include <atomic>
#include <iostream>
#include <mutex>
#include <set>

namespace vitrum {
namespace {
std::mutex gMutex;
std::set<std::string> gSeen;
std::atomic<int> gCount{0};
bool gSilent = false;
}  // namespace

void warn(const std::string& message) {
    std::lock_guard lock(gMutex);
    if (!gSeen.insert(message).second) return;
    ++gCount;
    if (!gSilent) std::cerr << "vitrum: warning: " << message << "\n";
}

int warningCount() { return gCount.load(); }

void silenceWarnings() {
    std::lock_guard lock(gMutex);
    gSilent = true;
}

}  // namespace vitrum
