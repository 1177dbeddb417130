// Whether surfaces of two glass objects come close enough to touch (docs/render-model-decisions.md,
// "Touching objects"), glass comes close enough to an opaque surface to rest on it ("Glass on
// an opaque surface"), or opaque surfaces of two objects may coincide ("Coincident opaque
// surfaces"): only then does a render need to look for them. Boxes around whole objects
// cannot tell a bubble inside a block (nested, never touching) from two blocks face to face; the
// triangles can.
#pragma once

#include <cstdint>
#include <set>

#include "scene/scene.h"

namespace vitrum {

// What findCloseGlassTriangles found: a pair of triangles within the distance asked.
struct CloseTriangles {
    bool found = false;
    // The pairs of triangles looked at (sharing a cell of the search's grid), and whether the
    // search stopped at kMaxExaminedPairs, which also counts as found.
    std::uint64_t examinedPairs = 0;
    bool gaveUp = false;
};

// Beyond this many pairs looked at, the answer is "may touch": a bound on the work for meshes
// whose triangles crowd one another's boxes, never a wrong "apart".
constexpr std::uint64_t kMaxExaminedPairs = 20'000'000;

// Looks for two triangles of different glass objects of `scene` that lie within `distance` of
// each other. Sound: when nothing is found, every two such triangles are farther apart than
// `distance`. Complete up to rounding and to kMaxExaminedPairs: a pair farther apart is found
// only when the search gives up.
CloseTriangles findCloseGlassTriangles(const Scene& scene, double distance,
                                       std::uint64_t maxPairs = kMaxExaminedPairs);

// Looks for a glass triangle and an opaque one (of any objects, one and the same included) that
// lie within `distance` of each other; sound and complete as findCloseGlassTriangles.
CloseTriangles findGlassNearOpaque(const Scene& scene, double distance, std::uint64_t maxPairs = kMaxExaminedPairs);

// Looks for two opaque triangles of different objects, at least one of them in `metFromBehind`,
// that lie within `distance` of each other (surfaces that may coincide where a ray can come from
// behind one of them: a box standing on another, seen from inside; render-model-decisions.md,
// "Coincident opaque surfaces"); sound and complete as findCloseGlassTriangles.
CloseTriangles findCloseOpaqueTriangles(const Scene& scene, double distance,
                                        const std::set<std::uint32_t>& metFromBehind,
                                        std::uint64_t maxPairs = kMaxExaminedPairs);

// Whether triangles a and b are farther apart than `distance`, by the separating-axis test:
// some axis along which their projections leave a gap wider than `distance`, among axes that
// include the direction between their closest points (so the test is exact up to rounding).
bool trianglesApart(const glm::dvec3 a[3], const glm::dvec3 b[3], double distance);

}  // namespace vitrum
