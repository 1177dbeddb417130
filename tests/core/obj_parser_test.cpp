// vitrum parses OBJ files itself, in parts on every core, as tinyobjloader parsed them on one
// (host/scene/obj_loader.cpp): its relative indices, shapes and materials across the parts'
// borders, worked out by hand, and every triangle the same, bit for bit, as the triangles made
// from tinyobjloader's LoadObj before, over random files of what OBJ writers write.
#include "scene/obj_loader.h"

#include <gtest/gtest.h>
#include <tiny_obj_loader.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "scene/mtl_material.h"
#include "scene/mtl_parser.h"

#include "../support/temporary_folder_test.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

// Each test in a folder of its own (dir_).
class ObjParser : public testing::TemporaryFolderTest {};

fs::path write(const fs::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
    return file;
}

Scene loadInParts(const fs::path& obj, std::size_t parts) {
    Scene scene;
    ObjOptions options;
    options.parts = parts;
    ObjLoader(scene).load(obj, options);
    return scene;
}

std::string materialOf(const Scene& scene, const Triangle& t) { return scene.materials[t.material].name; }
std::string objectOf(const Scene& scene, const Triangle& t) { return scene.objectNames[t.object]; }

// Negative indices count back from the statements read so far, across the parts' borders: each
// face takes the three vertices just before it, and the one normal, in every split of the file.
TEST_F(ObjParser, RelativeIndicesCountFromTheWholeFileInEveryPart) {
    std::string text;
    for (int i = 0; i < 40; ++i) {
        text += "v " + std::to_string(i) + " 0 0\nv " + std::to_string(i) + " 1 0\nv " + std::to_string(i) + " 0 1\n";
        text += "vn 0 " + std::to_string(i + 1) + " 0\n";
        text += "f -3//-1 -2//-1 -1//-1\n";
    }
    const fs::path obj = write(dir_ / "relative.obj", text);
    for (std::size_t parts : {1, 2, 3, 7, 40, 200}) {
        const Scene scene = loadInParts(obj, parts);
        ASSERT_EQ(scene.triangles.size(), 40u) << parts;
        for (int i = 0; i < 40; ++i) {
            const Triangle& t = scene.triangles[std::size_t(i)];
            EXPECT_EQ(t.position[0], glm::vec3(float(i), 0, 0)) << parts << " parts, face " << i;
            EXPECT_EQ(t.position[1], glm::vec3(float(i), 1, 0)) << parts << " parts, face " << i;
            EXPECT_EQ(t.position[2], glm::vec3(float(i), 0, 1)) << parts << " parts, face " << i;
            EXPECT_EQ(t.normal[0], glm::vec3(0, 1, 0)) << parts << " parts, face " << i;  // normalized
        }
    }
    // A negative index before the file's first vertex is named, however the file is split.
    const fs::path before = write(dir_ / "before.obj", text + "f -121 -1 -2\n");
    for (std::size_t parts : {1, 3}) {
        try {
            loadInParts(before, parts);
            ADD_FAILURE() << "no error";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("an index before the first of its vertices"), std::string::npos) << e.what();
        }
    }
}

