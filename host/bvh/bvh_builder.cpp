// Binned SAH BVH construction (Wald, "On fast Construction of SAH-based Bounding Volume
// Hierarchies", 2007), emitted directly in the depth-first flat layout of gpu_types.h
// (pbrt-v4's LinearBVHNode): a node's first child is written right after it, so recursing into
// the first child before the second produces the final array with no separate flattening pass.
//
// Triangles are held as an array of their boxes, centroids and indices, partitioned in place (each
// node's pass reads its range in order, not through an index array); a leaf is a contiguous range
// of it, and its indices become Bvh::triangleOrder. Large subtrees are built on the machine's other
// cores, into arrays joined in the same depth-first order.
#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cassert>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include "bvh/bvh.h"
#include "common/parallel.h"
#include "scene/instances.h"

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
// With instances, the stack holds the top level's pending siblings, the entry that leaves an
// instance and a mesh's (gpu_types.h, "Instances"): the two trees share the depth.
constexpr std::uint32_t kMaxTopLevelDepth = 22;
constexpr std::uint32_t kMaxMeshTreeDepth = kMaxTreeDepth - kMaxTopLevelDepth - 1;
static_assert(kMaxTopLevelDepth + 1 + kMaxMeshTreeDepth + 2 <= gpu::kTraversalStackSize);

// What a tree may be: how deep, and how many primitives a leaf.
struct TreeLimits {
    std::uint32_t depth = kMaxTreeDepth;
    std::uint32_t leafSize = gpu::kMaxLeafTriangles;
};

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
std::uint32_t medianSplitDepth(std::uint32_t count, std::uint32_t leafSize) {
    std::uint32_t depth = 0;
    while (count > leafSize) {
        count = (count + 1) / 2;
        ++depth;
    }
    return depth;
}

// A triangle as the build sees it.
struct Primitive {
    Box bounds;
    glm::vec3 centroid;
    std::uint32_t index;  // in the scene's triangles
};

// What every part of a build reads: the primitives, which the parts partition (each part its own
// range of them), and the root's area.
struct BuildInput {
    std::vector<Primitive> primitives;
    TreeLimits limits;
    double rootArea = 1.0;
    const std::function<void(double)>& progress;  // called by the part on the calling thread only
    std::atomic<std::size_t> placed{0};           // triangles in the leaves made so far, all parts
};

// Builds one subtree into its own depth-first node array (indices local to it). Above a size, a
// subtree's second child is built by another thread into a part of its own and appended after
// the first child's nodes, its indices moved on: the array is the one a single thread makes.
class Builder {
public:
    Builder(BuildInput& input, unsigned spareThreads, bool reportsProgress)
        : in_(input), spareThreads_(spareThreads), reportsProgress_(reportsProgress) {}

    std::vector<gpu::BvhNode> nodes;
    std::uint32_t leafCount = 0, maxDepth = 0, maxLeafTriangles = 0;
    double sahSum = 0.0;

    // Builds the subtree over primitives[begin, end) at the given depth; returns its index.
    std::uint32_t buildNode(std::uint32_t begin, std::uint32_t end, std::uint32_t depth) {
        const std::vector<Primitive>& primitives = in_.primitives;
        const std::uint32_t count = end - begin;
        Box box, centroidBox;
        for (std::uint32_t i = begin; i < end; ++i) {
            box.grow(primitives[i].bounds);
            centroidBox.grow(primitives[i].centroid);
        }
        const double area = box.area();
        maxDepth = std::max(maxDepth, depth);

        const auto index = static_cast<std::uint32_t>(nodes.size());
        nodes.emplace_back();

        std::uint32_t mid = begin;
        std::uint32_t axis = 0;
        if (!chooseSplit(begin, end, depth, box, centroidBox, mid, axis)) {
            makeLeaf(index, box, begin, count, area);
            return index;
        }
        assert(mid > begin && mid < end);
        sahSum += area / in_.rootArea * kTraversalCost;
        std::uint32_t second = 0;
        if (spareThreads_ > 0 && end - mid >= kParallelSubtree) {
            // Half the spare threads go with the second child, half stay with this part.
            const unsigned given = (spareThreads_ + 1) / 2;
            spareThreads_ -= given;
            Builder part(in_, given - 1, false);
            part.nodes.reserve(2 * std::size_t(end - mid));
            std::exception_ptr failed;  // out of memory, say: rethrown here
            std::thread worker([&] {
                try {
                    part.buildNode(mid, end, depth + 1);
                } catch (...) {
                    failed = std::current_exception();
                }
            });
            try {
                buildNode(begin, mid, depth + 1);
            } catch (...) {
                worker.join();
                throw;
            }
            worker.join();
            if (failed) std::rethrow_exception(failed);
            spareThreads_ += given;
            second = append(std::move(part));
        } else {
            buildNode(begin, mid, depth + 1);  // first child: the next node
            second = buildNode(mid, end, depth + 1);
        }
        gpu::BvhNode& node = nodes[index];
        node.boundsMin = glm::vec4(box.min, std::bit_cast<float>(second));
        node.boundsMax = glm::vec4(box.max, std::bit_cast<float>(gpu::kInteriorNodeFlag | axis));
        return index;
    }

private:
    // Subtrees smaller than this are not worth a thread.
    static constexpr std::uint32_t kParallelSubtree = 1u << 16;

