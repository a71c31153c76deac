// NAADF edits: after any sequence of edits every cell matches a voxel_model that received
// the same edits and every cuboid is empty; after refine() the cells equal a fresh
// build's and the hits are bit-identical to it; storage is reused (live groups and
// arrays equal a fresh build's after 10,000 sphere edits); growth, the outside-edit
// policies, concurrent editors, lines, copies and incremental updates.
#include <gtest/gtest.h>

#include <cstdio>
#include <thread>
#include <variant>
#include <vector>

#include "naadf_cells.hpp"
#include "random_models.hpp"
#include "voxray/brickmap/detail/edit.hpp"
#include "voxray/check/random_edits.hpp"
#include "voxray/cpu.hpp"
#include "voxray/naadf/naadf.hpp"
#include "voxray/tracer.hpp"

namespace voxray::test {
namespace {

void apply_edit(naadf& s, const region_edit& e, unsigned threads = 2) {
    std::visit([&](const auto& r) { s.apply(r, e.op, naadf::payload_type(e.value), threads); }, e.region);
}

// Hits of a and b on the same rays, equal field for field (steps aside).
void expect_same_hits(naadf& a, const naadf& b, std::span<const ray> rays, const std::string& what) {
    std::vector<hit> ha(rays.size()), hb(rays.size());
    tracer<cpu, naadf>(a).closest_hit(rays, ha);
    tracer<cpu, naadf>(b).closest_hit(rays, hb);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        ASSERT_EQ(ha[i].status, hb[i].status) << what << " ray " << i;
        ASSERT_EQ(ha[i].voxel, hb[i].voxel) << what << " ray " << i;
        ASSERT_EQ(ha[i].t, hb[i].t) << what << " ray " << i;
        ASSERT_EQ(ha[i].normal, hb[i].normal) << what << " ray " << i;
        ASSERT_EQ(ha[i].material, hb[i].material) << what << " ray " << i;
    }
}

// Cells of `edited` equal those of `fresh` voxel by voxel over `world` (page fields
// aside: a fresh build's page table may be smaller).
void expect_same_cells(const naadf& edited, const naadf& fresh, const box3i& world) {
    for (int z = world.min.z; z < world.max.z; ++z)
        for (int y = world.min.y; y < world.max.y; ++y)
            for (int x = world.min.x; x < world.max.x; ++x) {
                decoded_cell a = cell_at(edited.blob(), {x, y, z}), b = cell_at(fresh.blob(), {x, y, z});
                ASSERT_EQ(a.level, b.level) << x << " " << y << " " << z;
                if (a.level < VX_NA_PAGE_BITS || b.solid) {
                    ASSERT_EQ(a.value, b.value) << x << " " << y << " " << z;
                }
            }
}

// Dense content (every chunk stays non-empty) and sparse content (edits turn chunks
// and pages empty and non-empty, so chunk and page fields are reset and regrown).
void random_edits_then_refine(voxel_model model, int count, std::uint64_t seed, bool expect_reset) {
    naadf s(model);
    const box3i world = s.bounds();
    auto edits = random_edits(world, count, seed);
    for (std::size_t i = 0; i < edits.size(); ++i) {
        apply_edit(s, edits[i], 1 + unsigned(i % 2));
        apply_to_model(model, edits[i], world);
        if (i % 60 == 59) {
            expect_cells_match(s.blob(), model, world, "after edit " + std::to_string(i));
            ASSERT_EQ(s.voxel_count(), model.voxel_count()) << i;
        }
    }
    // Fields an edit reset are correct but short; refine grows them to what a fresh
    // build has, cell for cell, and the hits stay bit-identical throughout.
    naadf fresh(model);
    auto rays = random_rays(world, 3000, seed + 1);
    expect_same_hits(s, fresh, rays, "before refine");
    if (expect_reset) {
        EXPECT_FALSE(s.refine_progress().done());
    }
    EXPECT_TRUE(s.refine().done());
    expect_cells_match(s.blob(), model, world, "after refine");
    expect_same_cells(s, fresh, world);
    expect_same_hits(s, fresh, rays, "after refine");
}

TEST(naadf_edit, random_edits_match_the_model_and_every_cuboid_stays_empty) {
    // Both straddle pages (x crosses 256) and sit at negative coordinates.
    random_edits_then_refine(random_model(70, 0.08f, 3, {220, -30, 5}), 240, 77, false);
    random_edits_then_refine(random_sparse({{200, -30, 5}, {290, 40, 75}}, 40, 4), 240, 78, true);
}

TEST(naadf_edit, batches_equal_the_same_edits_one_by_one) {
    voxel_model model = random_model(40, 0.1f, 8);
    naadf one(model), batch(model);
    const box3i world = one.bounds();
    auto edits = random_edits(world, 80, 9);
    std::vector<naadf::edit> typed;
    for (auto& e : edits) {
        apply_edit(one, e);
        typed.push_back({e.region, e.op, naadf::payload_type(e.value)});
    }
    batch.apply_batch(typed, 2);
    one.refine();
    batch.refine();
    expect_same_cells(one, batch, world);
    EXPECT_EQ(one.voxel_count(), batch.voxel_count());
}

TEST(naadf_edit, ten_thousand_sphere_edits_reuse_their_storage) {
    voxel_model model = random_model(96, 0.05f, 4);
    naadf s(model);
    const box3i world = s.bounds();
    std::size_t bytes_at_start = s.bytes(), bytes_at_1000 = 0;
    rng g(31);
    for (int i = 0; i < 10000; ++i) {
        glm::ivec3 c = world.min + glm::ivec3(g.below(96), g.below(96), g.below(96));
        regions::sphere r{c, 1 + g.below(7)};
        edit_op op = g.below(2) ? edit_op::fill : edit_op::erase;
        auto value = naadf::payload_type(1 + g.below(255));
        s.apply(r, op, value);
        apply_to_model(model, {r, op, value}, world);
        if (i == 999) bytes_at_1000 = s.bytes();
    }
    s.refine();
    naadf fresh(model);
    std::printf("blob bytes: built %zu, after 1,000 edits %zu, after 10,000 %zu; a fresh build of the result %zu\n",
                bytes_at_start, bytes_at_1000, s.bytes(), fresh.bytes());
    // Exactly the storage a fresh build needs is in use: every unreachable group and
    // array went back to the free lists.
    EXPECT_EQ(s.stats().groups, fresh.stats().groups);
    EXPECT_EQ(s.stats().mixed_chunks, fresh.stats().mixed_chunks);
    EXPECT_EQ(s.stats().mixed_pages, fresh.stats().mixed_pages);
    EXPECT_EQ(s.voxel_count(), model.voxel_count());
    // Capacity follows the content, not the number of edits.
    EXPECT_LE(s.bytes(), 2 * fresh.bytes());
    EXPECT_LE(s.bytes(), bytes_at_1000 + bytes_at_1000 / 2);
    expect_cells_match(s.blob(), model, world, "after 10,000 edits");
}

TEST(naadf_edit, an_update_sends_only_the_edited_words) {
    voxel_model model = random_model(64, 0.1f, 5);
    naadf s(model);
    tracer<cpu, naadf> t(s);
    s.fill_sphere({20, 30, 40}, 3, 7);
    s.refine();
    t.update(s);
    EXPECT_GT(t.bytes_uploaded_last_update(), 0u);
    EXPECT_LT(t.bytes_uploaded_last_update(), s.bytes() / 10);
    apply_to_model(model, {regions::sphere{{20, 30, 40}, 3}, edit_op::fill, 7}, s.bounds());
    auto rays = random_rays(s.bounds(), 2000, 3);
    std::vector<hit> incremental(rays.size()), full(rays.size());
    t.closest_hit(rays, incremental);
    tracer<cpu, naadf>(naadf(model)).closest_hit(rays, full);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        ASSERT_EQ(incremental[i].voxel, full[i].voxel) << i;
        ASSERT_EQ(incremental[i].t, full[i].t) << i;
        ASSERT_EQ(incremental[i].material, full[i].material) << i;
    }
}

