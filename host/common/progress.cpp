#include "common/progress.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unistd.h>

namespace vitrum {

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)), start_(std::chrono::steady_clock::now()), lastDraw_(start_) {
    const char* env = std::getenv("VITRUM_PROGRESS");
    enabled_ = env ? std::strcmp(env, "0") != 0 : isatty(STDERR_FILENO) != 0;
}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(double fraction) {
    if (!enabled_ || finished_) return;
    auto now = std::chrono::steady_clock::now();
    double elapsed = std::chrono::duration<double>(now - start_).count();
    if (elapsed < 1.0 || now - lastDraw_ < std::chrono::milliseconds(100)) return;
    lastDraw_ = now;
    fraction = fraction < 0 ? 0 : (fraction > 1 ? 1 : fraction);
    constexpr int kWidth = 30;
    int filled = int(fraction * kWidth);
    char bar[kWidth + 1];
    for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '.';
    bar[kWidth] = 0;
    double eta = fraction > 0.01 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    std::fprintf(stderr, "\r%s [%s] %5.1f%%  %.1fs elapsed, ~%.1fs left ", label_.c_str(), bar, 100.0 * fraction,
                 elapsed, eta);
    std::fflush(stderr);
    drawn_ = true;
}

void ProgressBar::finish() {
    if (finished_) return;
    finished_ = true;
    if (drawn_) {
        double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        std::fprintf(stderr, "\r%s done in %.2fs%*s\n", label_.c_str(), elapsed, 40, "");
    }
}

}  // namespace vitrum