// o and g begin a shape (one object each, in the file's order), usemtl changes the material of
// the faces after it without beginning one, and a material outlives its shape; a shape without
// a name is "shapeN", N counting tinyobjloader's shapes, an o's of lines only among them.
TEST_F(ObjParser, ObjectsGroupsAndMaterialsAsTinyobjloaderMadeThem) {
    const fs::path& dir = dir_;
    write(dir / "m.mtl", "newmtl red\nshader 2\nKd 1 0 0\nnewmtl glass\nshader 4\nNi 1.5\n");
    const std::string text =
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
        "usemtl glass\n"  // before the library: no such material yet
        "f 1 2 3\n"       // shape 0, unnamed
        "mtllib m.mtl\n"
        "o first\n"
        "usemtl red\nf 1 2 3\n"
        "usemtl glass\nf 2 4 3\n"  // still "first"
        "g \n"                     // a group without a name: shape 2, a warning
        "f 1 4 3\n"
        "o lines\nl 1 2\n"  // shape 3: lines only, no object
        "o \n"              // shape 4, unnamed
        "f 1 2 4\n";
    for (std::size_t parts : {1, 2, 4, 9, 30}) {
        // A file of another path each time: a warning is given once.
        const fs::path obj = dir / std::to_string(parts) / "shapes.obj";
        fs::create_directories(obj.parent_path());
        fs::copy_file(dir / "m.mtl", obj.parent_path() / "m.mtl");
        write(obj, text);
        const int warningsBefore = warningCount();
        const Scene scene = loadInParts(obj, parts);
        EXPECT_EQ(warningCount(), warningsBefore + 1) << parts;  // the empty group name
        EXPECT_EQ(scene.objectNames, (std::vector<std::string>{"shapes.obj/shape0", "shapes.obj/first",
                                                               "shapes.obj/shape2", "shapes.obj/shape4"}))
            << parts;
        ASSERT_EQ(scene.triangles.size(), 5u);
        const std::vector<std::string> objects = {"shape0", "first", "first", "shape2", "shape4"};
        const std::vector<std::string> materials = {"default", "red", "glass", "glass", "glass"};
        for (std::size_t i = 0; i < 5; ++i) {
            EXPECT_EQ(objectOf(scene, scene.triangles[i]), "shapes.obj/" + objects[i]) << parts << " parts, triangle " << i;
            EXPECT_EQ(materialOf(scene, scene.triangles[i]), materials[i]) << parts << " parts, triangle " << i;
        }
    }
}

// A shape that runs on over the parts' borders stays one object; a face of fewer than three
// corners is dropped with a warning; a polygon is a fan of triangles from its first corner.
TEST_F(ObjParser, AShapeSplitAcrossPartsIsOneObject) {
    std::string text = "o grid\n";
    for (int i = 0; i < 30; ++i) text += "v " + std::to_string(i) + " 0 0\nv " + std::to_string(i) + " 1 0\n";
    for (int i = 0; i + 1 < 30; ++i) {
        const int a = 2 * i + 1;
        text += "f " + std::to_string(a) + " " + std::to_string(a + 2) + " " + std::to_string(a + 3) + " " +
                std::to_string(a + 1) + "\n";
        if (i == 10) text += "f 1 2\n";
    }
    text += "g second\nf 1 3 4\n";
    const fs::path& dir = dir_;
    for (std::size_t parts : {1, 2, 5, 16}) {
        const fs::path obj = dir / std::to_string(parts) / "grid.obj";
        fs::create_directories(obj.parent_path());
        write(obj, text);
        const int warningsBefore = warningCount();
        const Scene scene = loadInParts(obj, parts);
        EXPECT_EQ(warningCount(), warningsBefore + 1) << parts;  // the face of two corners
        EXPECT_EQ(scene.objectNames, (std::vector<std::string>{"grid.obj/grid", "grid.obj/second"})) << parts;
        ASSERT_EQ(scene.triangles.size(), 2u * 29 + 1) << parts;
        for (int i = 0; i < 29; ++i) {
            const Triangle& first = scene.triangles[2 * std::size_t(i)];
            const Triangle& second = scene.triangles[2 * std::size_t(i) + 1];
            EXPECT_EQ(first.object, 0u);
            EXPECT_EQ(first.position[0], glm::vec3(float(i), 0, 0)) << parts;
            EXPECT_EQ(first.position[2], glm::vec3(float(i + 1), 1, 0)) << parts;
            EXPECT_EQ(second.position[0], glm::vec3(float(i), 0, 0)) << parts;
            EXPECT_EQ(second.position[1], glm::vec3(float(i + 1), 1, 0)) << parts;
            EXPECT_EQ(second.position[2], glm::vec3(float(i), 1, 0)) << parts;
        }
        EXPECT_EQ(scene.triangles.back().object, 1u);
    }
}