TEST(naadf_edit, fills_outside_the_world_grow_it_or_fail_or_clip_as_asked) {
    voxel_model model = random_model(20, 0.2f, 6);
    naadf grow(model), fail_(model, {.outside = outside_edits::fail}), clip(model, {.outside = outside_edits::clip});
    const box3i world = grow.bounds();
    // A sphere far below the world, in pages the table does not have yet.
    regions::sphere far{{-700, 10, 300}, 5};
    grow.apply(far, edit_op::fill, 42);
    apply_to_model(model, {far, edit_op::fill, 42}, world);
    EXPECT_EQ(grow.get({-700, 10, 300}), 42);
    EXPECT_EQ(grow.voxel_count(), model.voxel_count());
    box3i grown = grow.bounds();
    EXPECT_LE(grown.min.x, -705);
    EXPECT_GE(grown.max.z, 306);
    grow.refine();
    expect_cells_match(grow.blob(), model, model.bounds(), "grown");
    std::vector<ray> rays{ray{{-699.5f, 10.5f, 1000.f}, 0.f, {0, 0, -1}}, ray{{5.5f, 5.5f, -50.f}, 0.f, {0, 0, 1}}};
    std::vector<hit> hits(rays.size());
    tracer<cpu, naadf>(grow).closest_hit(rays, hits);
    EXPECT_EQ(hits[0].voxel, glm::ivec3(-700, 10, 305));
    EXPECT_EQ(hits[0].material, 42u);
    // Within the page table: only the header moves.
    naadf near(random_model(20, 0.2f, 6));
    near.set({40, 3, 3}, 9);
    EXPECT_EQ(near.get({40, 3, 3}), 9);
    EXPECT_GE(near.bounds().max.x, 41);

    // An empty structure takes its world from the first fill.
    naadf empty;
    empty.fill_sphere({1000, -5, 3}, 2, 4);
    EXPECT_EQ(empty.get({1000, -5, 3}), 4);
    EXPECT_EQ(empty.voxel_count(), 33u);
    std::vector<hit> one(1);
    tracer<cpu, naadf>(empty).closest_hit(std::vector<ray>{ray{{1000.5f, -4.5f, 100.f}, 0.f, {0, 0, -1}}}, one);
    EXPECT_EQ(one[0].voxel, glm::ivec3(1000, -5, 5));

    auto before = std::vector<std::uint32_t>(fail_.blob().begin(), fail_.blob().end());
    EXPECT_THROW(fail_.apply(far, edit_op::fill, 42), error);
    EXPECT_TRUE(std::equal(before.begin(), before.end(), fail_.blob().begin(), fail_.blob().end()));
    regions::sphere edge{{19, 10, 10}, 3};
    clip.apply(edge, edit_op::fill, 42);
    EXPECT_EQ(clip.bounds().max, world.max);
    EXPECT_EQ(clip.get({19, 10, 10}), 42);
    EXPECT_EQ(clip.get({21, 10, 10}), 0);
}

