#include "distributed/distributed_render.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include "distributed/mpi_wait.h"
#include "gpu/tile_schedule.h"

namespace vitrum {
namespace {

using Clock = std::chrono::steady_clock;

// A rank asks rank 0 for a tile with the pixels of the one it finished (none at its first ask):
// [tile index, or kNoTile][its pixels as linear RGB floats, row by row]. Rank 0 answers with the
// next tile's index, or kNoTile when none is left.
constexpr int kTagRequest = 1;
constexpr int kTagTile = 2;
constexpr std::uint32_t kNoTile = 0xFFFFFFFFu;

// What each rank reports at the end, gathered to rank 0 as bytes.
struct RankSummary {
    TraceCounts counts;
    std::uint64_t dispatches = 0, restartedPixels = 0, tiles = 0;
    double renderSeconds = 0;
    char device[128] = {};
};
static_assert(std::is_trivially_copyable_v<RankSummary>);

RankSummary summaryOf(const RenderStats& stats, std::uint64_t tiles) {
    RankSummary s;
    s.counts = stats;
    s.dispatches = stats.dispatches;
    s.restartedPixels = stats.restartedPixels;
    s.tiles = tiles;
    s.renderSeconds = stats.seconds("render");
    std::strncpy(s.device, stats.device.c_str(), sizeof(s.device) - 1);
    return s;
}

// A rank other than 0: its tiles come from rank 0, and go back to it with the next ask.
class WorkerTiles final : public TileSchedule {
public:
    std::optional<std::uint32_t> next() override {
        if (request_.empty()) request_.resize(sizeof(kNoTile));
        std::memcpy(request_.data(), &kNoTile, sizeof(kNoTile));
        if (finished_) {
            std::memcpy(request_.data(), &*finished_, sizeof(*finished_));
            finished_.reset();
        }
        MPI_Request requests[2];
        std::uint32_t tile = kNoTile;
        MPI_Irecv(&tile, 1, MPI_UINT32_T, 0, kTagTile, MPI_COMM_WORLD, &requests[1]);
        MPI_Isend(request_.data(), int(request_.size()), MPI_BYTE, 0, kTagRequest, MPI_COMM_WORLD, &requests[0]);
        waitWithoutSpinning(requests[0]);
        waitWithoutSpinning(requests[1]);
        request_.resize(sizeof(kNoTile));
        if (tile == kNoTile) return std::nullopt;
        ++tiles_;
        return tile;
    }

    void finished(std::uint32_t index, const Image& pixels) override {
        const std::size_t bytes = pixels.pixels.size() * sizeof(glm::vec3);
        request_.resize(sizeof(index) + bytes);
        std::memcpy(request_.data() + sizeof(index), pixels.pixels.data(), bytes);
        finished_ = index;
    }

    std::uint64_t tiles() const { return tiles_; }

private:
    std::vector<char> request_;
    std::optional<std::uint32_t> finished_;
    std::uint64_t tiles_ = 0;
};

// Rank 0's image and the tiles not yet handed out: its own render thread and the thread that
// serves the other ranks share them.
class RootTiles {
public:
    RootTiles(const TileGrid& grid, const PhaseCallback& progress)
        : grid_(grid), image_(grid.width, grid.height), progress_(progress) {}

    std::optional<std::uint32_t> take() {
        std::lock_guard lock(mutex_);
        if (next_ == grid_.count()) return std::nullopt;
        if (next_ == 0) firstTaken_ = Clock::now();
        return next_++;
    }

    void put(std::uint32_t index, const Image& pixels) {
        std::lock_guard lock(mutex_);
        const auto start = Clock::now();
        LocalTiles::copyTile(grid_, index, pixels, image_);
        assembleSeconds_ += std::chrono::duration<double>(Clock::now() - start).count();
        if (++done_ == grid_.count()) lastDone_ = Clock::now();
        if (progress_) progress_("rendering", double(done_) / double(grid_.count()));
    }

    // The progress of rank 0's own render before its tiles: its analysis and upload, shown until
    // the first tile of the image is done.
    void phase(const std::string& name, double fraction) {
        std::lock_guard lock(mutex_);
        if (progress_ && done_ == 0 && name != "rendering") progress_(name, fraction);
    }

