// Errors that reach the user. An InputError is the user's to fix (a bad scene, a missing file):
// its message already names the file and, where there is one, the line, in the form
// "path:line: what was expected, got what". Everything else is a bug or a device failure.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace vitrum {

class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// "path:line: message" (line 0 means the file as a whole: "path: message").
inline InputError inputError(const std::filesystem::path& file, int line, const std::string& message) {
    std::string text = file.string();
    if (line > 0) text.append(":").append(std::to_string(line));
    text.append(": ").append(message);
    return InputError(text);
}

// Warnings go to stderr once each; tests can count them.
void warn(const std::string& message);
int warningCount();
// Counted, no longer printed: the ranks of a distributed render but rank 0 load the same scene
// and would repeat its warnings.
void silenceWarnings();

}  // namespace vitrum
