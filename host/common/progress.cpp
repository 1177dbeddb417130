#include "common/progress.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unistd.h>

namespace vitrum {

std::string progressLine(const std::string& label, double fraction, double elapsedSeconds) {
    fraction = fraction < 0 ? 0 : (fraction > 1 ? 1 : fraction);
    constexpr int kWidth = 30;
    const int filled = int(fraction * kWidth);
    std::string bar(kWidth, '.');
    bar.replace(0, std::size_t(filled), std::size_t(filled), '#');
    // The time left is padded to one width, so that a shorter line leaves nothing of a longer one.
    char left[64] = "estimating the time left";
    if (fraction >= 0.01 && elapsedSeconds >= 2.0)
        std::snprintf(left, sizeof(left), "~%.1fs left", elapsedSeconds * (1.0 - fraction) / fraction);
    char line[256];
    std::snprintf(line, sizeof(line), "%s [%s] %5.1f%%  %.1fs elapsed, %-24s ", label.c_str(), bar.c_str(),
                  100.0 * fraction, elapsedSeconds, left);
    return line;
}

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
    std::fprintf(stderr, "\r%s", progressLine(label_, fraction, elapsed).c_str());
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

void PhaseProgress::update(const std::string& phase, double fraction) {
    if (!bar_ || phase != phase_) {
        bar_.reset();  // finishes the phase before
        phase_ = phase;
        bar_ = std::make_unique<ProgressBar>(phase);
    }
    bar_->update(fraction);
}

}  // namespace vitrum
