// A small command-line reader: flags with values, repeatable flags and positional arguments,
// with errors that say which argument was wrong and what it should look like.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace vitrum {

// Whether argv[first..] asks for a command's help (--help or -h).
bool wantsHelp(int argc, char** argv, int first);

class Arguments {
public:
    Arguments(int argc, char** argv, int first);

    bool empty() const { return position_ >= args_.size(); }
    std::string next();  // throws InputError when there is none
    std::string valueOf(const std::string& flag);

    static std::uint32_t toUint(const std::string& flag, const std::string& text, std::uint32_t min, std::uint32_t max);
    static float toFloat(const std::string& flag, const std::string& text);
    static glm::vec3 toVec3(const std::string& flag, const std::string& text);

private:
    std::vector<std::string> args_;
    std::size_t position_ = 0;
};

}  // namespace vitrum