    struct Bin {
        Box bounds;
        std::uint32_t count = 0;
    };

    // Appends a part's nodes after this one's; returns where its root went.
    std::uint32_t append(Builder&& part) {
        const auto offset = static_cast<std::uint32_t>(nodes.size());
        for (gpu::BvhNode& node : part.nodes) {
            if (std::bit_cast<std::uint32_t>(node.boundsMax.w) & gpu::kInteriorNodeFlag)
                node.boundsMin.w = std::bit_cast<float>(std::bit_cast<std::uint32_t>(node.boundsMin.w) + offset);
        }
        nodes.insert(nodes.end(), part.nodes.begin(), part.nodes.end());
        leafCount += part.leafCount;
        maxDepth = std::max(maxDepth, part.maxDepth);
        maxLeafTriangles = std::max(maxLeafTriangles, part.maxLeafTriangles);
        sahSum += part.sahSum;
        return offset;
    }

    void makeLeaf(std::uint32_t index, const Box& box, std::uint32_t first, std::uint32_t count, double area) {
        assert(count >= 1 && count <= in_.limits.leafSize);
        gpu::BvhNode& node = nodes[index];
        node.boundsMin = glm::vec4(box.min, std::bit_cast<float>(first));
        node.boundsMax = glm::vec4(box.max, std::bit_cast<float>(count));
        leafCount += 1;
        const std::size_t placed = in_.placed.fetch_add(count, std::memory_order_relaxed) + count;
        if (reportsProgress_ && in_.progress && placed >= nextReport_) {
            in_.progress(double(placed) / double(in_.primitives.size()));
            nextReport_ = placed + in_.primitives.size() / 256 + 1;
        }
        maxLeafTriangles = std::max(maxLeafTriangles, count);
        sahSum += area / in_.rootArea * kIntersectionCost * count;
    }

// Decides between a leaf (returns false) and a split of [begin, end) at `mid` along `axis`
    // (returns true, the range already partitioned).
    bool chooseSplit(std::uint32_t begin, std::uint32_t end, std::uint32_t depth, const Box& box,
                     const Box& centroidBox, std::uint32_t& mid, std::uint32_t& axis) {
        std::vector<Primitive>& primitives = in_.primitives;
        const std::uint32_t count = end - begin;
        if (count <= 2 && count <= in_.limits.leafSize) return false;

        const glm::vec3 extent = centroidBox.max - centroidBox.min;
        axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);

        // Invariant: depth + medianSplitDepth(count) <= the depth limit, so halving always fits.
        // An SAH split may leave up to count - 1 triangles on one side; when that could break
        // the invariant, split at the median instead.
        const TreeLimits& limits = in_.limits;
        if (depth + 1 + medianSplitDepth(count - 1, limits.leafSize) > limits.depth) {
            if (count <= limits.leafSize) return false;
            mid = begin + count / 2;
            if (extent[axis] > 0.0f) {
                std::nth_element(primitives.begin() + begin, primitives.begin() + mid, primitives.begin() + end,
                                 [&](const Primitive& a, const Primitive& b) {
                                     return a.centroid[axis] < b.centroid[axis];
                                 });
            }
            return true;
        }

