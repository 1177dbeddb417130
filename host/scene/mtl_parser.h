// Reading a Wavefront MTL file into raw records, line by line so that every error and warning
// can name its line. Only the keys the render model uses are kept (docs/scene-format.md); the
// mapping to a Material (shader numbers, sRGB decoding, defaults) is mtl_material.h's job.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

namespace vitrum {

struct MtlEntry {
    std::string name;                         // after `newmtl`
    int line = 0;                             // of the `newmtl` line
    std::optional<glm::vec3> ka, kd, ks, tf, tint;  // as written: sRGB for Ka Kd Ks tint, linear mu for Tf
    std::optional<float> ns, ni, vd;
    std::optional<int> illum, shader, priority, thinWalled;
    int shaderLine = 0;
    std::optional<std::string> mapKd;  // as written, relative to the MTL file
    int mapKdLine = 0;
    std::optional<std::string> mapD;  // map_d: the cut-out mask, as written
    int mapDLine = 0;
    // vitrum's partial coverage (render-model-decisions.md, "Partial coverage"): `coverage`, the
    // share of the surface that is there, and `map_coverage`, a map of it, as written.
    std::optional<float> coverage;
    int coverageLine = 0;
    std::optional<std::string> mapCoverage;
    int mapCoverageLine = 0;
};

// Throws InputError for a file that cannot be read or a malformed value ("file.mtl:7: Kd expects
// three numbers, got ..."). Unknown keys are skipped; the course typo "1.0." reads as 1.0 with a
// warning (once per file).
std::vector<MtlEntry> parseMtlFile(const std::filesystem::path& path);

}  // namespace vitrum
