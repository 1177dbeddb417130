// Binned SAH BVH construction (Wald, "On fast Construction of SAH-based Bounding Volume
// Hierarchies", 2007), emitted directly in the depth-first flat layout of gpu_types.h
// (pbrt-v4's LinearBVHNode): a node's first child is written right after it, so recursing into
// the first child before the second produces the final array with no separate flattening pass.
//
// Triangles are referred to by an index array that is partitioned in place; a leaf is a
// contiguous range of it, and the array becomes Bvh::triangleOrder.
#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <chrono>
#include <cmath>
#include <limits>

#include "bvh/bvh.h"

namespace vitrum {
namespace {

constexpr int kBinCount = 16;
constexpr float kTraversalCost = 1.0f;     // C_trav
constexpr float kIntersectionCost = 1.0f;  // C_isect
// Leaves deeper than this are never made. A depth-first traversal holds at most one pending
// sibling per level plus the two children just pushed, so a tree of depth D needs D + 1 stack
// entries; this keeps a margin below gpu::kTraversalStackSize.
constexpr std::uint32_t kMaxTreeDepth = gpu::kTraversalStackSize - 4;
static_assert(kMaxTreeDepth + 2 <= gpu::kTraversalStackSize);

struct Box {
    glm::vec3 min{std::numeric_limits<float>::infinity()};
    glm::vec3 max{-std::numeric_limits<float>::infinity()};

