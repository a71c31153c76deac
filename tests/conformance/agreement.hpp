// Hits on many rays, checked three ways: against the brute-force oracle on small random
// models (lattice, grazing and random rays; negative coordinates, sizes that are no
// multiple of a brick), against the reference on tiny/huge/denormal direction components
// and on real scenes, and bit for bit against cpu_scalar on the same structure.
#pragma once
#include <map>
#include <string>

#include "fixture.hpp"
#include "random_models.hpp"
#include "special_rays.hpp"
#include "test_data.hpp"
#include "voxray/io/vox_reader.hpp"
#include "voxray/scenes/builtin.hpp"

namespace voxray::test {

template <class Case>
struct agreement_suite : conformance<Case> {};
TYPED_TEST_SUITE_P(agreement_suite);

// Sparse and dense noise, a shell seen from inside and out, solid blocks; offsets
// below zero and extents such as 13 x 7 x 10 and 37^3 that end inside a brick.
inline std::vector<named_model> oracle_models() {
    std::vector<named_model> out;
    out.push_back({"sparse noise", random_model(20, 0.05f, 1)});
    out.push_back({"dense noise, negative", random_model(16, 0.3f, 2, {-9, -3, -20})});
    out.push_back({"hollow box", hollow_box(18, {5, 5, 5})});
    out.push_back({"solid block 13x7x10", solid_block({-4, 0, 2}, {9, 7, 12})});
    out.push_back({"patterned block 21x9x11", patterned_block({-30, -1, 7}, {-9, 8, 18})});
    out.push_back({"noise 37^3, negative", random_model(37, 0.02f, 9, {-5, 3, -40})});
    return out;
}

TYPED_TEST_P(agreement_suite, random_models_agree_with_the_oracle) {
    std::uint64_t seed = 11;
    for (auto& [name, model] : oracle_models()) {
        auto rays = mixed_rays(model.bounds(), 2000, seed++);
        auto c = this->expect_agrees_with_oracle(name, model, rays);
        EXPECT_LT(c.ties, c.rays / 50) << name << ": ties should be rare edge/corner cases";
        EXPECT_GT(c.same, c.rays / 2) << name;
    }
}

TYPED_TEST_P(agreement_suite, lattice_rays_agree_with_the_oracle) {
    voxel_model shell = hollow_box(box3i{{0, 0, 0}, {6, 5, 4}});
    shell.set({2, 2, 2}, 77);  // something inside, for rays that start within the shell
    std::vector<ray> rays = lattice_rays(shell.bounds());
    this->expect_agrees_with_oracle("lattice, shell", shell, rays);
    // A whole number of bricks: the world's max faces are the top grid's too.
    voxel_model bricks = hollow_box(box3i{{-8, 0, 8}, {0, 16, 16}});
    rays = lattice_rays(bricks.bounds());
    this->expect_agrees_with_oracle("lattice, shell of whole bricks", bricks, rays);
    voxel_model noise = random_model(6, 0.4f, 3, {-3, -2, -4});
    rays = lattice_rays(noise.bounds());
    this->expect_agrees_with_oracle("lattice, noise at negative", noise, rays);
}

TYPED_TEST_P(agreement_suite, grazing_rays_agree_with_the_oracle) {
    voxel_model model = random_model(12, 0.25f, 5, {-6, -6, 2});
    auto rays = grazing_rays(model.bounds(), 20000, 6);
    auto c = this->expect_agrees_with_oracle("along planes and edges", model, rays);
    EXPECT_GT(c.same, c.rays / 2);
}

// Tiny and huge components (1/d near the float limits) and denormal ones (which every
// DDA treats as zero), origins on the grid's planes and on either zero.
TYPED_TEST_P(agreement_suite, extreme_directions_agree_with_the_reference) {
    box3i b{{-8, -8, -8}, {8, 8, 8}};
    voxel_model model = random_sparse(b, 800, 37);
    auto huge = extreme_rays(b, huge_and_tiny_components, 20000, 41);
    this->expect_agrees_with_reference("tiny and huge components", model, huge);
    auto denormal = extreme_rays(b, denormal_components, 20000, 43);
    this->expect_agrees_with_reference("denormal components", model, denormal);
}

// Origins up to 3e38 and components at the edges of the minimum-direction rule: the same
// hits as the reference, and every hit one a float can express (finite t, a solid voxel).
TYPED_TEST_P(agreement_suite, far_origins_and_tiny_components_agree_with_the_reference) {
    box3i b{{-8, -8, -8}, {8, 8, 8}};
    voxel_model model = random_sparse(b, 800, 53);
    auto rays = far_rays(b, 30000, 59);
    this->expect_agrees_with_reference("far origins, tiny components", model, rays);
    typename TestFixture::structure s(model);
    typename TestFixture::tracer_type t(s);
    std::size_t hits = 0;
    for (mode m : {mode::closest, mode::any}) {
        auto got = trace(t, rays, m);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            if (!got[i].is_hit()) continue;
            ++hits;
            ASSERT_TRUE(std::isfinite(got[i].t)) << "ray " << i << " hits at t = " << got[i].t;
            ASSERT_NE(model.get(got[i].voxel), 0) << "ray " << i << " hits an empty voxel";
        }
    }
    EXPECT_GT(hits, rays.size() / 50) << "too few hits to mean much";
}

