// What the benchmark programs share: the median and quantiles, number formatting, the machine and the date
// for their reports, and a main() that turns an exception into a message and exit code 1.
#pragma once

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <exception>
#include <fstream>
#include <iostream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace vitrum::bench {

// The q-quantile of v (0 <= q <= 1), interpolated linearly between the two nearest order
// statistics; 0 for no values.
inline double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const double at = q * double(v.size() - 1);
    const std::size_t below = std::size_t(at);
    const std::size_t above = std::min(below + 1, v.size() - 1);
    return v[below] + (at - double(below)) * (v[above] - v[below]);
}

// The middle value, or the mean of the two middle ones.
inline double median(std::vector<double> v) { return quantile(std::move(v), 0.5); }

// "CPU model, N hardware threads".
inline std::string machine() {
    std::string cpu = "unknown CPU";
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);)
        if (line.rfind("model name", 0) == 0) {
            cpu = line.substr(line.find(':') + 2);
            break;
        }
    return cpu + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
}

// v with `digits` decimals, for the reports' tables.
inline std::string fixed(double v, int digits) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
    return buffer;
}

inline std::string today() {
    const std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
    return date;
}

template <class Run>
int guardedMain(const char* program, Run run) {
    try {
        return run();
    } catch (const std::exception& e) {
        std::cerr << program << ": " << e.what() << "\n";
        return 1;
    }
}

}  // namespace vitrum::bench