    void grow(const glm::vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void grow(const Box& b) {
        min = glm::min(min, b.min);
        max = glm::max(max, b.max);
    }
    bool empty() const { return !(min.x <= max.x); }
    // Surface area; 0 for an empty box.
    float area() const {
        if (empty()) return 0.0f;
        glm::vec3 e = max - min;
        return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
};

// Depth of the tree that halving by count produces: the depth a median split guarantees.
std::uint32_t medianSplitDepth(std::uint32_t count) {
    std::uint32_t depth = 0;
    while (count > gpu::kMaxLeafTriangles) {
        count = (count + 1) / 2;
        ++depth;
    }
    return depth;
}

class Builder {
public:
    Builder(std::span<const Triangle> triangles, Bvh& bvh, const std::function<void(double)>& progress)
        : bvh_(bvh), progress_(progress) {
        const std::size_t n = triangles.size();
        bounds_.resize(n);
        centroids_.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            Box b;
            for (const glm::vec3& p : triangles[i].position) b.grow(p);
            bounds_[i] = b;
            centroids_[i] = 0.5f * (b.min + b.max);  // box centre: cheaper and as good as the mean
        }
        bvh_.triangleOrder.resize(n);
        for (std::size_t i = 0; i < n; ++i) bvh_.triangleOrder[i] = static_cast<std::uint32_t>(i);
        bvh_.nodes.reserve(n == 0 ? 1 : 2 * n);
    }

    void build() {
        const auto count = static_cast<std::uint32_t>(bvh_.triangleOrder.size());
        if (count == 0) {
            // The empty scene: one leaf with no triangles and a degenerate box at the origin, so
            // that every traversal (CPU and GPU) works without a special case.
            gpu::BvhNode leaf{};
            leaf.boundsMin = glm::vec4(0.0f, 0.0f, 0.0f, std::bit_cast<float>(0u));
            leaf.boundsMax = glm::vec4(0.0f, 0.0f, 0.0f, std::bit_cast<float>(0u));
            bvh_.nodes.push_back(leaf);
            bvh_.stats.nodeCount = 1;
            bvh_.stats.leafCount = 1;
            return;
        }
        rootArea_ = 0.0;
        buildNode(0, count, 0);
        bvh_.stats.nodeCount = static_cast<std::uint32_t>(bvh_.nodes.size());
        bvh_.stats.sahCost = sahSum_;
    }

private:
    struct Bin {
        Box bounds;
        std::uint32_t count = 0;
    };

    // Builds the subtree over triangleOrder[begin, end) at the given depth; returns its index.
    std::uint32_t buildNode(std::uint32_t begin, std::uint32_t end, std::uint32_t depth) {
        auto& order = bvh_.triangleOrder;
        const std::uint32_t count = end - begin;
        Box box, centroidBox;
        for (std::uint32_t i = begin; i < end; ++i) {
            box.grow(bounds_[order[i]]);
            centroidBox.grow(centroids_[order[i]]);
        }
        const double area = box.area();
        if (depth == 0) rootArea_ = area > 0.0 ? area : 1.0;  // a zero-area scene: plain counts
        bvh_.stats.maxDepth = std::max(bvh_.stats.maxDepth, depth);

        const auto index = static_cast<std::uint32_t>(bvh_.nodes.size());
        bvh_.nodes.emplace_back();

        std::uint32_t mid = begin;
        std::uint32_t axis = 0;
        if (!chooseSplit(begin, end, depth, box, centroidBox, mid, axis)) {
            makeLeaf(index, box, begin, count, area);
            return index;
        }
        assert(mid > begin && mid < end);
        sahSum_ += area / rootArea_ * kTraversalCost;
        buildNode(begin, mid, depth + 1);  // first child: the next node
        const std::uint32_t second = buildNode(mid, end, depth + 1);
        gpu::BvhNode& node = bvh_.nodes[index];
        node.boundsMin = glm::vec4(box.min, std::bit_cast<float>(second));
        node.boundsMax = glm::vec4(box.max, std::bit_cast<float>(gpu::kInteriorNodeFlag | axis));
        return index;
    }

    void makeLeaf(std::uint32_t index, const Box& box, std::uint32_t first, std::uint32_t count, double area) {
        assert(count >= 1 && count <= gpu::kMaxLeafTriangles);
        gpu::BvhNode& node = bvh_.nodes[index];
        node.boundsMin = glm::vec4(box.min, std::bit_cast<float>(first));
        node.boundsMax = glm::vec4(box.max, std::bit_cast<float>(count));
        bvh_.stats.leafCount += 1;
        placed_ += count;
        if (progress_ && placed_ >= nextReport_) {
            progress_(double(placed_) / double(bvh_.triangleOrder.size()));
            nextReport_ = placed_ + bvh_.triangleOrder.size() / 256 + 1;
        }
        bvh_.stats.maxLeafTriangles = std::max(bvh_.stats.maxLeafTriangles, count);
        sahSum_ += area / rootArea_ * kIntersectionCost * count;
    }

    // Decides between a leaf (returns false) and a split of [begin, end) at `mid` along `axis`
    // (returns true, the range already partitioned).
    bool chooseSplit(std::uint32_t begin, std::uint32_t end, std::uint32_t depth, const Box& box,
                     const Box& centroidBox, std::uint32_t& mid, std::uint32_t& axis) {
        auto& order = bvh_.triangleOrder;
        const std::uint32_t count = end - begin;
        if (count <= 2) return false;

        const glm::vec3 extent = centroidBox.max - centroidBox.min;
        axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);

        // Invariant: depth + medianSplitDepth(count) <= kMaxTreeDepth, so halving always fits.
        // An SAH split may leave up to count - 1 triangles on one side; when that could break
        // the invariant, split at the median instead.
        if (depth + 1 + medianSplitDepth(count - 1) > kMaxTreeDepth) {
            if (count <= gpu::kMaxLeafTriangles) return false;
            mid = begin + count / 2;
            if (extent[axis] > 0.0f) {
                std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                                 [&](std::uint32_t a, std::uint32_t b) {
                                     return centroids_[a][axis] < centroids_[b][axis];
                                 });
            }
            return true;
        }

