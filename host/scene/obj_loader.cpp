#include "scene/obj_loader.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <set>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "common/error.h"
#include "common/float_text.h"
#include "common/input_file.h"
#include "common/parallel.h"
#include "image/image.h"
#include "image/srgb.h"
#include "scene/mtl_material.h"
#include "scene/mtl_parser.h"
#include "scene/quote_input.h"
#include "scene/scene_names.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& file) { return readInputLines(file, "the OBJ file", kMaxObjFileBytes); }

bool isBlank(char c) { return c == ' ' || c == '\t'; }

// A loop of two compares: find_first_of(" \t") calls memchr on the set for each character, a
// quarter of the parse's time.
std::string_view firstWord(std::string_view line, std::size_t* end = nullptr) {
    std::size_t begin = 0;
    while (begin < line.size() && isBlank(line[begin])) ++begin;
    if (begin == line.size()) return {};
    std::size_t stop = begin;
    while (stop < line.size() && !isBlank(line[stop])) ++stop;
    if (end) *end = stop;
    return line.substr(begin, stop - begin);
}

// The digits of a number's decimal exponent, leading zeros left out: "1e-0012" has 2.
std::size_t exponentDigits(std::string_view number) {
    std::size_t at = number.find_first_of("eE");
    if (at == std::string_view::npos) return 0;
    ++at;
    if (at < number.size() && (number[at] == '+' || number[at] == '-')) ++at;
    while (at < number.size() && number[at] == '0') ++at;
    std::size_t digits = 0;
    while (at + digits < number.size() && number[at + digits] >= '0' && number[at + digits] <= '9') ++digits;
    return digits;
}

// vitrum reads OBJ files as tinyobjloader 2.0 (Debian 12) read them, which its images were made
// from: the same numbers, indices, shapes and materials (docs/gpu-design.md, "The OBJ parsed on
// every core"). The functions named tinyobj* do what its functions of those names do.

// tryParseDouble, step for step: it is not correctly rounded (a digit at a time into a double),
// and a coordinate read correctly rounded could differ from it in its float's last bit.
bool tinyobjDouble(const char* s, const char* s_end, double* result) {
    if (s >= s_end) return false;
    double mantissa = 0.0;
    int exponent = 0;
    char sign = '+';
    char exp_sign = '+';
    const char* curr = s;
    int read = 0;
    bool end_not_reached = false;
    bool leading_decimal_dots = false;
    auto isDigit = [](char c) { return static_cast<unsigned int>(c - '0') < 10u; };

    if (*curr == '+' || *curr == '-') {
        sign = *curr;
        curr++;
        if ((curr != s_end) && (*curr == '.')) leading_decimal_dots = true;
    } else if (isDigit(*curr)) {
    } else if (*curr == '.') {
        leading_decimal_dots = true;
    } else {
        return false;
    }
    end_not_reached = (curr != s_end);
    if (!leading_decimal_dots) {
        while (end_not_reached && isDigit(*curr)) {
            mantissa *= 10;
            mantissa += static_cast<int>(*curr - 0x30);
            curr++;
            read++;
            end_not_reached = (curr != s_end);
        }
        if (read == 0) return false;
    }
    if (!end_not_reached) goto assemble;
    if (*curr == '.') {
        curr++;
        read = 1;
        end_not_reached = (curr != s_end);
        while (end_not_reached && isDigit(*curr)) {
            static const double pow_lut[] = {1.0, 0.1, 0.01, 0.001, 0.0001, 0.00001, 0.000001, 0.0000001};
            const int lut_entries = sizeof pow_lut / sizeof pow_lut[0];
            mantissa += static_cast<int>(*curr - 0x30) * (read < lut_entries ? pow_lut[read] : std::pow(10.0, -read));
            read++;
            curr++;
            end_not_reached = (curr != s_end);
        }
    } else if (*curr == 'e' || *curr == 'E') {
    } else {
        goto assemble;
    }
    if (!end_not_reached) goto assemble;
    if (*curr == 'e' || *curr == 'E') {
        curr++;
        end_not_reached = (curr != s_end);
        // *curr at s_end is a space, '\n' or the text's closing '\0': no digit, as in tinyobj's line.
        if (end_not_reached && (*curr == '+' || *curr == '-')) {
            exp_sign = *curr;
            curr++;
        } else if (isDigit(*curr)) {
        } else {
            return false;
        }
        read = 0;
        end_not_reached = (curr != s_end);
        while (end_not_reached && isDigit(*curr)) {
            if (exponent > (2147483647 / 10)) return false;
            exponent *= 10;
            exponent += static_cast<int>(*curr - 0x30);
            curr++;
            read++;
            end_not_reached = (curr != s_end);
        }
        exponent *= (exp_sign == '+' ? 1 : -1);
        if (read == 0) return false;
    }
assemble:
    *result = (sign == '+' ? 1 : -1) * (exponent ? std::ldexp(mantissa * std::pow(5.0, exponent), exponent) : mantissa);
    return true;
}

// parseReal: the next word of the line, `fallback` where it is no number.
float tinyobjReal(const char*& at, const char* lineEnd, double fallback = 0.0) {
    while (at < lineEnd && isBlank(*at)) ++at;
    const char* end = at;
    while (end < lineEnd && !isBlank(*end)) ++end;
    double value = fallback;
    tinyobjDouble(at, end, &value);
    at = end;
    return static_cast<float>(value);
}