    const TileGrid& grid() const { return grid_; }
    Image& image() { return image_; }
    double assembleSeconds() const { return assembleSeconds_; }
    // From the first tile handed out to the last one put into the image.
    double renderSeconds() const { return std::chrono::duration<double>(lastDone_ - firstTaken_).count(); }

private:
    std::mutex mutex_;
    TileGrid grid_;
    Image image_;
    PhaseCallback progress_;
    std::uint32_t next_ = 0, done_ = 0;
    double assembleSeconds_ = 0;
    Clock::time_point firstTaken_, lastDone_;
};

class RootOwnTiles final : public TileSchedule {
public:
    explicit RootOwnTiles(RootTiles& shared) : shared_(shared) {}
    std::optional<std::uint32_t> next() override {
        std::optional<std::uint32_t> tile = shared_.take();
        if (tile) ++tiles_;
        return tile;
    }
    void finished(std::uint32_t index, const Image& pixels) override { shared_.put(index, pixels); }
    std::uint64_t tiles() const { return tiles_; }

private:
    RootTiles& shared_;
    std::uint64_t tiles_ = 0;
};

// Serves the other ranks until each has been told that no tile is left, while rank 0's own
// render runs on another thread (only this thread calls MPI). Returns the bytes sent.
std::uint64_t serveTiles(int ranks, RootTiles& tiles, const std::atomic<bool>& ownRenderFailed) {
    std::uint64_t bytes = 0;
    std::vector<char> request;
    Image pixels;
    for (int working = ranks - 1; working > 0;) {
        MPI_Status status;
        int arrived = 0;
        for (;;) {
            MPI_Iprobe(MPI_ANY_SOURCE, kTagRequest, MPI_COMM_WORLD, &arrived, &status);
            if (arrived || ownRenderFailed) break;
            std::this_thread::sleep_for(kMpiPollInterval);
        }
        if (!arrived) return bytes;  // the caller rethrows the render's error
        int size = 0;
        MPI_Get_count(&status, MPI_BYTE, &size);
        request.resize(std::size_t(size));
        MPI_Recv(request.data(), size, MPI_BYTE, status.MPI_SOURCE, kTagRequest, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        bytes += std::uint64_t(size);
        std::uint32_t index = kNoTile;
        if (request.size() >= sizeof(index)) std::memcpy(&index, request.data(), sizeof(index));
        if (index != kNoTile) {
            const glm::uvec2 inside = index < tiles.grid().count() ? tiles.grid().pixelsInside(index) : glm::uvec2(0);
            const std::size_t expected = sizeof(index) + std::size_t(inside.x) * inside.y * sizeof(glm::vec3);
            if (index >= tiles.grid().count() || request.size() != expected)
                throw std::runtime_error("rank " + std::to_string(status.MPI_SOURCE) + " sent tile " +
                                         std::to_string(index) + " with " + std::to_string(request.size()) +
                                         " bytes, not the " + std::to_string(expected) + " of its pixels");
            pixels = Image(inside.x, inside.y);
            std::memcpy(pixels.pixels.data(), request.data() + sizeof(index), expected - sizeof(index));
            tiles.put(index, pixels);
        }
        const std::uint32_t reply = tiles.take().value_or(kNoTile);
        MPI_Send(&reply, 1, MPI_UINT32_T, status.MPI_SOURCE, kTagTile, MPI_COMM_WORLD);
        bytes += sizeof(reply);
        if (reply == kNoTile) --working;
    }
    return bytes;
}

}  // namespace

Image renderDistributed(MpiJob& job, VulkanDevice& device, const Scene& scene, const Bvh& bvh,
                        const VulkanRenderOptions& options, RenderStats& stats, DistributedReport& report) {
    const TileGrid grid = tileGridFor(device, scene, options);
    std::uint64_t ownTiles = 0;
    std::optional<RootTiles> shared;
    if (job.rank() != 0) {
        WorkerTiles tiles;
        VulkanRenderOptions quiet = options;
        quiet.progress = nullptr;
        renderVulkanTiles(device, scene, bvh, quiet, tiles, stats);
        ownTiles = tiles.tiles();
    } else {
        shared.emplace(grid, options.progress);
        VulkanRenderOptions own = options;
        own.progress = [&](const std::string& phase, double fraction) { shared->phase(phase, fraction); };
        RootOwnTiles tiles(*shared);
        std::exception_ptr failure;
        std::atomic<bool> failed{false};
        std::thread render([&] {
            try {
                renderVulkanTiles(device, scene, bvh, own, tiles, stats);
            } catch (...) {
                failure = std::current_exception();
                failed = true;
            }
        });
        try {
            report.bytesSent = serveTiles(job.size(), *shared, failed);
        } catch (...) {
            render.join();
            throw;
        }
        render.join();
        if (failure) std::rethrow_exception(failure);
        ownTiles = tiles.tiles();
    }

    const RankSummary mine = summaryOf(stats, ownTiles);
    std::vector<char> bytes(sizeof(mine));
    std::memcpy(bytes.data(), &mine, sizeof(mine));
    const std::vector<std::vector<char>> all = job.gatherToRoot(bytes);
    const std::vector<std::string> hosts = job.hosts();
    if (job.rank() != 0) return Image();

    // The image's render time is the job's, not rank 0's share of it.
    for (auto& [phase, seconds] : stats.phaseSeconds)
        if (phase == "render") seconds = shared->renderSeconds();
    report.tiles = grid.count();
    report.assembleSeconds = shared->assembleSeconds();
    report.bytesSent += std::uint64_t(job.size() - 1) * sizeof(RankSummary);
    for (int r = 0; r < job.size(); ++r) {
        RankSummary s;
        std::memcpy(&s, all[std::size_t(r)].data(), sizeof(s));
        if (r > 0) {
            stats += s.counts;
            stats.dispatches += s.dispatches;
            stats.restartedPixels += s.restartedPixels;
        }
        report.ranks.push_back({r, hosts[std::size_t(r)], s.device, s.tiles, s.renderSeconds});
    }
    return std::move(shared->image());
}

}  // namespace vitrum