// A polygon of 256 corners or more is a fan of them all: tinyobjloader kept a face's corner count
// in 8 bits, and the loader made triangles of the wrong corners after it.
TEST_F(ObjParser, APolygonOfThreeHundredCornersIsOneFan) {
    std::string text;
    for (int i = 0; i < 300; ++i) text += "v " + std::to_string(i) + " " + std::to_string(i * i) + " 0\n";  // convex
    text += "f";
    for (int i = 1; i <= 300; ++i) text += ' ' + std::to_string(i);
    text += "\nf 1 2 3\n";
    const Scene scene = loadInParts(write(dir_ / "polygon.obj", text), 1);
    ASSERT_EQ(scene.triangles.size(), 298u + 1u);
    for (int i = 0; i < 298; ++i) {  // corners 1, i + 2, i + 3
        const Triangle& t = scene.triangles[std::size_t(i)];
        EXPECT_EQ(t.position[0], glm::vec3(0, 0, 0)) << i;
        EXPECT_EQ(t.position[1], glm::vec3(float(i + 1), float((i + 1) * (i + 1)), 0)) << i;
        EXPECT_EQ(t.position[2], glm::vec3(float(i + 2), float((i + 2) * (i + 2)), 0)) << i;
    }
    EXPECT_EQ(scene.triangles[298].position[2], glm::vec3(2, 4, 0));
}

// An index tinyobjloader reads as 0 (an empty part, "/2", a fourth part) is its error, with its
// line; an error of vitrum's own checks later in the file comes first, and a library after the
// refused line is never read.
TEST_F(ObjParser, ZeroIndicesAreTinyobjloadersErrorsWithTheirLine) {
    const fs::path& dir = dir_;
    const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (const char* face : {"f 1 0 2", "f 1 2 /3", "f 1/1/1/1 2 3", "f 1 2 3/"}) {
        const fs::path obj = write(dir / "zero.obj", vertices + "vt 0 0\nvn 0 0 1\n" + face + "\nmtllib none.mtl\n");
        for (std::size_t parts : {1, 3}) {
            const int warningsBefore = warningCount();
            try {
                loadInParts(obj, parts);
                ADD_FAILURE() << face;
            } catch (const InputError& e) {
                EXPECT_NE(std::string(e.what()).find("Failed parse `f' line(e.g. zero value for face index. line 6.)"),
                          std::string::npos)
                    << face << ": " << e.what();
            }
            EXPECT_EQ(warningCount(), warningsBefore) << face;  // none.mtl was never looked for
        }
    }
    const fs::path obj = write(dir / "line.obj", vertices + "l 1 0\nf 1 2 3\n");
    try {
        loadInParts(obj, 1);
        ADD_FAILURE();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("Failed parse `l' line(e.g. zero value for vertex index. line 4.)"),
                  std::string::npos)
            << e.what();
    }
    try {
        loadInParts(write(dir / "both.obj", vertices + "f 1 0 2\nv 1 x 0\n"), 1);
        ADD_FAILURE();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("both.obj:5:"), std::string::npos) << e.what();
    }
}

// --- The same triangles as tinyobjloader's, over random files ---

// A number as OBJ writers write it, in one of many forms, some of which tinyobjloader does not
// round correctly (more than seven decimals, exponents).
std::string number(std::mt19937& random) {
    std::uniform_real_distribution<double> value(-100.0, 100.0);
    const double x = value(random);
    char text[64];
    switch (random() % 9) {
    case 0: std::snprintf(text, sizeof text, "%.7f", x); break;
    case 1: std::snprintf(text, sizeof text, "%.12f", x / 7.0); break;
    case 2: std::snprintf(text, sizeof text, "%.6e", x); break;
    case 3: std::snprintf(text, sizeof text, "%.9E", x * 1e-5); break;
    case 4: std::snprintf(text, sizeof text, "%d", int(x)); break;
    case 5: std::snprintf(text, sizeof text, "%+.3f", x); break;
    case 6: std::snprintf(text, sizeof text, "%.4f", x / 1000.0); break;  // "0.0123", "-0.0456"
    case 7: std::snprintf(text, sizeof text, "%.17g", x); break;
    default: std::snprintf(text, sizeof text, "%.1f", x); break;
    }
    std::string s = text;
    if (random() % 10 == 0 && s.rfind("0.", 0) == 0) s.erase(0, 1);  // ".25"
    if (random() % 10 == 0 && s.rfind("-0.", 0) == 0) s.erase(1, 1);  // "-.25"
    return s;
}

std::string space(std::mt19937& random) {
    switch (random() % 8) {
    case 0: return "  ";
    case 1: return "\t";
    default: return " ";
    }
}