// atoi as glibc's (strtol, then int): it skips white space first, so that "f 1/ 2 3" reads the
// texture coordinate of its first corner from the word after it.
int tinyobjAtoi(const char* at, const char* lineEnd) {
    while (at < lineEnd && (isBlank(*at) || *at == '\v' || *at == '\f')) ++at;
    bool negative = false;
    if (at < lineEnd && (*at == '+' || *at == '-')) negative = *at++ == '-';
    unsigned long long magnitude = 0;
    bool beyond = false;
    for (; at < lineEnd && *at >= '0' && *at <= '9'; ++at) {
        if (magnitude > (ULLONG_MAX - 9) / 10) beyond = true;
        if (!beyond) magnitude = magnitude * 10 + unsigned(*at - '0');
    }
    const unsigned long long limit = negative ? (unsigned long long)LONG_MAX + 1 : (unsigned long long)LONG_MAX;
    long value = 0;
    if (beyond || magnitude > limit) value = negative ? LONG_MIN : LONG_MAX;
    else value = negative ? long(0 - magnitude) : long(magnitude);
    return static_cast<int>(value);  // the low 32 bits, as GCC converts
}

// parseTriple's reading of one corner "v", "v/vt", "v//vn" or "v/vt/vn", moving `at` past it:
// the atoi values (0 where a part is absent), or false where a present one is 0.
bool tinyobjCorner(const char*& at, const char* lineEnd, int (&index)[3]) {
    auto next = [&] {  // strcspn(at, "/ \t\r")
        while (at < lineEnd && *at != '/' && !isBlank(*at)) ++at;
    };
    auto peek = [&] { return at < lineEnd ? *at : '\0'; };
    index[0] = index[1] = index[2] = 0;
    if ((index[0] = tinyobjAtoi(at, lineEnd)) == 0) return false;
    next();
    if (peek() != '/') return true;
    ++at;
    if (peek() == '/') {
        ++at;
        if ((index[2] = tinyobjAtoi(at, lineEnd)) == 0) return false;
        next();
        return true;
    }
    if ((index[1] = tinyobjAtoi(at, lineEnd)) == 0) return false;
    next();
    if (peek() != '/') return true;
    ++at;
    if ((index[2] = tinyobjAtoi(at, lineEnd)) == 0) return false;
    next();
    return true;
}

// A face corner's vertex, texture coordinate and normal, 0-based; -1 for none.
struct Corner {
    int v = -1, vt = -1, vn = -1;
};

// What changes the shape or the material of the faces after it, in file order: tinyobjloader
// starts a shape at each o and g, and a usemtl sets the material of the faces that follow.
struct ObjEvent {
    enum Kind : std::uint8_t { Usemtl, Mtllib, Object, Group, Degenerate, LinesOrPoints } kind;
    int line = 0;
    std::size_t face = 0;  // the faces of three corners or more before it in its part
    std::string name;      // usemtl's material, o's or g's name
    std::vector<std::string> files;  // mtllib's
    bool emptyGroup = false;         // a g without a name, which tinyobjloader warns of
};

// One part of the file, read from a line's start: what the checks found (the first error, the
// statements counted) and what tinyobjloader would have read from it.
struct ObjPart {
    std::size_t vertices = 0, normals = 0, texcoords = 0, skinWeights = 0;
    bool hasMtllib = false;
    std::vector<std::string> usemtlNames;
    int freeLine = -1;  // a blank or comment line before any usemtl: where an mtllib can go
    std::vector<float> positions, normalValues, uvs;  // three, three and two a statement
    std::vector<Corner> corners;                      // of the faces of three corners or more
    std::vector<std::uint32_t> faceEnds;              // where each face's corners end in `corners`
    std::vector<std::uint64_t> relative;  // 3 * corner + (0 v, 1 vt, 2 vn): negative indices, from the part's start
    std::vector<ObjEvent> events;
    int readerErrorLine = 0;   // the first line tinyobjloader refused (0: none), and its message
    std::string readerError;
};

