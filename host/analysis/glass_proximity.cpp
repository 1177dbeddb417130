#include "analysis/glass_proximity.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>
#include <vector>

#include "analysis/double_box.h"

namespace vitrum {
namespace {

struct NearTriangle {
    glm::dvec3 corner[3];
    DoubleBox bounds;
    std::uint32_t group = 0;
};

// [lo, hi] of the three corners' projections on `axis`.
void project(const glm::dvec3 p[3], const glm::dvec3& axis, double& lo, double& hi) {
    const double d0 = glm::dot(p[0], axis), d1 = glm::dot(p[1], axis), d2 = glm::dot(p[2], axis);
    lo = std::min({d0, d1, d2});
    hi = std::max({d0, d1, d2});
}

// The triangles of a group that lie within `distance` of the box of another group that
// `pairMatters` with it: no triangle of such a group can be that close to the others.
template <class GroupOf, class PairMatters>
std::vector<NearTriangle> trianglesNearOtherGroups(const Scene& scene, double distance, GroupOf groupOf,
                                                   PairMatters pairMatters) {
    // The groups' boxes first, and each group's neighbours: the other groups whose boxes come
    // within the distance of its own. Most scenes' groups have none, and then no triangle is
    // copied (a million-triangle model spent a second and 128 MB on copies for nothing).
    std::map<std::uint32_t, DoubleBox> groupBoxes;
    for (const Triangle& t : scene.triangles)
        if (const std::optional<std::uint32_t> group = groupOf(t))
            for (int i = 0; i < 3; ++i) groupBoxes[*group].grow(glm::dvec3(t.position[i]));
    std::vector<std::uint32_t> groups;
    std::vector<DoubleBox> boxes;
    for (const auto& [group, box] : groupBoxes) {
        groups.push_back(group);
        boxes.push_back(box);
    }
    std::map<std::uint32_t, std::vector<DoubleBox>> neighbours;
    forEachBoxPairWithin(boxes, distance, [&](std::size_t i, std::size_t j) {
        if (!pairMatters(groups[i], groups[j])) return;
        neighbours[groups[i]].push_back(boxes[j]);
        neighbours[groups[j]].push_back(boxes[i]);
    });
    std::vector<NearTriangle> near;
    if (neighbours.empty()) return near;
    for (const Triangle& t : scene.triangles) {
        const std::optional<std::uint32_t> group = groupOf(t);
        if (!group) continue;
        const auto found = neighbours.find(*group);
        if (found == neighbours.end()) continue;
        NearTriangle g;
        for (int i = 0; i < 3; ++i) {
            g.corner[i] = glm::dvec3(t.position[i]);
            g.bounds.grow(g.corner[i]);
        }
        g.group = *group;
        if (std::any_of(found->second.begin(), found->second.end(),
                        [&](const DoubleBox& box) { return g.bounds.within(box, distance); }))
            near.push_back(g);
    }
    return near;
}

// A cell of the grid over the triangles, packed 21 bits an axis.
using CellKey = std::uint64_t;
constexpr double kCellsPerAxis = double(1 << 21) - 2;

}  // namespace

bool trianglesApart(const glm::dvec3 a[3], const glm::dvec3 b[3], double distance) {
    const glm::dvec3 ea[3] = {a[1] - a[0], a[2] - a[1], a[0] - a[2]};
    const glm::dvec3 eb[3] = {b[1] - b[0], b[2] - b[1], b[0] - b[2]};
    // The direction between the two closest points is an axis along which the triangles are as
    // far apart as they are, and those points are two corners, a corner and a point of an edge,
    // a corner and a point inside the other's face, or points of two edges (where an edge lies
    // parallel to a face, or two edges parallel to each other, a corner is among the closest
    // points too). So the axes below are: the corner-to-corner directions, their parts across
    // each edge of the other triangle, the two normals and the cross products of two edges.
    glm::dvec3 axes[2 + 9 + 9 + 18];
    int count = 0;
    axes[count++] = glm::cross(ea[0], ea[1]);
    axes[count++] = glm::cross(eb[0], eb[1]);
    for (const glm::dvec3& u : ea)
        for (const glm::dvec3& v : eb) axes[count++] = glm::cross(u, v);
    auto across = [](const glm::dvec3& w, const glm::dvec3& edge) {
        const double length2 = glm::dot(edge, edge);
        return length2 > 0.0 ? w - edge * (glm::dot(w, edge) / length2) : w;
    };
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const glm::dvec3 w = b[j] - a[i];
            axes[count++] = w;
            axes[count++] = across(w, eb[j]);  // corner i of a to edge j of b
            axes[count++] = across(w, ea[i]);  // corner j of b to edge i of a
        }
    for (const glm::dvec3& axis : axes) {
        const double length = glm::length(axis);
        if (!(length > 0.0) || !std::isfinite(length)) continue;  // parallel edges, a degenerate triangle
        double aLo, aHi, bLo, bHi;
        project(a, axis, aLo, aHi);
        project(b, axis, bLo, bHi);
        // Along the unit axis, every point of one is at least this far from every point of the other.
        if (std::max(bLo - aHi, aLo - bHi) > distance * length) return true;
    }
    return false;
}

