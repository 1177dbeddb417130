#include "scene/obj_loader.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <set>
#include <istream>
#include <sstream>
#include <streambuf>
#include <tuple>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "common/error.h"
#include "common/parallel.h"
#include "common/float_text.h"
#include "common/input_file.h"
#include "image/image.h"
#include "scene/mtl_material.h"
#include "scene/mtl_parser.h"
#include "scene/quote_input.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& file) { return readInputLines(file, "the OBJ file", kMaxObjFileBytes); }

// The OBJ's text as tinyobjloader reads it, a chunk at a time, telling how far it has read (an
// istringstream copied the text first: one more copy of a 100 MB file).
class TextStream : public std::streambuf {
public:
    TextStream(std::string& text, std::function<void(double)> progress)
        : text_(text), progress_(std::move(progress)) {}

protected:
    int_type underflow() override {
        if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
        if (next_ >= text_.size()) return traits_type::eof();
        if (progress_) progress_(double(next_) / double(text_.size()));
        const std::size_t count = std::min(kChunk, text_.size() - next_);
        char* begin = text_.data() + next_;
        setg(begin, begin, begin + count);
        next_ += count;
        return traits_type::to_int_type(*gptr());
    }

private:
    static constexpr std::size_t kChunk = std::size_t(1) << 20;
    std::string& text_;
    std::function<void(double)> progress_;
    std::size_t next_ = 0;
};