// Checks and reads the whole lines text[from, to), which follow `linesBefore` lines; `progress`
// (the calling thread's part) is told each of `reports` fractions of the file in turn.
void readLines(const fs::path& file, const std::string& text, std::size_t from, std::size_t to, int linesBefore,
               ObjPart& part, const std::function<void(double)>& progress, std::size_t reports) {
    bool seenUsemtl = false;
    int lineNumber = linesBefore;
    std::size_t reported = 0, nextReport = progress && reports ? from : std::string::npos;
    auto report = [&](std::size_t at) {
        for (; reported < reports && at >= from + (to - from) * reported / reports; ++reported)
            progress(double(reported << 20) / double(text.size()));
        nextReport = reported < reports ? from + (to - from) * reported / reports : std::string::npos;
    };
    auto readerError = [&](const char* statement, const char* what) {
        if (part.readerErrorLine) return;
        part.readerErrorLine = lineNumber;
        part.readerError = std::string("Failed parse `") + statement + "' line(e.g. zero value for " + what +
                           " index. line " + std::to_string(lineNumber) + ".)";
    };
    auto index = [&](int value, std::size_t count, std::size_t corner, int which) {
        if (value > 0) return value - 1;
        part.relative.push_back(3 * std::uint64_t(corner) + std::uint64_t(which));
        return int(std::int64_t(count) + value);  // fixIndex; the part's start is added later
    };
    for (std::size_t begin = from; begin < to;) {
        if (begin >= nextReport) report(begin);
        std::size_t end = std::min(text.find('\n', begin), text.size());
        std::string_view line = std::string_view(text).substr(begin, end - begin);  // no '\r' (readInputLines)
        const char* lineEnd = text.data() + end;
        ++lineNumber;
        std::size_t wordEnd = 0;
        std::string_view word = firstWord(line, &wordEnd);
        // vitrum's checks first: what tinyobjloader would read as 0, read with an overflow, or
        // wrap around is an error with its line.
        if (word.empty() || word.front() == '#') {
            if (!seenUsemtl && part.freeLine < 0) part.freeLine = lineNumber;
        } else if (word == "v") {
            ++part.vertices;
            std::string_view rest = line.substr(wordEnd);
            for (int i = 0; i < 3; ++i) {
                std::size_t numberEnd = 0;
                std::string_view number = firstWord(rest, &numberEnd);
                float value = 0.0f;
                const FloatText read = readFloat(number, value);
                if (read == FloatText::NotANumber)
                    throw inputError(file, lineNumber, "v expects three numbers, got " + quoteInput(line));
                if (read == FloatText::NotFinite)
                    throw inputError(file, lineNumber,
                                     "vertex coordinate " + quoteInput(number) + " is not a finite number");
                rest = rest.substr(numberEnd);
            }
        } else if (word == "f") {
            // atoi stops where a number does ("1.5" is vertex 1) and wraps one beyond the int
            // range around ("4294967299" is vertex 3): each index must be an integer in full, in
            // the int range.
            for (std::string_view rest = line.substr(wordEnd);;) {
                std::size_t cornerEnd = 0;
                std::string_view corner = firstWord(rest, &cornerEnd);
                if (corner.empty()) break;
                for (std::size_t at = 0; at <= corner.size();) {
                    std::size_t slash = std::min(corner.find('/', at), corner.size());
                    std::string_view number = corner.substr(at, slash - at);
                    if (!number.empty() && number.front() == '+') number.remove_prefix(1);
                    long long value = 0;
                    auto [ptr, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
                    if (ec == std::errc::result_out_of_range || value > std::numeric_limits<int>::max() ||
                        value < -std::numeric_limits<int>::max())
                        throw inputError(file, lineNumber, "face index " + quoteInput(number) + " is out of range");
                    if (ptr != number.data() + number.size())  // an empty one tinyobjloader reports as 0
                        throw inputError(file, lineNumber, "face corner " + quoteInput(corner) +
                                                               " is not v, v/vt, v//vn or v/vt/vn in integers");
                    at = slash + 1;
                }
                rest = rest.substr(cornerEnd);
            }
        } else if (word == "vn" || word == "vt" || word == "vp") {
            if (word == "vn") ++part.normals;
            if (word == "vt") ++part.texcoords;
            // tinyobjloader read an exponent into an int that overflowed (undefined behaviour) at
            // ten digits or more (found by fuzzing); such a number is 0 or infinite anyway. It
            // reads a normal's or a texture coordinate's word that is no number as 0, without an
            // error: those must be numbers, three for vn and one to three for vt.
            const bool checked = word != "vp";
            int numbers = 0;
            for (std::string_view rest = line.substr(wordEnd);;) {
                std::size_t numberEnd = 0;
                std::string_view number = firstWord(rest, &numberEnd);
                if (number.empty() || number.front() == '#') break;
                if (exponentDigits(number) > 9)
                    throw inputError(file, lineNumber, "the exponent of " + quoteInput(number) + " is out of range");
                float value = 0.0f;
                const FloatText read = checked && numbers < 3 ? readFloat(number, value) : FloatText::Number;
                if (read != FloatText::Number)
                    throw inputError(file, lineNumber,
                                     std::string(word) + " expects numbers, got " + quoteInput(number) +
                                         (read == FloatText::NotFinite ? ", which is not finite" : ""));
                ++numbers;
                rest = rest.substr(numberEnd);
            }
            if (word == "vn" && numbers < 3)
                throw inputError(file, lineNumber, "vn expects three numbers, got " + quoteInput(line));
            if (word == "vt" && numbers < 1)
                throw inputError(file, lineNumber, "vt expects one to three numbers, got " + quoteInput(line));
        } else if (word == "vw") {
            // Skin weights ("vw", tinyobjloader's extension) mean nothing to a ray tracer, and
            // tinyobjloader converted their joint numbers to int unchecked (undefined behaviour
            // beyond the int range, found by fuzzing): they are ignored, with a warning.
            ++part.skinWeights;
            begin = end + 1;
            continue;
        } else if (word == "mtllib") {
            part.hasMtllib = true;
        } else if (word == "usemtl") {
            seenUsemtl = true;
            part.usemtlNames.emplace_back(firstWord(line.substr(wordEnd)));
        }

        // Then the statement as tinyobjloader's LoadObj reads it: by its first characters.
        const char* token = line.data() + (word.empty() ? line.size() : std::size_t(word.data() - line.data()));
        auto at = [&](std::size_t k) { return token + k < lineEnd ? token[k] : '\0'; };
        const ObjEvent::Kind noEvent = ObjEvent::Kind(255);
        ObjEvent event{noEvent, lineNumber, part.faceEnds.size(), {}, {}, false};
        if (at(0) == 'v' && isBlank(at(1))) {
            const char* p = token + 2;
            for (int i = 0; i < 3; ++i) part.positions.push_back(tinyobjReal(p, lineEnd));
        } else if (at(0) == 'v' && at(1) == 'n' && isBlank(at(2))) {
            const char* p = token + 3;
            for (int i = 0; i < 3; ++i) part.normalValues.push_back(tinyobjReal(p, lineEnd));
        } else if (at(0) == 'v' && at(1) == 't' && isBlank(at(2))) {
            const char* p = token + 3;
            for (int i = 0; i < 2; ++i) part.uvs.push_back(tinyobjReal(p, lineEnd));
        } else if ((at(0) == 'f' || at(0) == 'l' || at(0) == 'p') && isBlank(at(1))) {
            const char kind = at(0);
            const char* p = token + 2;
            if (kind == 'f')
                while (p < lineEnd && isBlank(*p)) ++p;
            const std::size_t first = part.corners.size();
            std::size_t count = 0;
            bool failed = false;
            while (p < lineEnd) {
                int raw[3];
                if (!tinyobjCorner(p, lineEnd, raw)) {
                    readerError(kind == 'f' ? "f" : kind == 'l' ? "l" : "p", kind == 'f' ? "face" : "vertex");
                    failed = true;
                    break;
                }
                if (kind == 'f') {
                    // Vertices, texture coordinates and normals read so far (in this part).
                    const std::size_t c = first + count;
                    part.corners.push_back({index(raw[0], part.vertices, c, 0),
                                            raw[1] ? index(raw[1], part.texcoords, c, 1) : -1,
                                            raw[2] ? index(raw[2], part.normals, c, 2) : -1});
                }
                ++count;
                while (p < lineEnd && isBlank(*p)) ++p;
            }
            if (kind == 'f' && !failed && count >= 3) {
                part.faceEnds.push_back(std::uint32_t(part.corners.size()));
            } else if (kind == 'f') {  // a degenerate face (tinyobjloader warns of it), or one refused
                while (!part.relative.empty() && part.relative.back() >= 3 * std::uint64_t(first)) part.relative.pop_back();
                part.corners.resize(first);
                if (!failed) event.kind = ObjEvent::Degenerate;
            } else if (count > 0) {
                event.kind = ObjEvent::LinesOrPoints;
            }
        } else if (std::string_view(token, std::size_t(lineEnd - token)).starts_with("usemtl")) {
            event.kind = ObjEvent::Usemtl;
            const char* p = token + 6;
            while (p < lineEnd && isBlank(*p)) ++p;
            const char* e = p;
            while (e < lineEnd && !isBlank(*e)) ++e;
            event.name.assign(p, e);
        } else if (std::string_view(token, std::size_t(lineEnd - token)).starts_with("mtllib") && isBlank(at(6))) {
            // SplitString(rest, ' ', '\\'): names apart at spaces, a backslash escaping the next
            // character; the last name is kept even when empty.
            event.kind = ObjEvent::Mtllib;
            std::string name;
            bool escaping = false;
            for (const char* p = token + 7; p < lineEnd; ++p) {
                if (escaping) {
                    escaping = false;
                } else if (*p == '\\') {
                    escaping = true;
                    continue;
                } else if (*p == ' ') {
                    if (!name.empty()) event.files.push_back(name);
                    name.clear();
                    continue;
                }
                name += *p;
            }
            event.files.push_back(name);
        } else if (at(0) == 'g' && isBlank(at(1))) {
            // The words after g, one space between them.
            event.kind = ObjEvent::Group;
            std::size_t words = 0;
            for (const char* p = token; p < lineEnd;) {
                while (p < lineEnd && isBlank(*p)) ++p;
                const char* e = p;
                while (e < lineEnd && !isBlank(*e)) ++e;
                if (e == p) break;
                if (words++ > 1) event.name += ' ';
                if (words > 1) event.name.append(p, e);
                p = e;
            }
            event.emptyGroup = words < 2;
        } else if (at(0) == 'o' && isBlank(at(1))) {
            event.kind = ObjEvent::Object;
            event.name.assign(token + 2, lineEnd);
        }
        if (event.kind != noEvent) part.events.push_back(std::move(event));
        begin = end + 1;
    }
    if (progress) report(to);
}

// The file in parts, one a core, each from a line's start, read at once: the first error, in
// the file's order, is the first part's that has one (issue 52; docs/gpu-design.md, "A big model
// to the image as fast as an Embree renderer" and "The OBJ parsed on every core").
std::vector<ObjPart> readParts(const fs::path& file, const std::string& text, std::size_t parts,
                               const std::function<void(double)>& progress) {
    constexpr std::size_t kBytesAPart = std::size_t(16) << 20;
    if (parts == 0) parts = std::clamp<std::size_t>(text.size() / kBytesAPart, 1, std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::size_t> starts = {0};
    for (std::size_t k = 1; k < parts; ++k) {
        const std::size_t lineEnd = text.find('\n', std::max(starts.back(), text.size() * k / parts));
        starts.push_back(lineEnd == std::string_view::npos ? text.size() : lineEnd + 1);
    }
    starts.push_back(text.size());
    // A progress call a megabyte of text, as when tinyobjloader read it in chunks of one.
    const std::size_t reports = (text.size() + (std::size_t(1) << 20) - 1) >> 20;
    std::vector<ObjPart> read(parts);
    // The first part's error is the file's first, as one core would find it.
    onThreads(parts, [&](std::size_t k) {
        const int linesBefore = int(std::count(text.begin(), text.begin() + std::ptrdiff_t(starts[k]), '\n'));
        readLines(file, text, starts[k], starts[k + 1], linesBefore, read[k], k == 0 ? progress : nullptr, reports);
    });
    return read;
}

// A grey map's values times `scale`: the image's alpha where it has an alpha channel, else its
// grey level as stored (the mean of its channels re-encoded to sRGB: a mask holds data, not
// colour). map_d's mask (render-model-decisions.md, "Cut-out surfaces") cuts the surface where it
// is below 1/2, glTF's default cutoff, so Material::cutout holds twice it; map_coverage's values
// are the share of the surface that is there ("Partial coverage"). The scalar `d` is not read
// (course files give opaque materials `d 0`).
std::vector<glm::vec3> greyTexels(const Image& image, float scale) {
    std::vector<glm::vec3> texels;
    texels.reserve(image.pixels.size());
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const glm::vec3& c = image.pixels[i];
        const float value =
            image.alpha.empty() ? (linearToSrgb(c.x) + linearToSrgb(c.y) + linearToSrgb(c.z)) / 3.0f : image.alpha[i];
        texels.push_back(glm::vec3(scale * value));
    }
    return texels;
}

// The file's canonical path, where the file system gives one, as the key of the files read
// once: a name it refuses (one longer than NAME_MAX, found by fuzzing) is its own key, and the
// read that follows reports it.
fs::path fileKey(const fs::path& file) {
    std::error_code ec;
    fs::path key = fs::weakly_canonical(file, ec);
    return ec ? file : key;
}

}  // namespace

