// A progress bar on stderr that appears only for work that takes more than a second, and only
// when stderr is a terminal or VITRUM_PROGRESS=1.
#pragma once

#include <chrono>
#include <string>

namespace vitrum {

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

}  // namespace vitrum
