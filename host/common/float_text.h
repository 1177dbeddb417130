// A float written in a scene file (OBJ, MTL): an optional '+', then all of what std::from_chars
// reads. A number below float's smallest is 0 with its sign, as tinyobjloader and strtof round it;
// one beyond float's largest, an infinity or a NaN is not finite.
#pragma once

#include <string_view>

namespace vitrum {

enum class FloatText { Number, NotANumber, NotFinite };

FloatText readFloat(std::string_view text, float& value);

}  // namespace vitrum