std::string_view firstWord(std::string_view line, std::size_t* end = nullptr) {
    std::size_t begin = line.find_first_not_of(" \t");
    if (begin == std::string_view::npos) return {};
    std::size_t stop = std::min(line.find_first_of(" \t", begin), line.size());
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

// What tinyobjloader does not tell: it reads "nan" or an unparsable coordinate as 0 and has no
// line numbers for its own checks, so vertex lines (and face indices and exponents it would read
// with overflows) are checked here first. Also notes the
// mtllib and usemtl statements, and a line that can hold an inserted mtllib statement.
struct ObjScan {
    // The v, vn, vt and f statements (faces of three corners or more) and the faces' corners: what
    // tinyobjloader returns is checked against them, since a line it reads differently from this
    // scan would shift every index after it, or change a face, without an error.
    std::size_t vertices = 0, normals = 0, texcoords = 0, faces = 0, corners = 0;
    std::vector<std::size_t> skinWeights;  // where each "vw" statement begins
    bool hasMtllib = false;
    std::vector<std::string> usemtlNames;
    std::size_t freeLineBegin = std::string::npos, freeLineEnd = 0;  // a blank or comment line before any usemtl
};

// Scans the whole lines text[from, to), which follow `linesBefore` lines.
ObjScan scanLines(const fs::path& file, std::string_view text, std::size_t from, std::size_t to, int linesBefore) {
    ObjScan scan;
    bool seenUsemtl = false;
    int lineNumber = linesBefore;
    for (std::size_t begin = from; begin < to;) {
        std::size_t end = std::min(text.find('\n', begin), text.size());
        std::string_view line = text.substr(begin, end - begin);  // readInputLines ended every line in '\n'
        ++lineNumber;
        std::size_t wordEnd = 0;
        std::string_view word = firstWord(line, &wordEnd);
        if (word.empty() || word.front() == '#') {
            if (!seenUsemtl && scan.freeLineBegin == std::string::npos) {
                scan.freeLineBegin = begin;
                scan.freeLineEnd = begin + line.size();
            }
        } else if (word == "v") {
            ++scan.vertices;
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
            // tinyobjloader reads indices with atoi, which stops where a number does ("1.5" is
            // vertex 1) and wraps one beyond the int range around ("4294967299" is vertex 3): each
            // index must be an integer in full, in the int range.
            std::size_t corners = 0;
            for (std::string_view rest = line.substr(wordEnd);;) {
                std::size_t cornerEnd = 0;
                std::string_view corner = firstWord(rest, &cornerEnd);
                if (corner.empty()) break;
                ++corners;
                for (std::size_t part = 0; part <= corner.size();) {
                    std::size_t slash = std::min(corner.find('/', part), corner.size());
                    std::string_view index = corner.substr(part, slash - part);
                    if (!index.empty() && index.front() == '+') index.remove_prefix(1);
                    long long value = 0;
                    auto [ptr, ec] = std::from_chars(index.data(), index.data() + index.size(), value);
                    if (ec == std::errc::result_out_of_range || value > std::numeric_limits<int>::max() ||
                        value < -std::numeric_limits<int>::max())
                        throw inputError(file, lineNumber, "face index " + quoteInput(index) + " is out of range");
                    if (ptr != index.data() + index.size())  // an empty one tinyobjloader reports as 0
                        throw inputError(file, lineNumber, "face corner " + quoteInput(corner) +
                                                               " is not v, v/vt, v//vn or v/vt/vn in integers");
                    part = slash + 1;
                }
                rest = rest.substr(cornerEnd);
            }
            if (corners >= 3) {  // tinyobjloader drops a face of fewer, with a warning
                ++scan.faces;
                scan.corners += corners;
            }
        } else if (word == "vn" || word == "vt" || word == "vp") {
            if (word == "vn") ++scan.normals;
            if (word == "vt") ++scan.texcoords;
            // tinyobjloader reads an exponent into an int that overflows (undefined behaviour) at
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
            scan.skinWeights.push_back(begin + std::size_t(word.data() - line.data()));
        } else if (word == "mtllib") {
            scan.hasMtllib = true;
        } else if (word == "usemtl") {
            seenUsemtl = true;
            scan.usemtlNames.emplace_back(firstWord(line.substr(wordEnd)));
        }
        begin = end + 1;
    }
    return scan;
}

// The scan of a big file in parts, one a core, each from a line's start: the parts' counts and
// statements joined in order, and the error of the first part that has one, which is the file's
// first (issue 52; docs/gpu-design.md, "A big model to the image as fast as an Embree renderer").
ObjScan scanObj(const fs::path& file, std::string_view text) {
    constexpr std::size_t kBytesAPart = std::size_t(16) << 20;
    const std::size_t parts = std::clamp<std::size_t>(text.size() / kBytesAPart, 1, std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::size_t> starts = {0};
    for (std::size_t k = 1; k < parts; ++k) {
        const std::size_t lineEnd = text.find('\n', std::max(starts.back(), text.size() * k / parts));
        starts.push_back(lineEnd == std::string_view::npos ? text.size() : lineEnd + 1);
    }
    starts.push_back(text.size());
    std::vector<ObjScan> scans(parts);
    std::vector<std::exception_ptr> failed(parts);
    auto scanPart = [&](std::size_t k) {
        try {
            const int linesBefore = int(std::count(text.begin(), text.begin() + std::ptrdiff_t(starts[k]), '\n'));
            scans[k] = scanLines(file, text, starts[k], starts[k + 1], linesBefore);
        } catch (...) {
            failed[k] = std::current_exception();
        }
    };
    std::vector<std::thread> threads;
    try {
        for (std::size_t k = 1; k < parts; ++k) threads.emplace_back(scanPart, k);
    } catch (...) {  // a thread that cannot start (no memory for its stack): those started end first
        for (std::thread& t : threads) t.join();
        throw;
    }
    scanPart(0);
    for (std::thread& t : threads) t.join();
    for (const std::exception_ptr& e : failed)
        if (e) std::rethrow_exception(e);

    ObjScan scan = std::move(scans[0]);
    bool usemtlBefore = !scan.usemtlNames.empty();
    for (std::size_t k = 1; k < parts; ++k) {
        ObjScan& part = scans[k];
        scan.vertices += part.vertices;
        scan.normals += part.normals;
        scan.texcoords += part.texcoords;
        scan.faces += part.faces;
        scan.corners += part.corners;
        scan.skinWeights.insert(scan.skinWeights.end(), part.skinWeights.begin(), part.skinWeights.end());
        scan.hasMtllib = scan.hasMtllib || part.hasMtllib;
        // A part's free line counts if no usemtl came before it in the file.
        if (scan.freeLineBegin == std::string::npos && !usemtlBefore) {
            scan.freeLineBegin = part.freeLineBegin;
            scan.freeLineEnd = part.freeLineEnd;
        }
        usemtlBefore = usemtlBefore || !part.usemtlNames.empty();
        scan.usemtlNames.insert(scan.usemtlNames.end(), std::make_move_iterator(part.usemtlNames.begin()),
                                std::make_move_iterator(part.usemtlNames.end()));
    }
    return scan;
}

// Hands tinyobjloader the names of our own materials (parsed by mtl_parser with line numbers),
// so that its material ids map back to scene materials.
class LibraryReader : public tinyobj::MaterialReader {
public:
    using Lookup = std::function<const std::map<std::string, std::uint32_t>*(const std::string& mtllib)>;
    explicit LibraryReader(Lookup lookup) : lookup_(std::move(lookup)) {}

    bool operator()(const std::string& mtllib, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* names, std::string*, std::string*) override {
        if (const auto* library = lookup_(mtllib)) {
            for (const auto& [name, index] : *library) {
                if (names->count(name)) continue;
                (*names)[name] = int(materials->size());
                materials->emplace_back().name = name;
                sceneIndex.push_back(index);
            }
        }
        return true;  // a missing library was reported by lookup_; tinyobj need not say it again
    }

    std::vector<std::uint32_t> sceneIndex;  // tinyobj material id -> index in Scene::materials

private:
    Lookup lookup_;
};

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
        if (entry.mapKd) {
            std::string name = *entry.mapKd;
            std::replace(name.begin(), name.end(), '\\', '/');  // Windows exporters write backslashes
            material.diffuseTexture = texture(mtlFile.parent_path() / name, mtlFile, entry.mapKdLine);
        }
        library[entry.name] = std::uint32_t(scene_.materials.size());
        scene_.materials.push_back(std::move(material));
    }
    return libraries_[key] = std::move(library);
}

