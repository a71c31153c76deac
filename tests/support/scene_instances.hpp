// Instances for backend tests that trace a scene without being about entities (interop):
// `count` copies of a small hollow box at spread-out places inside box b, turned by
// arbitrary rotations, so that rays over b meet the world and instances alike.
#pragma once
#include <cmath>

#include "random_models.hpp"
#include "voxray/entities/scene.hpp"

namespace voxray::test {

template <class World>
void add_test_instances(scene<World>& s, const box3i& b, int count) {
    model_id box = s.add_model(hollow_box(6));
    rng g(31);
    for (int i = 0; i < count; ++i) {
        pose p;
        for (int a = 0; a < 3; ++a) p.position[a] = float(b.min[a]) + g.uniform() * float(b.extent()[a]);
        p.rotation = {g.uniform(-1, 1), g.uniform(-1, 1), g.uniform(-1, 1), g.uniform(-1, 1) + 0.01f};
        s.add(box, p);
    }
}

}  // namespace voxray::test