// Rays entering the world on another axis's cell plane, over empty space that reaches the
// world's top: the walk may cross that plane a hair before it enters the world.
TYPED_TEST_P(agreement_suite, rays_entering_on_a_cell_plane_agree_with_the_reference) {
    // Under the top face, stripes 4 voxels wide along y: solid, empty, solid... so an empty
    // cuboid's side lies on the very plane a ray enters on, with solid just past it.
    voxel_model model = random_sparse(box3i{{0, 0, 0}, {96, 96, 20}}, 3000, 61);
    for (int z = 80; z < 94; ++z)  // the world's top cuts blocks, chunks and pages: their cuboids stick out
        for (int y = 0; y < 96; ++y)
            for (int x = 0; x < 96; ++x)
                if ((y & 4) == 0 && x % 7 != 3) model.set({x, y, z}, std::uint8_t(1 + (x + z) % 200));
    auto rays = entry_on_plane_rays(box3i{{0, 0, 0}, {96, 96, 94}}, 2000, 67);
    ASSERT_GT(rays.size(), 200u) << "too few rays with the rounding this test is about";
    this->expect_agrees_with_reference("entering on a cell plane", model, rays);
    std::printf("[%s] %zu rays enter on a plane they have already crossed\n", this->case_name().c_str(), rays.size());
}

// The same structure on cpu_scalar (one thread) gives the same hit records, t, voxel,
// face, material, steps and status, on every model and ray set, in both modes.
TYPED_TEST_P(agreement_suite, bit_identical_to_cpu_scalar) {
    std::uint64_t seed = 10;
    for (auto& [name, model] : backend_models()) {
        typename TestFixture::structure s(model);
        typename TestFixture::tracer_type t(s);
        box3i b = model.bounds();
        auto rays = mixed_rays(b, 10000, seed++);
        for (std::span<const float> extra : {std::span<const float>(huge_and_tiny_components),
                                             std::span<const float>(denormal_components)}) {
            auto more = extreme_rays(b, extra, 3000, seed++);
            rays.insert(rays.end(), more.begin(), more.end());
        }
        auto grazing = grazing_rays(b, 4000, seed++);
        rays.insert(rays.end(), grazing.begin(), grazing.end());
        auto far = far_rays(b, 3000, seed++);
        rays.insert(rays.end(), far.begin(), far.end());
        auto invalid = invalid_rays(glm::vec3(b.min) - 3.0f, glm::vec3(b.min + b.max) * 0.5f);
        rays.insert(rays.end(), invalid.begin(), invalid.end());
        std::size_t hits = this->expect_bit_identical(name, t, s, rays);
        if (name != "single_voxel") {
            EXPECT_GT(hits, rays.size() / 20) << name << ": too few hits to mean much";
        }
    }
    voxel_model shell = hollow_box(box3i{{0, 0, 0}, {6, 5, 4}});
    typename TestFixture::structure s(shell);
    typename TestFixture::tracer_type t(s);
    this->expect_bit_identical("lattice", t, s, lattice_rays(shell.bounds()));
}

// Batches of every awkward size: partial SIMD packets and work groups, one ray, none.
TYPED_TEST_P(agreement_suite, odd_batch_sizes_are_bit_identical) {
    voxel_model model = random_model(12, 0.1f, 4);
    typename TestFixture::structure s(model);
    typename TestFixture::tracer_type t(s);
    for (std::size_t n : {1u, 7u, 17u, 64u, 65u, 1023u, 1025u, 5003u}) {
        auto rays = random_rays(model.bounds(), n, n);
        rays.push_back(ray{{NAN, 0, 0}, 0, {1, 0, 0}, INFINITY});  // an invalid ray among valid ones
        this->expect_bit_identical("batch of " + std::to_string(rays.size()), t, s, rays);
    }
    std::vector<hit> none;
    t.closest_hit(std::span<const ray>{}, none);  // zero rays: nothing to do
    std::vector<ray> two(2);
    std::vector<hit> one(1);
    EXPECT_THROW(t.closest_hit(two, one), voxray::error);
}

// Models of the shared scenes, loaded once per process.
inline const std::vector<named_model>& shared_scenes() {
    static const std::vector<named_model> scenes = [] {
        std::vector<named_model> out;
        for (auto& file : data_files("vox", ".vox")) out.push_back({file.filename().string(), io::load_vox(file)});
        return out;
    }();
    return scenes;
}

TYPED_TEST_P(agreement_suite, builtin_scenes_agree_with_the_reference) {
    for (const char* spec : {"menger:81", "terrain:128"}) {
        auto model = scenes::make_builtin(spec);
        auto rays = check_rays(model.bounds(), model.up_axis, 40000, 17);
        auto c = this->expect_agrees_with_reference(spec, model, rays);
        EXPECT_LE(c.ties, c.rays / 100) << spec;
    }
}

TYPED_TEST_P(agreement_suite, shared_scenes_agree_with_the_reference) {
    VOXRAY_REQUIRE_DATA();
    auto& scenes = shared_scenes();
    EXPECT_GT(scenes.size(), 2u) << "no .vox files in the data folder";
    for (auto& [name, model] : scenes) {
        auto rays = check_rays(model.bounds(), model.up_axis, 8000, 18);
        auto c = this->expect_agrees_with_reference(name, model, rays);
        EXPECT_LE(c.ties, c.rays / 100) << name;
    }
}

REGISTER_TYPED_TEST_SUITE_P(agreement_suite, random_models_agree_with_the_oracle, lattice_rays_agree_with_the_oracle,
                            grazing_rays_agree_with_the_oracle, extreme_directions_agree_with_the_reference,
                            far_origins_and_tiny_components_agree_with_the_reference,
                            rays_entering_on_a_cell_plane_agree_with_the_reference,
                            bit_identical_to_cpu_scalar, odd_batch_sizes_are_bit_identical,
                            builtin_scenes_agree_with_the_reference, shared_scenes_agree_with_the_reference);

}  // namespace voxray::test