int ObjLoader::texture(const fs::path& imageFile, const fs::path& mtlFile, int line) {
    fs::path key = fileKey(imageFile);
    if (auto found = textures_.find(key); found != textures_.end()) return found->second;
    int index = -1;
    try {
        Image image = readImage(imageFile, options_.texelLimit.leftAfter(scene_));
        index = int(scene_.textures.size());
        scene_.textures.push_back(Texture{imageFile, int(image.width), int(image.height), std::move(image.pixels)});
    } catch (const ImageTooLarge& e) {
        throw inputError(mtlFile, line, std::string("map_Kd ") + e.what());
    } catch (const InputError& e) {
        warn(mtlFile.string() + ":" + std::to_string(line) + ": texture cannot be read (" + e.what() +
             "); using Kd instead");
    }
    return textures_[key] = index;
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
    ObjScan scan = scanObj(objFile, text);
    // A face of n corners makes n - 2 triangles (fanned below).
    if (options_.checkTriangles) options_.checkTriangles(scene_.triangles.size() + scan.corners - 2 * scan.faces);
    // Skin weights ("vw", tinyobjloader's extension of OBJ) mean nothing to a ray tracer, and
    // tinyobjloader converts their joint numbers to int unchecked (undefined behaviour beyond
    // the int range, found by fuzzing): they become comments, and the lines keep their numbers.
    for (std::size_t at : scan.skinWeights) text[at] = '#';
    if (!scan.skinWeights.empty())
        warn(objFile.string() + ": " + std::to_string(scan.skinWeights.size()) + " skin weight (vw) lines ignored");
    if (options.mtlOverride && !scan.hasMtllib) {
        // The override comes in through tinyobj's mtllib hook: give it an mtllib statement on a
        // free line, so that tinyobj's line numbers stay those of the file.
        if (scan.freeLineBegin != std::string::npos)
            text.replace(scan.freeLineBegin, scan.freeLineEnd - scan.freeLineBegin, "mtllib override");
        else
            text.insert(0, "mtllib override\n");
    }

    std::set<std::string> knownNames;
    LibraryReader reader([&](const std::string& mtllib) -> const Library* {
        fs::path mtlFile = options.mtlOverride ? *options.mtlOverride : objFile.parent_path() / mtllib;
        std::error_code ec;
        if (!fs::exists(mtlFile, ec)) {  // one that exists but is no regular file is refused when read
            warn(objFile.string() + ": material library \"" + mtlFile.string() +
                 "\" not found; its faces get the default material");
            return nullptr;
        }
        const Library& found = library(mtlFile);
        for (const auto& entry : found) knownNames.insert(entry.first);
        return &found;
    });

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> tinyMaterials;
    std::string warnings, errors;
    const std::string fileName = objFile.filename().string();
    auto report = [&](const std::string& phase) -> std::function<void(double)> {
        if (!options_.progress) return {};
        return [this, phase](double fraction) { options_.progress(phase, fraction); };
    };
    TextStream textStream(text, report("parsing " + fileName));
    std::istream stream(&textStream);
    // No triangulation by tinyobj: it reads vertices of quads and polygons before any index check.
    bool ok = tinyobj::LoadObj(&attrib, &shapes, &tinyMaterials, &warnings, &errors, &stream, &reader, false);
    auto oneLine = [](std::string s) {
        std::replace(s.begin(), s.end(), '\n', ' ');
        return std::string(s.begin(), std::find_if(s.rbegin(), s.rend(), [](char c) { return c != ' '; }).base());
    };
    if (!ok || !errors.empty()) throw inputError(objFile, 0, oneLine(errors.empty() ? "unreadable OBJ" : errors));
    std::istringstream warningLines(warnings);
    for (std::string w; std::getline(warningLines, w);) {
        w.erase(0, w.find_first_not_of(". "));  // tinyobj ends some warnings with "\n."
        // Unknown material names are reported below with their names; index checks are ours.
        if (!w.empty() && w.find("not found in .mtl") == std::string::npos &&
            w.find("out of bounds") == std::string::npos)
            warn(objFile.string() + ": " + w);
    }
    for (const std::string& name : scan.usemtlNames) {
        if (!knownNames.count(name))
            warn(objFile.string() + ": material " + quoteInput(name) +
                 " is not defined; its faces get the default material");
    }

    const glm::mat4& m = options.transform;
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
    const bool mirrored = glm::determinant(glm::mat3(m)) < 0.0f;  // keep the winding outward-facing
    const int vertexCount = int(attrib.vertices.size() / 3);
    const int normalCount = int(attrib.normals.size() / 3);
    const int uvCount = int(attrib.texcoords.size() / 2);
    std::size_t faceCount = 0, cornerCount = 0;
    for (const tinyobj::shape_t& shape : shapes) {
        faceCount += shape.mesh.num_face_vertices.size();
        cornerCount += shape.mesh.indices.size();
    }
    for (const auto& [kind, read, lines] : {std::tuple{"vertices", std::size_t(vertexCount), scan.vertices},
                                            std::tuple{"normals", std::size_t(normalCount), scan.normals},
                                            std::tuple{"texture coordinates", std::size_t(uvCount), scan.texcoords},
                                            std::tuple{"faces", faceCount, scan.faces},
                                            std::tuple{"face corners", cornerCount, scan.corners}})
        if (read != lines)
            throw inputError(objFile, 0, std::string("the OBJ reader returned ") + std::to_string(read) + " " + kind +
                                             " where the file has " + std::to_string(lines) +
                                             " statements for them: some line is not what it seems");
    const std::size_t firstTriangle = scene_.triangles.size();

    // Where each face's corners and triangles begin (a fan of n corners makes n - 2), shape by
    // shape, and each shape's object: the faces then become triangles on every core, each in its
    // place (issue 52: one core took 0.4-0.6 s for a 3M-triangle model).
    struct ShapeFaces {
        std::vector<std::size_t> firstCorner, firstTriangle;
        std::uint32_t object = 0;
        std::string name;
    };
    std::vector<ShapeFaces> faces(shapes.size());
    std::size_t triangleCount = 0;
    bool defaultNeeded = false;
    for (std::size_t s = 0; s < shapes.size(); ++s) {
        const tinyobj::mesh_t& mesh = shapes[s].mesh;
        ShapeFaces& shape = faces[s];
        shape.name = shapes[s].name;
        shape.name.erase(shape.name.find_last_not_of(" \t\r") + 1);
        if (shape.name.empty()) shape.name = "shape" + std::to_string(s);
        shape.object = std::uint32_t(scene_.objectNames.size());
        shape.firstCorner.resize(mesh.num_face_vertices.size());
        shape.firstTriangle.resize(mesh.num_face_vertices.size());
        const std::size_t before = triangleCount;
        std::size_t corner = 0;
        for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
            shape.firstCorner[f] = corner;
            shape.firstTriangle[f] = firstTriangle + triangleCount;
            const std::size_t corners = mesh.num_face_vertices[f];
            corner += corners;
            if (corners >= 3) triangleCount += corners - 2;
            const int tinyMaterial = mesh.material_ids[f];
            defaultNeeded = defaultNeeded || !(tinyMaterial >= 0 && std::size_t(tinyMaterial) < reader.sceneIndex.size());
        }
        if (triangleCount > before) scene_.objectNames.push_back(objFile.filename().string() + "/" + shape.name);
    }
    const std::uint32_t defaultMaterial = defaultNeeded ? defaultMaterialIndex() : 0;
    // Room for the file's triangles at once, doubling still, so that many files stay linear.
    const std::size_t needed = firstTriangle + triangleCount;
    if (needed > scene_.triangles.capacity()) scene_.triangles.reserve(std::max(needed, 2 * scene_.triangles.capacity()));
    scene_.triangles.resize(needed);

    const std::function<void(double)> triangleProgress = report("triangles of " + fileName);
    std::size_t facesBefore = 0;
    for (std::size_t s = 0; s < shapes.size(); ++s) {
        const tinyobj::mesh_t& mesh = shapes[s].mesh;
        const ShapeFaces& shape = faces[s];
        // The faces [begin, end) of this shape; a chunk's first error is the first of its faces, and
        // parallelFor rethrows the first chunk's: the file's first, as one core found it.
        parallelFor(mesh.num_face_vertices.size(), [&](std::size_t begin, std::size_t end) {
            for (std::size_t f = begin; f < end; ++f) {
                // The calling thread's share tells how far all are (they run alike).
                if (triangleProgress && begin == 0 && f % 65536 == 0)
                    triangleProgress((double(facesBefore) + double(f) / double(end) * double(mesh.num_face_vertices.size())) /
                                     double(std::max<std::size_t>(faceCount, 1)));
                const std::size_t offset = shape.firstCorner[f];
                const std::size_t corners = mesh.num_face_vertices[f];
                for (std::size_t k = 0; k < corners; ++k) {
                    const tinyobj::index_t& idx = mesh.indices[offset + k];
                    auto check = [&](int index, int count, bool optional, const char* what) {
                        if ((optional && index == -1) || (index >= 0 && index < count)) return;
                        std::string problem = index < 0 ? "an index before the first of its " + std::string(what)
                                                        : "index " + std::to_string(index + 1) + ", but the file has " +
                                                              std::to_string(count) + " " + what;
                        throw inputError(objFile, 0, "a face of " + quoteInput(shape.name) + " uses " + problem);
                    };
                    check(idx.vertex_index, vertexCount, false, "vertices");
                    check(idx.normal_index, normalCount, true, "normals");
                    check(idx.texcoord_index, uvCount, true, "texture coordinates");
                }
                const int tinyMaterial = mesh.material_ids[f];
                const std::uint32_t material = tinyMaterial >= 0 && std::size_t(tinyMaterial) < reader.sceneIndex.size()
                                                   ? reader.sceneIndex[std::size_t(tinyMaterial)]
                                                   : defaultMaterial;
                // Fan triangulation: exact for triangles and convex polygons, which is what exporters write.
                for (std::size_t k = 1; k + 1 < corners; ++k) {
                    std::size_t c[3] = {offset, offset + k, offset + k + 1};
                    if (mirrored) std::swap(c[1], c[2]);
                    Triangle& t = scene_.triangles[shape.firstTriangle[f] + k - 1];
                    t.material = material;
                    t.object = shape.object;
                    for (int i = 0; i < 3; ++i) {
                        const tinyobj::index_t& idx = mesh.indices[c[i]];
                        const tinyobj::real_t* p = &attrib.vertices[3 * std::size_t(idx.vertex_index)];
                        t.position[i] = glm::vec3(m * glm::vec4(float(p[0]), float(p[1]), float(p[2]), 1.0f));
                        if (!std::isfinite(t.position[i].x) || !std::isfinite(t.position[i].y) ||
                            !std::isfinite(t.position[i].z))
                            throw inputError(objFile, 0,
                                             "vertex " + std::to_string(idx.vertex_index + 1) +
                                                 " is not finite after the transform");
                        const tinyobj::real_t* uv =
                            idx.texcoord_index >= 0 ? &attrib.texcoords[2 * std::size_t(idx.texcoord_index)] : nullptr;
                        t.uv[i] = uv ? glm::vec2(float(uv[0]), float(uv[1])) : glm::vec2(0.0f);
                    }
                    glm::vec3 geometric = glm::cross(t.position[1] - t.position[0], t.position[2] - t.position[0]);
                    float length = glm::length(geometric);
                    // A zero-area triangle is kept; it still gets a valid unit normal. A repeated corner is
                    // never hit; distinct collinear corners can be, by rounding (docs/hard-cases.md).
                    geometric = length > 0.0f && std::isfinite(length) ? geometric / length : glm::vec3(0.0f, 0.0f, 1.0f);
                    for (int i = 0; i < 3; ++i) {
                        const int ni = mesh.indices[c[i]].normal_index;
                        glm::vec3 n(0.0f);
                        if (ni >= 0) {
                            const tinyobj::real_t* v = &attrib.normals[3 * std::size_t(ni)];
                            n = normalMatrix * glm::vec3(float(v[0]), float(v[1]), float(v[2]));
                        }
                        float nl = glm::length(n);
                        t.normal[i] = nl > 0.0f && std::isfinite(nl) ? n / nl : geometric;
                    }
                }
            }
        });
        facesBefore += mesh.num_face_vertices.size();
    }
    if (scene_.triangles.size() == firstTriangle) throw inputError(objFile, 0, "contains no triangles");
}

}  // namespace vitrum
