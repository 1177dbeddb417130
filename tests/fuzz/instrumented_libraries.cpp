// The fuzz build compiles stb_image's and tinyobjloader's implementations from the installed
// headers into each fuzz target, so that the fuzzer sees their coverage and AddressSanitizer
// checks their memory accesses. These definitions take precedence over the same functions in
// Debian's libstb and libtinyobjloader, which the normal build uses (same headers, same
// TINYOBJLOADER_USE_DOUBLE). Built only with -DVITRUM_FUZZ=ON.
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
