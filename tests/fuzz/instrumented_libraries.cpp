// The fuzz build compiles stb_image's implementation from the installed header into each fuzz
// target, so that the fuzzer sees its coverage and AddressSanitizer checks its memory accesses.
// These definitions take precedence over the same functions in Debian's libstb, which the normal
// build uses (same header). Built only with -DVITRUM_FUZZ=ON. (tinyobjloader's was compiled here
// too until vitrum parsed OBJ files itself.)
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
