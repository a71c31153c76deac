// Saving and uploading a brickmap while other threads edit it: every file saved meanwhile
// loads (checksum and voxel count agree with its content), tracer::update() reads the
// blob only inside a sync frame (TSan covers this file through the sync label), and once
// the editors stop, one more update leaves the device blob equal to the host's.
#include <atomic>
#include <filesystem>
#include <memory>
#include <unistd.h>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "voxray/brickmap/brickmap.hpp"
#include "voxray/brickmap/serialize.hpp"
#include "voxray/cpu.hpp"

using namespace voxray;

namespace {

// Random fills, erases, paints and single voxels, some reaching outside the world (it
// grows) and many new bricks (the pool grows): every kind of writer a save can meet.
void edit_randomly(brickmap<>& m, unsigned seed, const std::atomic<bool>& stop) {
    std::mt19937 g(seed);
    auto coord = [&](int lo, int hi) { return lo + int(g() % unsigned(hi - lo)); };
    for (int i = 0; !stop.load() || i < 200; ++i) {
        glm::ivec3 c(coord(-20, 110), coord(-10, 70), coord(-20, 110));
        auto v = std::uint8_t(1 + g() % 250);
        switch (g() % 5) {
        case 0: m.fill_sphere(c, coord(1, 9), v); break;
        case 1: m.erase_sphere(c, coord(1, 7)); break;
        case 2: m.paint_box({c - 4, c + 5}, v); break;
        case 3: m.fill_box({c, c + glm::ivec3(coord(1, 12), coord(1, 5), coord(1, 12))}, v, 2); break;
        default:
            for (int k = 0; k < 20; ++k) m.set(c + glm::ivec3(k, k % 3, 2 * k), v);
        }
        if (i > 5000) break;  // bounds the run if the main thread is slow
    }
}

}  // namespace

TEST(edit_while_sync, saves_load_and_updates_converge) {
    brickmap<> m(box3i{{0, 0, 0}, {96, 64, 96}}, {4, 1});  // tiny pool: growth during the run
    tracer<cpu, brickmap<>> early(m, cpu_options{1});
    std::atomic<bool> stop{false};
    std::vector<std::thread> editors;
    for (unsigned t = 0; t < 3; ++t) editors.emplace_back([&, t] { edit_randomly(m, 50 + t, stop); });

    auto dir = std::filesystem::temp_directory_path() / ("voxray_edit_while_sync_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    int saves = 0, loaded = 0;
    std::unique_ptr<tracer<cpu, brickmap<>>> late;
    for (int round = 0; round < 12; ++round) {
        auto path = dir / ("snap" + std::to_string(round) + ".vxbm");
        save(m, path);
        ++saves;
        try {
            auto back = load_brickmap<brickmap<>>(path);
            ++loaded;
            EXPECT_GE(back.bounds().max.x, 96);
        } catch (const error& e) {
            ADD_FAILURE() << "snapshot " << round << " does not load: " << e.what();
        }
        early.update(m);  // incremental, while the editors run
        if (round == 4) late = std::make_unique<tracer<cpu, brickmap<>>>(m, cpu_options{1});
        if (late) late->update(m);
    }
    stop = true;
    for (auto& e : editors) e.join();
    EXPECT_EQ(loaded, saves);

    early.update(m);
    late->update(m);
    auto host = std::vector<std::uint32_t>(m.blob().begin(), m.blob().end());
    EXPECT_TRUE(early.engine().download_blob() == host) << "the early tracer's copy differs from the host blob";
    EXPECT_TRUE(late->engine().download_blob() == host) << "the late tracer's copy differs from the host blob";
    auto path = dir / "final.vxbm";
    save(m, path);
    auto back = load_brickmap<brickmap<>>(path);
    EXPECT_EQ(back.voxel_count(), m.voxel_count());
    EXPECT_TRUE(std::equal(host.begin(), host.end(), back.blob().begin(), back.blob().end()));
    std::filesystem::remove_all(dir);
}