namespace {

// Two triangles of different groups (groupOf: a group, or none for a triangle left out) within
// `distance` of each other.
// Pairs of triangles of two groups for which `pairMatters(group, otherGroup)`, which must be
// symmetric.
template <class GroupOf, class PairMatters>
CloseTriangles findCloseTriangles(const Scene& scene, double distance, std::uint64_t maxPairs, GroupOf groupOf,
                                  PairMatters pairMatters) {
    CloseTriangles result;
    const std::vector<NearTriangle> near = trianglesNearOtherGroups(scene, distance, groupOf, pairMatters);
    if (near.empty()) return result;

    // A uniform grid with cells about twice as large as a typical triangle (twice the median of
    // their largest box sides, at least 4 distances): each triangle, its box grown by the distance, goes
    // into the cells it covers, and triangles of different groups in one cell are paired. A
    // triangle that would cover more than kMaxCells cells (a large face beside a fine mesh) is
    // paired with every other instead.
    DoubleBox region;
    std::vector<double> sizes;
    for (const NearTriangle& g : near) {
        region.grow(g.bounds.min - distance);
        region.grow(g.bounds.max + distance);
        const glm::dvec3 side = g.bounds.max - g.bounds.min;
        sizes.push_back(std::max({side.x, side.y, side.z}));
    }
    std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
    const glm::dvec3 extent = region.max - region.min;
    double cell =
        std::max({2.0 * sizes[sizes.size() / 2], 4.0 * distance, std::max({extent.x, extent.y, extent.z}) / kCellsPerAxis});
    // None of the three is positive only when every triangle is one and the same point and the
    // distance is 0: one cell of any size holds them (a 0 would divide 0 by 0 below).
    if (!(cell > 0.0)) cell = 1.0;
    constexpr std::uint64_t kMaxCells = 64;

    struct Entry {
        CellKey cell;
        std::uint32_t group, triangle;
        bool operator<(const Entry& o) const {
            return std::tie(cell, group, triangle) < std::tie(o.cell, o.group, o.triangle);
        }
    };
    auto key = [](const glm::uvec3& c) { return CellKey(c.x) << 42 | CellKey(c.y) << 21 | CellKey(c.z); };
    std::vector<Entry> entries;
    std::vector<CellKey> lowestCell(near.size());  // of the cells a triangle is in
    std::vector<std::uint32_t> large;
    for (std::uint32_t i = 0; i < near.size(); ++i) {
        const glm::uvec3 lo(glm::floor((near[i].bounds.min - distance - region.min) / cell));
        const glm::uvec3 hi(glm::floor((near[i].bounds.max + distance - region.min) / cell));
        const glm::u64vec3 span = glm::u64vec3(hi - lo) + std::uint64_t(1);
        lowestCell[i] = key(lo);
        if (span.x * span.y * span.z > kMaxCells) {
            large.push_back(i);
            continue;
        }
        for (std::uint32_t x = lo.x; x <= hi.x; ++x)
            for (std::uint32_t y = lo.y; y <= hi.y; ++y)
                for (std::uint32_t z = lo.z; z <= hi.z; ++z) entries.push_back({key({x, y, z}), near[i].group, i});
    }

    // Whether the pair may touch (or the work's bound is reached): boxes within `distance` and
    // no separating axis.
    auto mayTouch = [&](const NearTriangle& a, const NearTriangle& b) {
        if (++result.examinedPairs > maxPairs) return result.gaveUp = true;
        return a.bounds.within(b.bounds, distance) && !trianglesApart(a.corner, b.corner, distance);
    };
    // Two triangles that share cells are paired in one of them: the one at the lowest corner of
    // where their grown boxes overlap (on each axis the larger of their lowest cells).
    auto pairedHere = [&](CellKey here, std::uint32_t i, std::uint32_t j) {
        const CellKey mask = (CellKey(1) << 21) - 1;
        CellKey corner = 0;
        for (int shift : {42, 21, 0})
            corner |= std::max(lowestCell[i] >> shift & mask, lowestCell[j] >> shift & mask) << shift;
        return corner == here;
    };
    auto search = [&] {
        for (std::uint32_t i : large)
            for (std::uint32_t j = 0; j < near.size(); ++j)
                if (near[i].group != near[j].group && pairMatters(near[i].group, near[j].group) &&
                    mayTouch(near[i], near[j]))
                    return true;
        std::sort(entries.begin(), entries.end());
        for (std::size_t first = 0; first < entries.size();) {
            std::size_t end = first;
            while (end < entries.size() && entries[end].cell == entries[first].cell) ++end;
            // The cell's entries come by group: each group's with those of the groups after it.
            for (std::size_t run = first; run < end;) {
                std::size_t runEnd = run;
                while (runEnd < end && entries[runEnd].group == entries[run].group) ++runEnd;
                for (std::size_t i = run; i < runEnd; ++i)
                    for (std::size_t j = runEnd; j < end; ++j)
                        if (pairMatters(entries[i].group, entries[j].group) &&
                            pairedHere(entries[i].cell, entries[i].triangle, entries[j].triangle) &&
                            mayTouch(near[entries[i].triangle], near[entries[j].triangle]))
                            return true;
                run = runEnd;
            }
            first = end;
        }
        return false;
    };
    result.found = search();
    return result;
}

bool anyPair(std::uint32_t, std::uint32_t) { return true; }

}  // namespace

