// The fuzz targets' entry functions: each writes the bytes to a file in a private temporary
// folder and loads it the way `vitrum render` would, and analyses a loaded scene as the renderers
// do (analysis/scene_features.h: camera media and surface, touching glass). Bad input may only end
// in an InputError (caught here, returning 0); any other exception escapes, and a crash is a
// crash: both are bugs.
// The libFuzzer wrappers (tests/fuzz/fuzz_*.cpp, built with -DVITRUM_FUZZ=ON) and the regression
// test (tests/core/fuzz_regression_test.cpp) call these. docs/testing.md describes both.
#pragma once

#include <cstddef>
#include <cstdint>

namespace vitrum {

// An OBJ file, then a zero byte, then an MTL file (no zero byte: no MTL). They are written as
// fuzz.obj and fuzz.mtl side by side and the OBJ is loaded as a bare OBJ scene, so an OBJ that
// says `mtllib fuzz.mtl` reads the MTL (and a `map_Kd` naming fuzz.mtl or fuzz.obj reads that
// file as a texture).
int fuzzObjMtl(const std::uint8_t* data, std::size_t size);

// A glTF file, written as fuzz.glb when it starts with the binary container's magic "glTF", else
// as fuzz.gltf, and loaded as a bare glTF scene (buffers and images in data URIs or in the GLB's
// binary chunk; a URI naming fuzz.gltf or fuzz.glb reads that file).
int fuzzGltf(const std::uint8_t* data, std::size_t size);

// A JSON scene file, written as scene.json next to files that it can name: tri.obj and tri.mtl (a
// triangle with a glass material), sky.pfm (4x3, for "spherical" and "cube_cross") and face.pfm
// (1x1, for "cube").
int fuzzSceneJson(const std::uint8_t* data, std::size_t size);

// An image file for readImage(): named .pfm when it starts with "PF" or "Pf", .hdr when it starts
// with "#?", .exr when it starts with OpenEXR's magic number, else .png (stb decides the format by
// content: PNG, JPEG, BMP, TGA, GIF, PSD, PNM).
int fuzzImage(const std::uint8_t* data, std::size_t size);

// `vitrum render`'s arguments: the bytes split at zero bytes, each piece an argument after
// "vitrum render"; parsed, and applied to a small scene (a triangle under a light) as the command
// applies them, with the checks of the camera, lights and image size. No file is read or written.
int fuzzRenderArguments(const std::uint8_t* data, std::size_t size);

struct FuzzTarget {
    const char* name;  // the folder name under tests/fuzz/corpus/ and tests/fuzz/regressions/
    int (*run)(const std::uint8_t* data, std::size_t size);
};
inline constexpr FuzzTarget kFuzzTargets[] = {
    {"obj_mtl", fuzzObjMtl},
    {"scene_json", fuzzSceneJson},
    {"gltf", fuzzGltf},
    {"image", fuzzImage},
    {"render_arguments", fuzzRenderArguments},
};

}  // namespace vitrum
