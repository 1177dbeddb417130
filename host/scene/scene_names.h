// The names reports and messages give the scene's enumerations (as the scene format spells them
// where it has a spelling).
#pragma once

#include "scene/scene.h"

namespace vitrum {

inline const char* materialModelName(MaterialModel model) {
    switch (model) {
        case MaterialModel::Normal: return "normal";
        case MaterialModel::Lambert: return "lambert";
        case MaterialModel::Phong: return "opaque dielectric";
        case MaterialModel::Glass: return "glass";
        case MaterialModel::Mirror: return "mirror";
        case MaterialModel::ThinGlass: return "thin glass";
    }
    return "?";
}

inline const char* fresnelModelName(FresnelModel model) {
    switch (model) {
        case FresnelModel::Schlick: return "schlick";
        case FresnelModel::Exact: return "exact";
        case FresnelModel::SchlickExp2: return "schlick-exp2";
    }
    return "?";
}

inline const char* backgroundKindName(BackgroundKind kind) {
    switch (kind) {
        case BackgroundKind::Constant: return "constant";
        case BackgroundKind::Spherical: return "spherical map";
        case BackgroundKind::Cube: return "cube map";
    }
    return "?";
}

inline const char* textureFilterName(TextureFilter filter) {
    switch (filter) {
        case TextureFilter::Bilinear: return "bilinear";
        case TextureFilter::Nearest: return "nearest";
    }
    return "?";
}

constexpr MaterialModel kMaterialModels[] = {MaterialModel::Normal, MaterialModel::Lambert, MaterialModel::Phong,
                                             MaterialModel::Glass,  MaterialModel::Mirror,  MaterialModel::ThinGlass};

}  // namespace vitrum