        // Binned SAH over all three axes: cost of a split relative to the node's area is
        // C_trav + (A_L N_L + A_R N_R) / A; kept multiplied by A to stay finite for flat nodes.
        // The three axes' bins are filled in one pass over the triangles (each triangle's box and
        // centroid fetched once), then swept axis by axis.
        std::array<float, 3> lo{}, scale{};
        std::array<bool, 3> binned{};
        for (int a = 0; a < 3; ++a) {
            lo[a] = centroidBox.min[a];
            scale[a] = kBinCount * (1.0f - 1e-6f) / extent[a];
            binned[a] = extent[a] > 0.0f && std::isfinite(scale[a]);
        }
        std::array<std::array<Bin, kBinCount>, 3> bins{};
        for (std::uint32_t i = begin; i < end; ++i) {
            const glm::vec3 centroid = primitives[i].centroid;
            const Box& bounds = primitives[i].bounds;
            for (int a = 0; a < 3; ++a) {
                if (!binned[a]) continue;
                Bin& bin = bins[a][binOf(centroid[a], lo[a], scale[a])];
                bin.count += 1;
                bin.bounds.grow(bounds);
            }
        }
        float bestCost = std::numeric_limits<float>::infinity();
        int bestAxis = -1;
        int bestBin = 0;  // first bin of the second child
        for (int a = 0; a < 3; ++a) {
            if (!binned[a]) continue;
            // Sweep from the right to get the area and count of every right side.
            std::array<float, kBinCount> rightArea{};
            std::array<std::uint32_t, kBinCount> rightCount{};
            Box right;
            std::uint32_t rc = 0;
            for (int b = kBinCount - 1; b > 0; --b) {
                right.grow(bins[a][b].bounds);
                rc += bins[a][b].count;
                rightArea[b] = right.area();
                rightCount[b] = rc;
            }
            Box left;
            std::uint32_t lc = 0;
            for (int b = 1; b < kBinCount; ++b) {
                left.grow(bins[a][b - 1].bounds);
                lc += bins[a][b - 1].count;
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
            if (count <= limits.leafSize) return false;
            mid = begin + count / 2;
            return true;
        }

        const float area = box.area();
        const float splitCost = kTraversalCost * area + kIntersectionCost * bestCost;
        const float leafCost = kIntersectionCost * area * count;
        if (count <= limits.leafSize && leafCost <= splitCost) return false;

        axis = static_cast<std::uint32_t>(bestAxis);
        auto* split = std::partition(primitives.data() + begin, primitives.data() + end, [&](const Primitive& p) {
            return binOf(p.centroid[bestAxis], lo[bestAxis], scale[bestAxis]) < bestBin;
        });
        mid = static_cast<std::uint32_t>(split - primitives.data());
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

    BuildInput& in_;
    unsigned spareThreads_;     // threads this part may still start
    bool reportsProgress_;      // the part on the calling thread
    std::size_t nextReport_ = 0;  // progress hears of it when the triangles placed reach this
};


// The tree over `primitives` (their indices 0, 1, ...) within `limits`.
Bvh buildTree(std::vector<Primitive> primitives, const TreeLimits& limits, const std::function<void(double)>& progress,
              unsigned threads) {
    const auto start = std::chrono::steady_clock::now();
    Bvh bvh;
    const std::size_t n = primitives.size();
    bvh.triangleOrder.resize(n);
    if (n == 0) {
        // The empty scene: one leaf with no triangles and a degenerate box at the origin, so
        // that every traversal (CPU and GPU) works without a special case.
        gpu::BvhNode leaf{};
        leaf.boundsMin = glm::vec4(0.0f, 0.0f, 0.0f, std::bit_cast<float>(0u));
        leaf.boundsMax = glm::vec4(0.0f, 0.0f, 0.0f, std::bit_cast<float>(0u));
        bvh.nodes.push_back(leaf);
        bvh.stats.nodeCount = 1;
        bvh.stats.leafCount = 1;
    } else {
        BuildInput input{.progress = progress};
        input.primitives = std::move(primitives);
        input.limits = limits;
        Box root;
        for (const Primitive& p : input.primitives) root.grow(p.bounds);
        const double rootArea = root.area();
        input.rootArea = rootArea > 0.0 ? rootArea : 1.0;  // a zero-area scene: plain counts
        if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
        Builder builder(input, threads - 1, true);
        builder.nodes.reserve(2 * n);
        builder.buildNode(0, static_cast<std::uint32_t>(n), 0);
        for (std::size_t i = 0; i < n; ++i) bvh.triangleOrder[i] = input.primitives[i].index;
        bvh.nodes = std::move(builder.nodes);
        bvh.stats.nodeCount = static_cast<std::uint32_t>(bvh.nodes.size());
        bvh.stats.leafCount = builder.leafCount;
        bvh.stats.maxDepth = builder.maxDepth;
        bvh.stats.maxLeafTriangles = builder.maxLeafTriangles;
        bvh.stats.sahCost = builder.sahSum;
    }
    if (progress) progress(1.0);
    bvh.stats.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return bvh;
}

std::vector<Primitive> trianglePrimitives(std::span<const Triangle> triangles) {
    std::vector<Primitive> primitives(triangles.size());
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        Box b;
        for (const glm::vec3& p : triangles[i].position) b.grow(p);
        // The box centre as centroid: cheaper and as good as the mean.
        primitives[i] = {b, 0.5f * (b.min + b.max), static_cast<std::uint32_t>(i)};
    }
    return primitives;
}