const ObjLoader::Library& ObjLoader::library(const fs::path& mtlFile) {
    fs::path key = fileKey(mtlFile);
    if (auto found = libraries_.find(key); found != libraries_.end()) return found->second;
    Library library;
    for (const MtlEntry& entry : parseMtlFile(mtlFile)) {
        if (library.count(entry.name)) {
            warn(mtlFile.string() + ":" + std::to_string(entry.line) + ": material \"" + entry.name +
                 "\" defined again; the first definition is used");
            continue;
        }
        Material material = materialFromMtl(entry, mtlFile);
        // An image the MTL names, relative to it; Windows exporters write backslashes.
        auto imageFile = [&](std::string name) {
            std::replace(name.begin(), name.end(), '\\', '/');
            return mtlFile.parent_path() / name;
        };
        if (entry.mapKd)
            material.diffuseTexture = texture(imageFile(*entry.mapKd), mtlFile, entry.mapKdLine, "map_Kd", "texture",
                                              "using Kd instead", [](Image& image) { return std::move(image.pixels); });
        if (entry.mapD && material.model == MaterialModel::Glass)
            warn(mtlFile.string() + ":" + std::to_string(entry.mapDLine) +
                 ": map_d of a glass volume ignored (its closed surface bounds its medium)");
        else if (entry.mapD)
            material.cutout = texture(imageFile(*entry.mapD), mtlFile, entry.mapDLine, "map_d", "mask",
                                      "the surface is not cut", [](Image& image) { return greyTexels(image, 2.0f); });
        if (entry.coverage || entry.mapCoverage) material.coverage = coverage(entry, mtlFile, material, imageFile);
        library[entry.name] = std::uint32_t(scene_.materials.size());
        scene_.materials.push_back(std::move(material));
    }
    return libraries_[key] = std::move(library);
}