        // Binned SAH over all three axes: cost of a split relative to the node's area is
        // C_trav + (A_L N_L + A_R N_R) / A; kept multiplied by A to stay finite for flat nodes.
        float bestCost = std::numeric_limits<float>::infinity();
        int bestAxis = -1;
        int bestBin = 0;  // first bin of the second child
        for (int a = 0; a < 3; ++a) {
            const float lo = centroidBox.min[a];
            const float ext = extent[a];
            if (!(ext > 0.0f)) continue;
            const float scale = kBinCount * (1.0f - 1e-6f) / ext;
            if (!std::isfinite(scale)) continue;
            std::array<Bin, kBinCount> bins{};
            for (std::uint32_t i = begin; i < end; ++i) {
                const std::uint32_t t = order[i];
                const int b = binOf(centroids_[t][a], lo, scale);
                bins[b].count += 1;
                bins[b].bounds.grow(bounds_[t]);
            }
            // Sweep from the right to get the area and count of every right side.
            std::array<float, kBinCount> rightArea{};
            std::array<std::uint32_t, kBinCount> rightCount{};
            Box right;
            std::uint32_t rc = 0;
            for (int b = kBinCount - 1; b > 0; --b) {
                right.grow(bins[b].bounds);
                rc += bins[b].count;
                rightArea[b] = right.area();
                rightCount[b] = rc;
            }
            Box left;
            std::uint32_t lc = 0;
            for (int b = 1; b < kBinCount; ++b) {
                left.grow(bins[b - 1].bounds);
                lc += bins[b - 1].count;
                if (lc == 0 || rightCount[b] == 0) continue;
                const float cost = left.area() * lc + rightArea[b] * rightCount[b];
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = a;
                    bestBin = b;
                }
            }
        }

        if (bestAxis < 0) {
            // All centroids equal (duplicates, or triangles sharing one centre): no spatial
            // split exists. Split by index until leaves are small enough.
            if (count <= gpu::kMaxLeafTriangles) return false;
            mid = begin + count / 2;
            return true;
        }

        const float area = box.area();
        const float splitCost = kTraversalCost * area + kIntersectionCost * bestCost;
        const float leafCost = kIntersectionCost * area * count;
        if (count <= gpu::kMaxLeafTriangles && leafCost <= splitCost) return false;

        axis = static_cast<std::uint32_t>(bestAxis);
        const float lo = centroidBox.min[bestAxis];
        const float scale = kBinCount * (1.0f - 1e-6f) / extent[bestAxis];
        auto* split = std::partition(order.data() + begin, order.data() + end, [&](std::uint32_t t) {
            return binOf(centroids_[t][bestAxis], lo, scale) < bestBin;
        });
        mid = static_cast<std::uint32_t>(split - order.data());
        assert(mid > begin && mid < end);  // the same binning that counted both sides non-empty
        return true;
    }

    // Written so that NaN (from a non-finite vertex) lands in bin 0 instead of being cast.
    static int binOf(float c, float lo, float scale) {
        const float f = (c - lo) * scale;
        if (!(f > 0.0f)) return 0;
        if (f >= float(kBinCount - 1)) return kBinCount - 1;
        return static_cast<int>(f);
    }

    Bvh& bvh_;
    std::vector<Box> bounds_;
    std::vector<glm::vec3> centroids_;
    double rootArea_ = 1.0;
    double sahSum_ = 0.0;
    const std::function<void(double)>& progress_;
    std::size_t placed_ = 0;      // triangles in the leaves made so far
    std::size_t nextReport_ = 0;  // progress_ hears of it when placed_ reaches this
};

}  // namespace

Bvh buildBvh(std::span<const Triangle> triangles, const std::function<void(double)>& progress) {
    const auto start = std::chrono::steady_clock::now();
    Bvh bvh;
    Builder builder(triangles, bvh, progress);
    builder.build();
    if (progress) progress(1.0);
    bvh.stats.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return bvh;
}

void packTriangleVertices(const Bvh& bvh, std::span<const Triangle> triangles, std::span<gpu::TriangleVertices> into) {
    for (std::size_t i = 0; i < into.size(); ++i) {
        const Triangle& tri = triangles[bvh.triangleOrder[i]];
        into[i].v0 = glm::vec4(tri.position[0], std::bit_cast<float>(tri.material));
        into[i].v1 = glm::vec4(tri.position[1], std::bit_cast<float>(tri.object));
        into[i].v2 = glm::vec4(tri.position[2], 0.0f);
    }
}

std::vector<gpu::TriangleVertices> packTriangleVertices(const Bvh& bvh, std::span<const Triangle> triangles) {
    std::vector<gpu::TriangleVertices> packed(bvh.triangleOrder.size());
    packTriangleVertices(bvh, triangles, packed);
    return packed;
}

}  // namespace vitrum
