#include "scene/json_lines.h"

#include <algorithm>
#include <vector>

namespace vitrum {

int lineOfOffset(std::string_view text, std::size_t offset) {
    offset = std::min(offset, text.size());
    return 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(offset), '\n'));
}

std::size_t offsetBeyondNesting(std::string_view text, int maxDepth) {
    int depth = 0;
    bool inString = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\') ++i;
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > maxDepth) return i;
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return text.size();
}

std::unordered_map<std::string, int> jsonValueLines(std::string_view text) {
    std::unordered_map<std::string, int> lines;
    std::size_t i = 0;
    int line = 1;
    auto peek = [&] { return i < text.size() ? text[i] : '\0'; };
    auto skipSpace = [&] {
        for (; i < text.size() && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r' || text[i] == '\n'); ++i)
            if (text[i] == '\n') ++line;
    };
    auto readString = [&] {  // at the opening quote; returns the raw contents
        std::size_t start = ++i;
        while (i < text.size() && text[i] != '"') i += text[i] == '\\' ? 2 : 1;
        std::string s(text.substr(start, std::min(i, text.size()) - start));
        ++i;
        return s;
    };
    // An explicit stack instead of recursion: nesting depth is the input's choice.
    struct Frame {
        std::string path;
        bool array;
        int next = 0;
    };
    std::vector<Frame> stack;
    auto value = [&](const std::string& path) {
        skipSpace();
        lines.emplace(path, line);
        if (peek() == '{' || peek() == '[') {
            stack.push_back({path, peek() == '['});
            ++i;
        } else if (peek() == '"') {
            readString();
        } else {
            while (i < text.size() && std::string_view(",]} \t\r\n").find(text[i]) == std::string_view::npos) ++i;
        }
    };
    value("");
    while (!stack.empty() && i < text.size()) {
        skipSpace();
        if (peek() == ',') {
            ++i;
            skipSpace();
        }
        if (peek() == '}' || peek() == ']') {
            ++i;
            stack.pop_back();
            continue;
        }
        Frame& frame = stack.back();
        if (frame.array) {
            value(frame.path + "/" + std::to_string(frame.next++));
        } else {
            int keyLine = line;
            std::string path = frame.path + "/" + readString();
            skipSpace();
            ++i;  // ':'
            lines.emplace(path, keyLine);
            value(path);
        }
    }
    return lines;
}

}  // namespace vitrum