// The partly covered share of an MTL material (`coverage`, `map_coverage`; render-model-decisions.md,
// "Partial coverage"): a texture, or -1 where the surface is all there or its model has no
// coverage (warned).
int ObjLoader::coverage(const MtlEntry& entry, const fs::path& mtlFile, const Material& material,
                        const std::function<fs::path(std::string)>& imageFile) {
    const int line = entry.mapCoverage ? entry.mapCoverageLine : entry.coverageLine;
    const std::string where = mtlFile.string() + ":" + std::to_string(line) + ": ";
    if (!canBePartlyCovered(material.model)) {
        warn(where + "coverage of a " + std::string(materialModelName(material.model)) +
             " ignored (only Lambert, Phong and mirror surfaces are partly there)");
        return -1;
    }
    if (entry.mapCoverage) {
        if (entry.coverage)
            warn(mtlFile.string() + ":" + std::to_string(entry.coverageLine) +
                 ": coverage ignored beside map_coverage");
        return texture(imageFile(*entry.mapCoverage), mtlFile, line, "map_coverage", "coverage map",
                       "the surface is all there", [](Image& image) { return greyTexels(image, 1.0f); });
    }
    float share = *entry.coverage;
    if (!(share >= 0.0f && share <= 1.0f)) {
        warn(where + "coverage " + std::to_string(share) + " outside [0, 1]; kept within it");
        share = std::isnan(share) ? 1.0f : std::clamp(share, 0.0f, 1.0f);
    }
    if (share == 1.0f) return -1;
    const int index = int(scene_.textures.size());
    scene_.textures.push_back(Texture{where + "coverage", 1, 1, {glm::vec3(share)}});
    return index;
}

