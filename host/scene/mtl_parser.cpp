#include "scene/mtl_parser.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <string_view>

#include "common/error.h"
#include "common/float_text.h"
#include "common/input_file.h"
#include "scene/quote_input.h"

namespace vitrum {
namespace {

std::vector<std::string_view> splitWords(std::string_view line) {
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
    }
    return words;
}

std::string_view trim(std::string_view s) {
    const char* space = " \t\r\n\v\f";
    std::size_t first = s.find_first_not_of(space);
    if (first == std::string_view::npos) return {};
    return s.substr(first, s.find_last_not_of(space) - first + 1);
}

std::optional<float> parseFloat(std::string_view word) {
    float value = 0.0f;
    if (readFloat(word, value) != FloatText::Number) return std::nullopt;
    return value;
}

class MtlReader {
public:
    explicit MtlReader(const std::filesystem::path& path) : path_(path) {}

    std::vector<MtlEntry> read() {
        std::istringstream in(readInputLines(path_, "the MTL file", kMaxSceneFileBytes));
        std::string text;
        while (std::getline(in, text)) {
            ++line_;
            parseLine(trim(text));
        }
        return std::move(entries_);
    }

private:
    [[noreturn]] void fail(const std::string& message) const { throw inputError(path_, line_, message); }

    // A number, or the course's typo "1.0." read as 1.0 with a warning once per file.
    std::optional<float> number(std::string_view word) {
        if (auto value = parseFloat(word)) return value;
        if (word.size() > 1 && word.back() == '.') {
            if (auto value = parseFloat(word.substr(0, word.size() - 1))) {
                if (!typoReported_) {
                    typoReported_ = true;
                    warn(path_.string() + ":" + std::to_string(line_) + ": read \"" + std::string(word) + "\" as " +
                         std::string(word.substr(0, word.size() - 1)));
                }
                return value;
            }
        }
        return std::nullopt;
    }

    // "Kd r g b", or "Kd v" for a grey (the MTL spec lets g and b default to r).
    glm::vec3 colour(std::string_view key, const std::vector<std::string_view>& words, std::string_view rest) {
        glm::vec3 c(0.0f);
        bool ok = words.size() == 2 || words.size() == 4;
        for (std::size_t i = 1; ok && i < words.size(); ++i) {
            auto value = number(words[i]);
            ok = value.has_value();
            if (ok) c[int(i - 1)] = *value;
        }
        if (!ok) fail(std::string(key) + " expects three numbers, got " + quoteInput(rest));
        return words.size() == 2 ? glm::vec3(c.x) : c;
    }

    float scalar(std::string_view key, const std::vector<std::string_view>& words, std::string_view rest) {
        std::optional<float> value = words.size() == 2 ? number(words[1]) : std::nullopt;
        if (!value) fail(std::string(key) + " expects one number, got " + quoteInput(rest));
        return *value;
    }

    int integer(std::string_view key, const std::vector<std::string_view>& words, std::string_view rest) {
        float value = scalar(key, words, rest);
        if (value != std::floor(value) || std::fabs(value) > 1e6f)
            fail(std::string(key) + " expects an integer, got " + quoteInput(rest));
        return int(value);
    }

    void parseLine(std::string_view text) {
        if (text.empty() || text.front() == '#') return;
        std::vector<std::string_view> words = splitWords(text);
        std::string_view key = words[0];
        std::string_view rest = trim(text.substr(key.size()));
        if (key == "newmtl") {
            if (words.size() < 2) fail("newmtl expects a material name");
            entries_.push_back(MtlEntry{.name = std::string(words[1]), .line = line_});
            return;
        }
        static constexpr std::string_view kUsedKeys[] = {
            "Ka",     "Kd",    "Ks",       "Tf", "Ns",          "Ni",   "illum",    "shader",
            "map_Kd", "map_d", "priority", "Vd", "thin_walled", "tint", "coverage", "map_coverage"};
        if (std::find(std::begin(kUsedKeys), std::end(kUsedKeys), key) == std::end(kUsedKeys)) return;
        if (entries_.empty()) {
            warn(path_.string() + ":" + std::to_string(line_) + ": " + std::string(key) + " before any newmtl ignored");
            return;
        }
        MtlEntry& m = entries_.back();
        if (key == "Ka")
            m.ka = colour(key, words, rest);
        else if (key == "Kd")
            m.kd = colour(key, words, rest);
        else if (key == "Ks")
            m.ks = colour(key, words, rest);
        else if (key == "Tf")
            m.tf = colour(key, words, rest);
        else if (key == "tint")
            m.tint = colour(key, words, rest);
        else if (key == "Ns")
            m.ns = scalar(key, words, rest);
        else if (key == "Ni")
            m.ni = scalar(key, words, rest);
        else if (key == "illum")
            m.illum = integer(key, words, rest);
        else if (key == "Vd")
            m.vd = scalar(key, words, rest);
        else if (key == "priority")
            m.priority = integer(key, words, rest);
        else if (key == "coverage") {
            m.coverage = scalar(key, words, rest);
            m.coverageLine = line_;
        } else if (key == "thin_walled") {
            m.thinWalled = integer(key, words, rest);
            if (*m.thinWalled != 0 && *m.thinWalled != 1) fail("thin_walled expects 0 or 1, got " + quoteInput(rest));
        } else if (key == "shader") {
            m.shader = integer(key, words, rest);
            m.shaderLine = line_;
        } else {  // map_Kd, map_d or map_coverage [options] file: options start with '-'; otherwise the whole rest may
                  // hold spaces
            if (words.size() < 2) fail(std::string(key) + " expects a file name");
            bool hasOptions = std::any_of(words.begin() + 1, words.end(), [](auto w) { return w.front() == '-'; });
            const std::string file(hasOptions ? words.back() : rest);
            if (key == "map_Kd") {
                m.mapKd = file;
                m.mapKdLine = line_;
            } else if (key == "map_d") {
                m.mapD = file;
                m.mapDLine = line_;
            } else {
                m.mapCoverage = file;
                m.mapCoverageLine = line_;
            }
        }
    }

    std::filesystem::path path_;
    int line_ = 0;
    bool typoReported_ = false;
    std::vector<MtlEntry> entries_;
};

}  // namespace

std::vector<MtlEntry> parseMtlFile(const std::filesystem::path& path) { return MtlReader(path).read(); }

}  // namespace vitrum