// Appends `tree`'s nodes to `nodes`, its triangles' positions moved on by `firstTriangle`; returns
// where its root went.
std::uint32_t appendTree(std::vector<gpu::BvhNode>& nodes, const Bvh& tree, std::uint32_t firstTriangle) {
    const auto offset = static_cast<std::uint32_t>(nodes.size());
    for (gpu::BvhNode node : tree.nodes) {
        const bool interior = (std::bit_cast<std::uint32_t>(node.boundsMax.w) & gpu::kInteriorNodeFlag) != 0;
        node.boundsMin.w =
            std::bit_cast<float>(std::bit_cast<std::uint32_t>(node.boundsMin.w) + (interior ? offset : firstTriangle));
        nodes.push_back(node);
    }
    return offset;
}

// Boxes of a tree's nodes that together hold every triangle of it: from the root, the node of
// largest area is replaced by its children until there are `parts` (or only leaves). Moved into
// the world they bound a turned copy of the mesh far more tightly than its one box does.
std::vector<FloatBox> treeCut(const Bvh& tree, std::size_t parts) {
    auto box = [&](std::uint32_t index) {
        const gpu::BvhNode& node = tree.nodes[index];
        return FloatBox{glm::vec3(node.boundsMin), glm::vec3(node.boundsMax)};
    };
    auto area = [&](std::uint32_t index) {
        const glm::vec3 d = box(index).max - box(index).min;
        return d.x * d.y + d.y * d.z + d.z * d.x;
    };
    auto interior = [&](std::uint32_t index) {
        return (std::bit_cast<std::uint32_t>(tree.nodes[index].boundsMax.w) & gpu::kInteriorNodeFlag) != 0;
    };
    std::vector<std::uint32_t> leaves;                       // of the cut, not to be split
    std::vector<std::pair<float, std::uint32_t>> splittable;  // a heap by area
    if (interior(0)) splittable.push_back({area(0), 0u});
    else leaves.push_back(0u);
    while (!splittable.empty() && leaves.size() + splittable.size() < parts) {
        std::pop_heap(splittable.begin(), splittable.end());
        const std::uint32_t node = splittable.back().second;
        splittable.pop_back();
        for (const std::uint32_t child : {node + 1, std::bit_cast<std::uint32_t>(tree.nodes[node].boundsMin.w)}) {
            if (!interior(child)) {
                leaves.push_back(child);
                continue;
            }
            splittable.push_back({area(child), child});
            std::push_heap(splittable.begin(), splittable.end());
        }
    }
    std::vector<FloatBox> cut;
    for (const std::uint32_t node : leaves) cut.push_back(box(node));
    for (const auto& [nodeArea, node] : splittable) cut.push_back(box(node));
    return cut;
}

}  // namespace

Bvh buildBvh(std::span<const Triangle> triangles, const std::function<void(double)>& progress, unsigned threads) {
    return buildTree(trianglePrimitives(triangles), TreeLimits{}, progress, threads);
}