TEST(naadf_edit, threads_editing_at_once_give_the_sequential_result) {
    voxel_model model = random_model(64, 0.05f, 12);
    naadf s(model);
    const box3i world = s.bounds();
    // Each thread edits its own x slab, so the result does not depend on the order.
    std::vector<std::vector<region_edit>> work(4);
    for (int k = 0; k < 4; ++k) {
        box3i slab = world;
        slab.min.x = world.min.x + k * 16;
        slab.max.x = slab.min.x + 16;
        work[k] = random_edits(slab, 40, 50 + k);
        for (auto& e : work[k]) apply_to_model(model, e, world);
    }
    std::vector<std::thread> threads;
    for (int k = 0; k < 4; ++k)
        threads.emplace_back([&, k] {
            for (auto& e : work[k]) apply_edit(s, e, 1);
        });
    threads.emplace_back([&] {  // a reader meanwhile: consistent frames
        for (int i = 0; i < 20; ++i) {
            auto frame = s.snapshot();
            EXPECT_EQ(frame.blob[VX_NA_HEADER_MAGIC], VX_NA_MAGIC);
        }
    });
    for (auto& t : threads) t.join();
    EXPECT_EQ(s.voxel_count(), model.voxel_count());
    expect_cells_match(s.blob(), model, world, "after concurrent edits");
}