// An MTL's image, map_Kd's, map_d's or map_coverage's (`key`), made into a texture by `texels`;
// read once per file and key. Where it cannot be read, -1, warned once naming `what` it is and the `fallback`;
// beyond the texel limit the scene is refused, naming the MTL line.
int ObjLoader::texture(const fs::path& imageFile, const fs::path& mtlFile, int line, const std::string& key,
                       const std::string& what, const std::string& fallback,
                       const std::function<std::vector<glm::vec3>(Image&)>& texels) {
    const auto cacheKey = std::make_pair(key, fileKey(imageFile));
    if (auto found = textures_.find(cacheKey); found != textures_.end()) return found->second;
    int index = -1;
    try {
        Image image = readImage(imageFile, options_.texelLimit.leftAfter(scene_));
        index = int(scene_.textures.size());
        scene_.textures.push_back(Texture{imageFile, int(image.width), int(image.height), texels(image)});
    } catch (const ImageTooLarge& e) {
        throw inputError(mtlFile, line, key + " " + e.what());
    } catch (const InputError& e) {
        warn(mtlFile.string() + ":" + std::to_string(line) + ": " + what + " cannot be read (" + e.what() + "); " +
             fallback);
    }
    return textures_[cacheKey] = index;
}

std::uint32_t ObjLoader::defaultMaterialIndex() {
    if (!defaultMaterial_) {
        defaultMaterial_ = std::uint32_t(scene_.materials.size());
        scene_.materials.push_back(defaultMaterial());
    }
    return *defaultMaterial_;
}

