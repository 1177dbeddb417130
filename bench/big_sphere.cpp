// Writes the big model of issue 52: a closed, consistently wound UV sphere of about N triangles
// (4 rings (rings - 1) of them, segments = 2 rings, rings ~ sqrt(N / 4)), one glass material, as an OBJ
// with its MTL beside it. Every vertex is written once and shared, as exporters do; with --smooth
// each has its normal (a vn of its own, the point itself on the unit sphere), shared as the vertex is.
//
//   vitrum_bench_big_sphere TRIANGLES OUT.obj [--smooth]   (e.g. 3000000 s3m.obj: 2,996,360 triangles)
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>

int main(int argc, char** argv) {
    const bool smooth = argc == 4 && std::string(argv[3]) == "--smooth";
    if (argc != 3 && !smooth) {
        std::fprintf(stderr, "usage: vitrum_bench_big_sphere TRIANGLES OUT.obj [--smooth]\n");
        return 2;
    }
    const double wanted = std::strtod(argv[1], nullptr);
    if (!(wanted >= 8.0 && wanted <= 4e9)) {
        std::fprintf(stderr, "vitrum_bench_big_sphere: TRIANGLES must be from 8 to 4e9, not %s\n", argv[1]);
        return 2;
    }
    // 2 segments (rings - 1) triangles: the caps' fans and two a quad between rings.
    const auto rings = std::uint64_t(std::max(2.0, std::round(std::sqrt(wanted / 4.0))));
    const std::uint64_t segments = 2 * rings;
    const std::filesystem::path obj = argv[2];
    std::filesystem::path mtl = obj;
    mtl.replace_extension(".mtl");
    std::FILE* m = std::fopen(mtl.c_str(), "w");
    std::FILE* f = std::fopen(obj.c_str(), "w");
    if (!m || !f) {
        std::fprintf(stderr, "vitrum_bench_big_sphere: cannot write %s\n", (!m ? mtl : obj).c_str());
        return 1;
    }
    std::fprintf(m, "newmtl glass\nshader 4\nKs 1 1 1\nNi 1.5\nTf 0 0 0\n");
    std::fclose(m);
    std::fprintf(f, "mtllib %s\nusemtl glass\n", mtl.filename().c_str());
    auto vertex = [&](double x, double y, double z) {
        std::fprintf(f, "v %.7f %.7f %.7f\n", x, y, z);
        if (smooth) std::fprintf(f, "vn %.7f %.7f %.7f\n", x, y, z);
    };
    vertex(0, 0, 1);
    for (std::uint64_t i = 1; i < rings; ++i) {
        const double theta = std::numbers::pi * double(i) / double(rings);
        for (std::uint64_t j = 0; j < segments; ++j) {
            const double phi = 2.0 * std::numbers::pi * double(j) / double(segments);
            vertex(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        }
    }
    vertex(0, 0, -1);
    // Vertex numbers (1-based): the north pole 1, ring i (1 .. rings - 1) segment j, the south pole last.
    auto at = [&](std::uint64_t i, std::uint64_t j) { return 2 + (i - 1) * segments + j % segments; };
    const std::uint64_t south = 2 + (rings - 1) * segments;
    std::uint64_t triangles = 0;
    // A face's corner: the vertex, and with --smooth its normal of the same number.
    auto face = [&](std::uint64_t a, std::uint64_t b, std::uint64_t c) {
        if (smooth)
            std::fprintf(f, "f %llu//%llu %llu//%llu %llu//%llu\n", (unsigned long long)a, (unsigned long long)a,
                         (unsigned long long)b, (unsigned long long)b, (unsigned long long)c, (unsigned long long)c);
        else
            std::fprintf(f, "f %llu %llu %llu\n", (unsigned long long)a, (unsigned long long)b, (unsigned long long)c);
        ++triangles;
    };
    for (std::uint64_t j = 0; j < segments; ++j) face(1, at(1, j), at(1, j + 1));
    for (std::uint64_t i = 1; i + 1 < rings; ++i)
        for (std::uint64_t j = 0; j < segments; ++j) {
            face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    for (std::uint64_t j = 0; j < segments; ++j) face(south, at(rings - 1, j + 1), at(rings - 1, j));
    if (std::fclose(f) != 0) {
        std::fprintf(stderr, "vitrum_bench_big_sphere: cannot write %s\n", obj.c_str());
        return 1;
    }
    std::printf("%s: %llu triangles (%llu rings, %llu segments)\n", obj.c_str(), (unsigned long long)triangles,
                (unsigned long long)rings, (unsigned long long)segments);
    return 0;
}