// A random OBJ file of the statements tinyobjloader knows, every index in range.
std::string randomObj(std::mt19937& random, int statements) {
    std::string text;
    int v = 0, vt = 0, vn = 0;
    const std::vector<std::string> materials = {"red", "glass", "missing", "water"};
    const std::vector<std::string> names = {"body", "Cube.001", "two words", "", " lead", "tail \t"};
    auto index = [&](int count) {
        const int i = 1 + int(random() % unsigned(count));
        return std::to_string(random() % 3 == 0 ? i - count - 1 : i);  // a third relative
    };
    for (int s = 0; s < statements; ++s) {
        const unsigned kind = random() % 100;
        std::string line = random() % 20 == 0 ? space(random) : "";
        if (kind < 30 || v < 3) {
            line += "v" + space(random) + number(random) + space(random) + number(random) + space(random) + number(random);
            if (random() % 10 == 0) line += " 1 0.5 0.25";  // a colour, ignored
            ++v;
        } else if (kind < 36) {
            line += "vt " + number(random);
            for (unsigned k = random() % 3; k > 0; --k) line += " " + number(random);
            ++vt;
        } else if (kind < 42) {
            line += "vn " + number(random) + " " + number(random) + " " + number(random);
            ++vn;
        } else if (kind < 80) {
            const unsigned corners = random() % 25 == 0 ? 1 + random() % 2 : 3 + (random() % 4 == 0 ? random() % 6 : 0);
            const unsigned form = random() % 4;  // v, v/vt, v//vn, v/vt/vn
            line += "f";
            for (unsigned c = 0; c < corners; ++c) {
                line += space(random) + index(v);
                if ((form == 1 || form == 3) && vt) line += "/" + index(vt);
                else if (form == 2 && vn) line += "/";
                if ((form == 2 || form == 3) && vn) line += (form == 3 && !vt ? "//" : "/") + index(vn);
            }
            if (random() % 10 == 0) line += " ";
        } else if (kind < 84) {
            line += "usemtl " + materials[random() % materials.size()];
        } else if (kind < 87) {
            line += "o " + names[random() % names.size()];
        } else if (kind < 90) {
            const unsigned g = random() % 4;
            line += g == 0 ? "g " : "g " + names[random() % names.size()] + (g == 1 ? " other" : "");
        } else if (kind < 92) {
            line += random() % 2 ? "mtllib a.mtl" : "mtllib b.mtl a.mtl";
        } else if (kind < 93) {
            line += (random() % 2 ? "l " : "p ") + index(v) + " " + index(v);
        } else if (kind < 95) {
            line += random() % 2 ? "s 1" : "s off";
        } else if (kind < 98) {
            line += "# " + number(random);
        }
        text += line + (random() % 30 == 0 ? "\r\n" : "\n");
    }
    return text;
}

// The triangles, objects and materials the OBJ loader made from tinyobjloader's LoadObj (the
// code it had before it parsed OBJ files itself, with the identity transform).
struct Reference {
    std::vector<Triangle> triangles;
    std::vector<std::string> triangleMaterials, objectNames;
};

// A material by its name and colour: two libraries may define the same name.
std::string describe(const Material& m) {
    if (m.name == "default") return m.name;
    return m.name + " " + std::to_string(m.diffuse.x) + " " + std::to_string(m.diffuse.y) + " " + std::to_string(m.diffuse.z);
}

class Libraries : public tinyobj::MaterialReader {
public:
    explicit Libraries(fs::path dir) : dir_(std::move(dir)) {}
    bool operator()(const std::string& mtllib, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* names, std::string*, std::string*) override {
        std::map<std::string, Material> library;  // vitrum's libraries list their names in order
        for (const MtlEntry& entry : parseMtlFile(dir_ / mtllib))
            library.emplace(entry.name, materialFromMtl(entry, dir_ / mtllib));
        for (const auto& [name, material] : library) {
            if (names->count(name)) continue;
            (*names)[name] = int(materials->size());
            materials->emplace_back().name = describe(material);
        }
        return true;
    }

private:
    fs::path dir_;
};