CloseTriangles findCloseGlassTriangles(const Scene& scene, double distance, std::uint64_t maxPairs) {
    return findCloseTriangles(
        scene, distance, maxPairs,
        [&](const Triangle& t) -> std::optional<std::uint32_t> {
            if (scene.materials[t.material].model != MaterialModel::Glass) return std::nullopt;
            return t.object;
        },
        anyPair);
}

CloseTriangles findGlassNearOpaque(const Scene& scene, double distance, std::uint64_t maxPairs) {
    return findCloseTriangles(
        scene, distance, maxPairs,
        [&](const Triangle& t) -> std::optional<std::uint32_t> {
            return scene.materials[t.material].model == MaterialModel::Glass ? 0u : 1u;
        },
        anyPair);
}

CloseTriangles findCloseOpaqueTriangles(const Scene& scene, double distance,
                                        const std::set<std::uint32_t>& metFromBehind, std::uint64_t maxPairs) {
    return findCloseTriangles(
        scene, distance, maxPairs,
        [&](const Triangle& t) -> std::optional<std::uint32_t> {
            if (scene.materials[t.material].model == MaterialModel::Glass) return std::nullopt;
            return t.object;
        },
        [&](std::uint32_t a, std::uint32_t b) { return metFromBehind.count(a) > 0 || metFromBehind.count(b) > 0; });
}

}  // namespace vitrum