Bvh buildSceneBvh(const Scene& scene, const std::function<void(double)>& progress, unsigned threads) {
    if (scene.instances.empty()) return buildBvh(scene.triangles, progress, threads);
    if (scene.instances.size() >= (std::size_t(1) << kMaxTopLevelDepth))
        throw std::length_error("a scene may have at most " + std::to_string((1u << kMaxTopLevelDepth) - 1) +
                                " instances");
    const auto start = std::chrono::steady_clock::now();
    const TreeLimits meshLimits{kMaxMeshTreeDepth, gpu::kMaxLeafTriangles};
    const std::uint32_t worldCount = worldTriangleCount(scene);
    // The trees below the top level: the world triangles' (where there are any), then each mesh's.
    std::vector<Bvh> trees;
    std::vector<std::uint32_t> firsts;
    if (worldCount > 0) {
        trees.push_back(buildTree(trianglePrimitives(std::span(scene.triangles).first(worldCount)), meshLimits, {}, threads));
        firsts.push_back(0);
    }
    for (const Mesh& mesh : scene.meshes) {
        trees.push_back(buildTree(trianglePrimitives(std::span(scene.triangles).subspan(mesh.first, mesh.count)),
                                  meshLimits, {}, threads));
        firsts.push_back(mesh.first);
    }
    if (progress) progress(0.5);
    // The top level: one leaf an instance (the world triangles' tree as an instance of its own).
    // A copy's box is the union of 64 upper boxes of its mesh's tree moved into the world, which
    // fits a turned copy more tightly than its moved mesh box (docs/gpu-design.md, "Boxes that fit
    // turned copies", which also says why 64).
    const std::uint32_t meshTreeOffset = worldCount > 0 ? 1 : 0;
    std::vector<std::vector<FloatBox>> meshCuts;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) meshCuts.push_back(treeCut(trees[meshTreeOffset + m], 64));
    std::vector<Primitive> items(scene.instances.size());
    parallelFor(
        scene.instances.size(),
        [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) {
                const FloatBox b = instanceBox(scene.instances[i], meshCuts[scene.instances[i].mesh]);
                items[i] = {Box{b.min, b.max}, 0.5f * (b.min + b.max), std::uint32_t(i)};
            }
        },
        4096);
    if (worldCount > 0) {
        const gpu::BvhNode& root = trees.front().nodes.front();
        const Box b{glm::vec3(root.boundsMin), glm::vec3(root.boundsMax)};
        items.push_back({b, 0.5f * (b.min + b.max), std::uint32_t(scene.instances.size())});
    }
    Bvh bvh = buildTree(std::move(items), TreeLimits{kMaxTopLevelDepth, 1}, {}, threads);
    for (gpu::BvhNode& node : bvh.nodes) {
        if (std::bit_cast<std::uint32_t>(node.boundsMax.w) & gpu::kInteriorNodeFlag) continue;
        node.boundsMin.w = std::bit_cast<float>(bvh.triangleOrder[std::bit_cast<std::uint32_t>(node.boundsMin.w)]);
        node.boundsMax.w = std::bit_cast<float>(0u);  // count 0: an instance
    }
    std::vector<std::uint32_t> roots;
    for (std::size_t t = 0; t < trees.size(); ++t) {
        roots.push_back(appendTree(bvh.nodes, trees[t], firsts[t]));
        bvh.stats.leafCount += trees[t].stats.leafCount;
        bvh.stats.maxLeafTriangles = std::max(bvh.stats.maxLeafTriangles, trees[t].stats.maxLeafTriangles);
    }
    // The depth through a leaf of the top level into the deepest tree below; the SAH cost stays
    // the top level's.
    std::uint32_t deepest = 0;
    for (const Bvh& tree : trees) deepest = std::max(deepest, tree.stats.maxDepth);
    bvh.stats.maxDepth += 1 + deepest;
    bvh.stats.nodeCount = std::uint32_t(bvh.nodes.size());
    bvh.triangleOrder.assign(scene.triangles.size(), 0);
    for (std::size_t t = 0; t < trees.size(); ++t)
        for (std::size_t i = 0; i < trees[t].triangleOrder.size(); ++i)
            bvh.triangleOrder[firsts[t] + i] = firsts[t] + trees[t].triangleOrder[i];
    for (const Instance& instance : scene.instances) {
        gpu::GpuInstance g{};
        const glm::mat4 toObject = glm::transpose(instance.worldToObject);  // rows as columns
        const glm::mat4 toWorld = glm::transpose(instance.objectToWorld);
        g.toObject0 = toObject[0];
        g.toObject1 = toObject[1];
        g.toObject2 = toObject[2];
        g.toWorld0 = toWorld[0];
        g.toWorld1 = toWorld[1];
        g.toWorld2 = toWorld[2];
        g.info = glm::uvec4(roots[meshTreeOffset + instance.mesh], 0u, instance.firstObject, 0u);
        bvh.instances.push_back(g);
    }
    if (worldCount > 0) {
        gpu::GpuInstance world{};
        world.toObject0 = world.toWorld0 = glm::vec4(1, 0, 0, 0);
        world.toObject1 = world.toWorld1 = glm::vec4(0, 1, 0, 0);
        world.toObject2 = world.toWorld2 = glm::vec4(0, 0, 1, 0);
        world.info = glm::uvec4(roots[0], 0u, 0u, gpu::kIdentityInstance);
        bvh.instances.push_back(world);
    }
    if (progress) progress(1.0);
    bvh.stats.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return bvh;
}

void packTriangleVertices(const Bvh& bvh, std::span<const Triangle> triangles, std::span<gpu::TriangleVertices> into,
                          std::size_t first) {
    for (std::size_t i = 0; i < into.size(); ++i) {
        const Triangle& tri = triangles[bvh.triangleOrder[first + i]];
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
