// A progress bar on stderr that appears only for work that takes more than a second, and only
// when stderr is a terminal or VITRUM_PROGRESS=1.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <string>

namespace vitrum {

// The line drawn for `fraction` (0..1) done after `elapsedSeconds`: the time left is estimated
// from the rate so far only once 1% is done and 2 s have passed; before that it says
// "estimating" (a first tile of glass can take as long as the rest).
std::string progressLine(const std::string& label, double fraction, double elapsedSeconds);

class ProgressBar {
public:
    explicit ProgressBar(std::string label);
    ~ProgressBar();
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    void update(double fraction);  // 0..1; cheap to call often
    void finish();

private:
    std::string label_;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point lastDraw_;
    bool enabled_;
    bool drawn_ = false;
    bool finished_ = false;
};

// Work done in phases that each report their own fraction ("parsing s3m.obj", then "building the
// BVH"): the library reports through the callback, the command line draws the bars.
using PhaseCallback = std::function<void(const std::string& phase, double fraction)>;

// A ProgressBar a phase, the next one begun when the phase changes.
class PhaseProgress {
public:
    void update(const std::string& phase, double fraction);
    void finish() { bar_.reset(); }
    PhaseCallback callback() {
        return [this](const std::string& phase, double fraction) { update(phase, fraction); };
    }

private:
    std::string phase_;
    std::unique_ptr<ProgressBar> bar_;
};

}  // namespace vitrum