TEST(naadf_edit, lines_copies_and_single_voxels_match_the_brickmap) {
    voxel_model model = random_model(48, 0.1f, 13, {-8, 0, 0});
    naadf s(model);
    brickmap<> b = brickmap<>::build(model);
    const box3i world = s.bounds();
    auto edit = [](auto& x) {
        x.apply_line({-8, 0, 0}, {39, 47, 30}, 0, edit_op::fill, 77);
        x.apply_line({0, 40, 2}, {30, 2, 40}, 2, edit_op::erase, 0);
        x.copy_region({{-8, 0, 0}, {12, 20, 20}}, {20, 20, 20});
        x.copy_region({{0, 0, 0}, {16, 16, 16}}, {4, 4, 4}, edit_op::paint, false);  // overlapping
        x.set({5, 5, 5}, 3);
        x.set({6, 5, 5}, 0);
    };
    edit(s);
    edit(b);
    for (int z = world.min.z; z < world.max.z; ++z)
        for (int y = world.min.y; y < world.max.y; ++y)
            for (int x = world.min.x; x < world.max.x; ++x)
                ASSERT_EQ(s.get({x, y, z}), b.get({x, y, z})) << x << " " << y << " " << z;
}

TEST(naadf_edit, refine_grows_deferred_fields_step_by_step_to_the_full_build) {
    voxel_model model = random_model(300, 0.0005f, 14);  // 2 x 2 x 2 pages
    naadf full(model), deferred(model, {.defer_chunk_fields = true});
    auto rays = random_rays(model.bounds(), 2000, 15);
    auto progress = deferred.refine_progress();
    EXPECT_EQ(progress.pages_left, 8u);
    EXPECT_TRUE(progress.table_left);
    expect_same_hits(deferred, full, rays, "deferred");
    EXPECT_EQ(deferred.refine(3).pages_left, 5u);
    expect_same_hits(deferred, full, rays, "3 pages refined");
    EXPECT_TRUE(deferred.refine().done());
    auto a = deferred.blob(), b = full.blob();
    ASSERT_EQ(a.size(), b.size());
    EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin()));
}

TEST(naadf_edit, erasing_everything_frees_everything) {
    voxel_model model = random_model(40, 0.2f, 16, {250, 250, 250});
    naadf s(model);
    s.erase_box(s.bounds(), 2);
    EXPECT_EQ(s.voxel_count(), 0u);
    EXPECT_EQ(s.stats().groups, 0u);
    EXPECT_EQ(s.stats().mixed_chunks, 0u);
    EXPECT_EQ(s.stats().mixed_pages, 0u);
    auto rays = random_rays(s.bounds(), 500, 17);
    std::vector<hit> hits(rays.size());
    tracer<cpu, naadf>(s).closest_hit(rays, hits);
    for (auto& h : hits) ASSERT_EQ(h.status, VX_STATUS_MISS);
}

// An edit that needs more blob than the limit allows fails with an error naming it, and
// leaves a consistent structure: the chunks committed before the failure stay, every
// cell decodes to what get() says, every cuboid is empty, the count is right, and it
// keeps working.
TEST(naadf_edit, an_edit_past_the_blob_limit_fails_and_leaves_a_consistent_structure) {
    voxel_model model = random_sparse({{0, 0, 0}, {200, 200, 200}}, 20, 40);
    naadf s(model, {.headroom = 0, .max_blob_bytes = naadf(model).bytes() + 200'000});
    const box3i world = s.bounds();
    // Checkered blocks everywhere: a new block array and groups for every chunk.
    std::vector<naadf::edit> edits;
    for (int z = world.min.z; z + 4 < world.max.z; z += 8)
        edits.push_back({regions::box{{{world.min.x, world.min.y, z}, {world.max.x, world.max.y, z + 3}}}, edit_op::fill, 5});
    try {
        s.apply_batch(edits, 2);
        FAIL() << "the edit fit";
    } catch (const error& e) {
        EXPECT_NE(std::string(e.what()).find("max_blob_bytes"), std::string::npos) << e.what();
    }
    EXPECT_LE(s.bytes(), naadf(model).bytes() + 200'000);
    voxel_model seen;
    for (int z = world.min.z; z < world.max.z; ++z)
        for (int y = world.min.y; y < world.max.y; ++y)
            for (int x = world.min.x; x < world.max.x; ++x)
                if (auto v = s.get({x, y, z})) seen.set({x, y, z}, v);
    EXPECT_GT(seen.voxel_count(), model.voxel_count());  // part of the edit is in
    EXPECT_EQ(s.voxel_count(), seen.voxel_count());
    expect_cells_match(s.blob(), seen, world, "after the failed edit");
    s.erase_box(world, 2);  // and it still edits, freeing everything
    EXPECT_EQ(s.voxel_count(), 0u);
    EXPECT_EQ(s.stats().groups, 0u);
}

}  // namespace
}  // namespace voxray::test
