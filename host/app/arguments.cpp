#include "app/arguments.h"

#include <cmath>
#include <cstring>
#include <sstream>

#include "common/error.h"

namespace vitrum {

bool wantsHelp(int argc, char** argv, int first) {
    for (int i = first; i < argc; ++i)
        if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) return true;
    return false;
}

Arguments::Arguments(int argc, char** argv, int first) {
    for (int i = first; i < argc; ++i) args_.emplace_back(argv[i]);
}

std::string Arguments::next() {
    if (empty()) throw InputError("missing argument");
    return args_[position_++];
}

std::string Arguments::valueOf(const std::string& flag) {
    if (empty()) throw InputError(flag + " needs a value");
    return args_[position_++];
}

std::uint32_t Arguments::toUint(const std::string& flag, const std::string& text, std::uint32_t min,
                                std::uint32_t max) {
    std::size_t used = 0;
    long long value = 0;
    try {
        value = std::stoll(text, &used);
    } catch (...) {
        used = 0;
    }
    if (used != text.size() || text.empty() || value < min || value > max)
        throw InputError(flag + " must be a whole number from " + std::to_string(min) + " to " + std::to_string(max) +
                         ", got \"" + text + "\"");
    return std::uint32_t(value);
}

float Arguments::toFloat(const std::string& flag, const std::string& text) {
    std::size_t used = 0;
    float value = 0;
    try {
        value = std::stof(text, &used);
    } catch (...) {
        used = 0;
    }
    if (used != text.size() || text.empty() || !std::isfinite(value))
        throw InputError(flag + " must be a finite number, got \"" + text + "\"");
    return value;
}

glm::vec3 Arguments::toVec3(const std::string& flag, const std::string& text) {
    std::vector<std::string> parts;
    std::stringstream stream(text);
    std::string part;
    while (std::getline(stream, part, ',')) parts.push_back(part);
    if (parts.size() != 3) throw InputError(flag + " must be three numbers X,Y,Z, got \"" + text + "\"");
    return {toFloat(flag, parts[0]), toFloat(flag, parts[1]), toFloat(flag, parts[2])};
}

}  // namespace vitrum