Reference tinyobjReference(const fs::path& obj) {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warnings, errors;
    std::ifstream stream(obj, std::ios::binary);
    Libraries libraries(obj.parent_path());
    EXPECT_TRUE(tinyobj::LoadObj(&attrib, &shapes, &materials, &warnings, &errors, &stream, &libraries, false));
    EXPECT_EQ(errors, "");
    Reference reference;
    const glm::mat4 m(1.0f);
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
    for (std::size_t s = 0; s < shapes.size(); ++s) {
        const tinyobj::mesh_t& mesh = shapes[s].mesh;
        std::string name = shapes[s].name;
        name.erase(name.find_last_not_of(" \t\r") + 1);
        if (name.empty()) name = "shape" + std::to_string(s);
        if (!mesh.num_face_vertices.empty()) reference.objectNames.push_back(obj.filename().string() + "/" + name);
        std::size_t offset = 0;
        for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
            const std::size_t corners = mesh.num_face_vertices[f];
            for (std::size_t k = 1; k + 1 < corners; ++k) {
                Triangle t;
                const std::size_t c[3] = {offset, offset + k, offset + k + 1};
                for (int i = 0; i < 3; ++i) {
                    const tinyobj::index_t& idx = mesh.indices[c[i]];
                    const tinyobj::real_t* p = &attrib.vertices[3 * std::size_t(idx.vertex_index)];
                    t.position[i] = glm::vec3(m * glm::vec4(float(p[0]), float(p[1]), float(p[2]), 1.0f));
                    const tinyobj::real_t* uv =
                        idx.texcoord_index >= 0 ? &attrib.texcoords[2 * std::size_t(idx.texcoord_index)] : nullptr;
                    t.uv[i] = uv ? glm::vec2(float(uv[0]), float(uv[1])) : glm::vec2(0.0f);
                }
                glm::vec3 geometric = glm::cross(t.position[1] - t.position[0], t.position[2] - t.position[0]);
                float length = glm::length(geometric);
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
                reference.triangles.push_back(t);
                const int material = mesh.material_ids[f];
                reference.triangleMaterials.push_back(material >= 0 ? materials[std::size_t(material)].name : "default");
            }
            offset += corners;
        }
    }
    return reference;
}

TEST_F(ObjParser, RandomFilesGiveTinyobjloadersTrianglesBitForBit) {
    const fs::path& dir = dir_;
    write(dir / "a.mtl", "newmtl red\nshader 2\nKd 1 0 0\nnewmtl glass\nshader 4\nNi 1.5\n");
    write(dir / "b.mtl", "newmtl water\nshader 4\nNi 1.33\nnewmtl red\nshader 2\nKd 0 1 0\n");
    std::mt19937 random(52);
    std::size_t triangles = 0;
    for (int file = 0; file < 40; ++file) {
        const fs::path obj = write(dir / "random.obj", randomObj(random, 300 + file * 40));
        const Reference reference = tinyobjReference(obj);
        for (std::size_t parts : {1, 2, 3, 8, 31}) {
            Scene scene;
            try {
                scene = loadInParts(obj, parts);
            } catch (const InputError& e) {
                if (reference.triangles.empty() && std::string(e.what()).find("no triangles") != std::string::npos) continue;
                FAIL() << "file " << file << ", " << parts << " parts: " << e.what();
            }
            ASSERT_EQ(scene.triangles.size(), reference.triangles.size()) << "file " << file << ", " << parts << " parts";
            // Shape by shape (an object's name may come twice), then triangle by triangle.
            ASSERT_EQ(scene.objectNames, reference.objectNames) << "file " << file << ", " << parts << " parts";
            std::size_t object = 0;
            for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
                const Triangle& t = scene.triangles[i];
                const Triangle& r = reference.triangles[i];
                const std::string where = "file " + std::to_string(file) + ", " + std::to_string(parts) +
                                          " parts, triangle " + std::to_string(i);
                for (int k = 0; k < 3; ++k) {
                    // Bit for bit: -0 and 0 told apart.
                    EXPECT_EQ(std::memcmp(&t.position[k], &r.position[k], sizeof(glm::vec3)), 0) << where;
                    EXPECT_EQ(std::memcmp(&t.normal[k], &r.normal[k], sizeof(glm::vec3)), 0) << where;
                    EXPECT_EQ(std::memcmp(&t.uv[k], &r.uv[k], sizeof(glm::vec2)), 0) << where;
                }
                EXPECT_EQ(describe(scene.materials[t.material]), reference.triangleMaterials[i]) << where;
                EXPECT_GE(t.object, object) << where;  // objects in order
                object = t.object;
            }
            triangles += scene.triangles.size();
        }
    }
    EXPECT_GT(triangles, 10000u);
}

}  // namespace
}  // namespace vitrum