void ObjLoader::load(const fs::path& objFile, const ObjOptions& options) {
    std::string text = readText(objFile);
    const std::string fileName = objFile.filename().string();
    auto report = [&](const std::string& phase) -> std::function<void(double)> {
        if (!options_.progress) return {};
        return [this, phase](double fraction) { options_.progress(phase, fraction); };
    };
    std::vector<ObjPart> parts = readParts(objFile, text, options.parts, report("parsing " + fileName));
    std::string().swap(text);  // the parts hold what is needed of it

    // Each part's statements counted from its start: where the part's begin in the file's.
    struct Base {
        std::size_t vertices = 0, normals = 0, texcoords = 0, faces = 0, corners = 0, triangles = 0;
    };
    std::vector<Base> bases(parts.size() + 1);
    std::size_t skinWeights = 0;
    for (std::size_t k = 0; k < parts.size(); ++k) {
        const ObjPart& part = parts[k];
        const std::size_t faces = part.faceEnds.size(), corners = part.corners.size();
        bases[k + 1] = {bases[k].vertices + part.vertices, bases[k].normals + part.normals, bases[k].texcoords + part.texcoords,
                        bases[k].faces + faces,            bases[k].corners + corners,    bases[k].triangles + corners - 2 * faces};
        skinWeights += part.skinWeights;
    }
    const Base& all = bases.back();
    if (options_.checkTriangles) options_.checkTriangles(scene_.triangles.size() + all.triangles);
    if (skinWeights) warn(objFile.string() + ": " + std::to_string(skinWeights) + " skin weight (vw) lines ignored");

    // Materials, shapes and their names in the file's order, as tinyobjloader made them: a usemtl
    // names a material of the libraries read before it; o and g end a shape, which is kept if it
    // has faces (or, at an o, lines or points: it still counts in the names "shapeN").
    bool hasMtllib = false;
    for (const ObjPart& part : parts) hasMtllib = hasMtllib || part.hasMtllib;
    int overrideLine = -1;  // the override's library is read at the line of a first free line
    if (options.mtlOverride && !hasMtllib) {
        overrideLine = 0;  // or before the first line
        for (const ObjPart& part : parts) {
            if (part.freeLine >= 0) {
                overrideLine = part.freeLine;
                break;
            }
            if (!part.usemtlNames.empty()) break;
        }
    }
    std::set<std::string> knownNames;
    std::map<std::string, int> materialIds;  // tinyobjloader's material ids: by the libraries' order
    std::vector<std::uint32_t> sceneIndex;   // material id -> index in Scene::materials
    std::set<std::string> librariesRead;
    auto readLibrary = [&](const std::string& mtllib) {
        fs::path mtlFile = options.mtlOverride ? *options.mtlOverride : objFile.parent_path() / mtllib;
        std::error_code ec;
        if (!fs::exists(mtlFile, ec)) {  // one that exists but is no regular file is refused when read
            warn(objFile.string() + ": material library \"" + mtlFile.string() +
                 "\" not found; its faces get the default material");
            return;
        }
        for (const auto& [name, index] : library(mtlFile)) {
            knownNames.insert(name);
            if (materialIds.count(name)) continue;
            materialIds[name] = int(sceneIndex.size());
            sceneIndex.push_back(index);
        }
    };
    struct Shape {
        std::string name;
        std::size_t firstFace = 0, endFace = 0;
    };
    std::vector<Shape> shapes;
    std::vector<std::pair<std::size_t, int>> materialRuns = {{0, -1}};  // from a face on, a material id
    std::vector<std::string> readerWarnings;
    std::size_t shapeCount = 0;  // tinyobjloader's shapes, those without triangles too
    std::string name;
    std::size_t shapeFirstFace = 0;
    bool linesOrPoints = false;
    auto endShape = [&](std::size_t face, bool keepWithLines) {
        if (face > shapeFirstFace || (keepWithLines && linesOrPoints)) {
            if (face > shapeFirstFace) {
                std::string shown = name.substr(0, name.find_last_not_of(" \t\r") + 1);
                if (shown.empty()) shown = "shape" + std::to_string(shapeCount);
                shapes.push_back({std::move(shown), shapeFirstFace, face});
            }
            ++shapeCount;
        }
        shapeFirstFace = face;
        linesOrPoints = false;
    };
    for (std::size_t k = 0; k < parts.size(); ++k) {
        for (const ObjEvent& event : parts[k].events) {
            if (parts[k].readerErrorLine && event.line > parts[k].readerErrorLine) break;
            if (overrideLine >= 0 && event.line > overrideLine) {
                readLibrary("override");
                overrideLine = -1;
            }
            const std::size_t face = bases[k].faces + event.face;
            switch (event.kind) {
            case ObjEvent::Usemtl: {
                const auto found = materialIds.find(event.name);
                const int id = found == materialIds.end() ? -1 : found->second;
                if (materialRuns.back().first == face) materialRuns.back().second = id;
                else if (materialRuns.back().second != id) materialRuns.emplace_back(face, id);
                break;
            }
            case ObjEvent::Mtllib:
                for (const std::string& library : event.files) {
                    if (librariesRead.count(library)) continue;
                    readLibrary(library);
                    librariesRead.insert(library);
                    break;
                }
                break;
            case ObjEvent::Object:
            case ObjEvent::Group:
                endShape(face, event.kind == ObjEvent::Object);
                name = event.name;
                if (event.emptyGroup) readerWarnings.push_back("Empty group name. line: " + std::to_string(event.line));
                break;
            case ObjEvent::Degenerate:
                readerWarnings.emplace_back("Degenerated face found");
                break;
            case ObjEvent::LinesOrPoints:
                linesOrPoints = true;
                break;
            }
        }
        if (parts[k].readerErrorLine) {
            if (overrideLine >= 0 && overrideLine < parts[k].readerErrorLine) readLibrary("override");
            throw inputError(objFile, 0, parts[k].readerError);
        }
    }
    if (overrideLine >= 0) readLibrary("override");
    endShape(all.faces, false);
    for (const std::string& w : readerWarnings) warn(objFile.string() + ": " + w);
    for (const ObjPart& part : parts)
        for (const std::string& usemtl : part.usemtlNames)
            if (!knownNames.count(usemtl))
                warn(objFile.string() + ": material " + quoteInput(usemtl) +
                     " is not defined; its faces get the default material");

    // The vertices, normals and texture coordinates of all parts in one array each, and each
    // negative index counted from the part's start counted from the file's.
    auto gather = [&](std::vector<float> ObjPart::*values) {
        std::vector<float> gathered;
        std::size_t size = 0;
        for (const ObjPart& part : parts) size += (part.*values).size();
        gathered.reserve(size);
        for (ObjPart& part : parts) {
            gathered.insert(gathered.end(), (part.*values).begin(), (part.*values).end());
            std::vector<float>().swap(part.*values);
        }
        return gathered;
    };
    const std::vector<float> positions = gather(&ObjPart::positions);
    const std::vector<float> normals = gather(&ObjPart::normalValues);
    const std::vector<float> uvs = gather(&ObjPart::uvs);
    for (std::size_t k = 1; k < parts.size(); ++k)
        for (std::uint64_t at : parts[k].relative) {
            Corner& c = parts[k].corners[at / 3];
            int& index = at % 3 == 0 ? c.v : at % 3 == 1 ? c.vt : c.vn;
            const std::size_t base = at % 3 == 0 ? bases[k].vertices : at % 3 == 1 ? bases[k].texcoords : bases[k].normals;
            index = int(std::int64_t(index) + std::int64_t(base));
        }

    const glm::mat4& m = options.transform;
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
    const bool mirrored = glm::determinant(glm::mat3(m)) < 0.0f;  // keep the winding outward-facing
    const int vertexCount = int(positions.size() / 3);
    const int normalCount = int(normals.size() / 3);
    const int uvCount = int(uvs.size() / 2);
    const std::size_t firstTriangle = scene_.triangles.size();

    std::vector<std::uint32_t> objects(shapes.size());
    for (std::size_t s = 0; s < shapes.size(); ++s) {
        objects[s] = std::uint32_t(scene_.objectNames.size());
        scene_.objectNames.push_back(fileName + "/" + shapes[s].name);
    }
    bool defaultNeeded = false;
    for (std::size_t r = 0; r < materialRuns.size(); ++r) {
        const std::size_t end = r + 1 < materialRuns.size() ? materialRuns[r + 1].first : all.faces;
        defaultNeeded = defaultNeeded || (materialRuns[r].second < 0 && end > materialRuns[r].first);
    }
    const std::uint32_t defaultMaterial = defaultNeeded ? defaultMaterialIndex() : 0;
    // Room for the file's triangles at once, doubling still, so that many files stay linear.
    const std::size_t needed = firstTriangle + all.triangles;
    if (needed > scene_.triangles.capacity()) scene_.triangles.reserve(std::max(needed, 2 * scene_.triangles.capacity()));
    scene_.triangles.resize(needed);

    // The faces become triangles on every core, each in its place (issue 52: one core took
    // 0.4-0.6 s for a 3M-triangle model); a chunk's first error is the first of its faces, and
    // parallelFor rethrows the first chunk's: the file's first, as one core found it.
    const std::function<void(double)> triangleProgress = report("triangles of " + fileName);
    parallelFor(all.faces, [&](std::size_t begin, std::size_t end) {
        std::size_t k = std::size_t(std::upper_bound(bases.begin(), bases.end(), begin,
                                                     [](std::size_t f, const Base& b) { return f < b.faces; }) -
                                    bases.begin()) - 1;
        std::size_t s = std::size_t(std::upper_bound(shapes.begin(), shapes.end(), begin,
                                                     [](std::size_t f, const Shape& sh) { return f < sh.firstFace; }) -
                                    shapes.begin()) - 1;
        std::size_t r = std::size_t(std::upper_bound(materialRuns.begin(), materialRuns.end(), begin,
                                                     [](std::size_t f, const auto& run) { return f < run.first; }) -
                                    materialRuns.begin()) - 1;
        for (std::size_t f = begin; f < end; ++f) {
            // The calling thread's share tells how far all are (they run alike).
            if (triangleProgress && begin == 0 && f % 65536 == 0) triangleProgress(double(f) / double(end));
            while (f >= bases[k + 1].faces) ++k;
            while (f >= shapes[s].endFace) ++s;
            while (r + 1 < materialRuns.size() && f >= materialRuns[r + 1].first) ++r;
            const ObjPart& part = parts[k];
            const std::size_t local = f - bases[k].faces;
            const std::size_t offset = local ? part.faceEnds[local - 1] : 0;
            const std::size_t corners = part.faceEnds[local] - offset;
            const Corner* corner = part.corners.data() + offset;
            for (std::size_t c = 0; c < corners; ++c) {
                if (corner[c].v >= 0 && corner[c].v < vertexCount && corner[c].vn >= -1 && corner[c].vn < normalCount &&
                    corner[c].vt >= -1 && corner[c].vt < uvCount)
                    continue;  // in range (-1: none), the checks below pass
                auto check = [&](int index, int count, bool optional, const char* what) {
                    if ((optional && index == -1) || (index >= 0 && index < count)) return;
                    std::string problem = index < 0 ? "an index before the first of its " + std::string(what)
                                                    : "index " + std::to_string(index + 1) + ", but the file has " +
                                                          std::to_string(count) + " " + what;
                    throw inputError(objFile, 0, "a face of " + quoteInput(shapes[s].name) + " uses " + problem);
                };
                check(corner[c].v, vertexCount, false, "vertices");
                check(corner[c].vn, normalCount, true, "normals");
                check(corner[c].vt, uvCount, true, "texture coordinates");
            }
            const int id = materialRuns[r].second;
            const std::uint32_t material = id >= 0 ? sceneIndex[std::size_t(id)] : defaultMaterial;
            const std::size_t faceTriangle = firstTriangle + bases[k].triangles + offset - 2 * local;
            // Fan triangulation: exact for triangles and convex polygons, which is what exporters write.
            for (std::size_t i = 1; i + 1 < corners; ++i) {
                std::size_t c[3] = {0, i, i + 1};
                if (mirrored) std::swap(c[1], c[2]);
                Triangle& t = scene_.triangles[faceTriangle + i - 1];
                t.material = material;
                t.object = objects[s];
                for (int j = 0; j < 3; ++j) {
                    const Corner& idx = corner[c[j]];
                    const float* p = &positions[3 * std::size_t(idx.v)];
                    t.position[j] = glm::vec3(m * glm::vec4(p[0], p[1], p[2], 1.0f));
                    if (!std::isfinite(t.position[j].x) || !std::isfinite(t.position[j].y) || !std::isfinite(t.position[j].z))
                        throw inputError(objFile, 0, "vertex " + std::to_string(idx.v + 1) + " is not finite after the transform");
                    t.uv[j] = idx.vt >= 0 ? glm::vec2(uvs[2 * std::size_t(idx.vt)], uvs[2 * std::size_t(idx.vt) + 1]) : glm::vec2(0.0f);
                }
                glm::vec3 geometric = glm::cross(t.position[1] - t.position[0], t.position[2] - t.position[0]);
                float length = glm::length(geometric);
                // A zero-area triangle is kept; it still gets a valid unit normal. A repeated corner is
                // never hit; distinct collinear corners can be, by rounding (docs/hard-cases.md).
                geometric = length > 0.0f && std::isfinite(length) ? geometric / length : glm::vec3(0.0f, 0.0f, 1.0f);
                for (int j = 0; j < 3; ++j) {
                    const int ni = corner[c[j]].vn;
                    glm::vec3 n(0.0f);
                    if (ni >= 0) {
                        const float* v = &normals[3 * std::size_t(ni)];
                        n = normalMatrix * glm::vec3(v[0], v[1], v[2]);
                    }
                    float nl = glm::length(n);
                    t.normal[j] = nl > 0.0f && std::isfinite(nl) ? n / nl : geometric;
                }
            }
        }
    });
    if (scene_.triangles.size() == firstTriangle) throw inputError(objFile, 0, "contains no triangles");
}

}  // namespace vitrum
