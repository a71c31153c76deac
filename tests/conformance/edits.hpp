// Incremental updates after seeded random region edits. An editable structure takes the
// edits through its own apply() and its tracer receives only the dirty ranges
// (tracer::update(structure)); any other structure is rebuilt from the edited model and
// sent whole. Either way the hits must match a dense grid rebuilt from a voxel_model that
// received the same edits, voxel by voxel, and the device must hold the host's blob.
#pragma once
#include <algorithm>
#include <variant>

#include "fixture.hpp"
#include "voxray/check/random_edits.hpp"
#include "random_models.hpp"
#include "special_rays.hpp"

namespace voxray::test {

template <class Case>
struct edit_suite : conformance<Case> {
    using typename conformance<Case>::structure;
    using typename conformance<Case>::tracer_type;

    static void apply_edit(structure& s, const region_edit& e) {
        using payload = typename structure::payload_type;
        std::visit(
            [&](const auto& region) {
                // Two threads where the structure can use them: edits split over bricks.
                if constexpr (requires { s.apply(region, e.op, payload(e.value), 2u); })
                    s.apply(region, e.op, payload(e.value), 2u);
                else
                    s.apply(region, e.op, payload(e.value));
            },
            e.region);
    }

    // Applies `edits` to the reference model and to the structure, then brings tracer t
    // up to date and checks what it sent and what the device holds.
    static void edit_and_update(const std::string& what, structure& s, tracer_type& t, voxel_model& model,
                                const box3i& world, std::span<const region_edit> edits, bool small) {
        for (auto& e : edits) apply_to_model(model, e, world);
        if constexpr (editable_structure<structure>) {
            std::size_t words = s.blob().size();
            for (auto& e : edits) apply_edit(s, e);
            t.update(s);  // takes the dirty ranges and sends only those words
            // A few small edits cost a few bricks, unless the blob was re-laid out.
            if (small && s.blob().size() == words) {
                EXPECT_LT(t.bytes_uploaded_last_update(), s.bytes()) << what << ": not incremental";
            }
        } else {
            s = structure(model);
            t.update(s);
            EXPECT_EQ(t.bytes_uploaded_last_update(), s.bytes()) << what;
        }
        if constexpr (requires { t.engine().download_blob(); }) {
            auto device = t.engine().download_blob();
            auto host = s.blob();
            ASSERT_EQ(device.size(), host.size()) << what;
            auto [a, b] = std::mismatch(device.begin(), device.end(), host.begin());
            EXPECT_TRUE(a == device.end()) << what << ": device blob differs from the host's at word "
                                           << (a - device.begin());
        }
    }

    // Hits of t against the reference dense grid of `model`, and bit for bit against a
    // fresh cpu_scalar tracer of s (incremental == full upload). Returns closest hits.
    static std::size_t expect_matches(const std::string& what, tracer_type& t, const structure& s,
                                      const voxel_model& model, std::span<const ray> rays) {
        auto expected = reference_hits(model, rays);
        for (mode m : {mode::closest, mode::any}) {
            auto c = expect_agreement(what, rays, expected, trace(t, rays, m), m);
            conformance<Case>::report(what + (m == mode::any ? " (any)" : ""), c);
        }
        conformance<Case>::expect_bit_identical(what, t, s, rays);
        return count_hits(expected);
    }
};
TYPED_TEST_SUITE_P(edit_suite);

TYPED_TEST_P(edit_suite, random_edits_then_update_agree_with_a_rebuilt_reference) {
    voxel_model model = random_model(41, 0.15f, 3, {-13, -7, 5});
    typename TestFixture::structure s(model);
    typename TestFixture::tracer_type t(s);
    const box3i world = s.bounds();
    // Many edits over the world (the pool grows), then a few in one corner (a few bricks).
    box3i corner{world.min + 3, world.min + 19};
    struct { box3i area; int count; bool small; } rounds[] = {
        {world, 60, false}, {corner, 4, true}, {world, 30, false}, {corner, 1, true}};
    for (int i = 0; i < 4; ++i) {
        std::string what = "edit round " + std::to_string(i);
        auto edits = random_edits(rounds[i].area, rounds[i].count, 100 + i);
        this->edit_and_update(what, s, t, model, world, edits, rounds[i].small);
        auto rays = mixed_rays(world, 3000, 200 + i);
        EXPECT_GT(this->expect_matches(what, t, s, model, rays), rays.size() / 20) << what;
    }
}

// Erasing the whole world empties it (bricks recycled, cells cleared); filling again
// brings voxels back where the reference has them.
TYPED_TEST_P(edit_suite, erase_everything_then_refill) {
    voxel_model model = patterned_block({-5, 0, 3}, {19, 13, 30});
    typename TestFixture::structure s(model);
    typename TestFixture::tracer_type t(s);
    const box3i world = s.bounds();
    auto rays = mixed_rays(world, 2000, 7);

    region_edit erase{regions::box{world}, edit_op::erase, 0};
    this->edit_and_update("erase all", s, t, model, world, std::span(&erase, 1), false);
    EXPECT_EQ(model.voxel_count(), 0u);
    EXPECT_EQ(this->expect_matches("erase all", t, s, model, rays), 0u);

    region_edit fill[] = {{regions::sphere{world.min + glm::ivec3(12, 6, 13), 6}, edit_op::fill, 7},
                          {regions::box{{world.min, world.min + glm::ivec3(9, 2, 27)}}, edit_op::fill, 3},
                          {regions::capsule{world.min, world.max - 1, 1}, edit_op::paint, 200}};
    this->edit_and_update("refill", s, t, model, world, fill, false);
    EXPECT_GT(this->expect_matches("refill", t, s, model, rays), rays.size() / 20);
}

REGISTER_TYPED_TEST_SUITE_P(edit_suite, random_edits_then_update_agree_with_a_rebuilt_reference,
                            erase_everything_then_refill);

}  // namespace voxray::test
