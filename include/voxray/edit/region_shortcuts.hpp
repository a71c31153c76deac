// The named region edits every editable structure offers (fill_box, erase_sphere, ...),
// written once over the structure's own apply(region, op, value, threads): a structure
// derives from region_shortcuts<itself, its payload type>.
#pragma once
#include <glm/vec3.hpp>

#include "voxray/core/box.hpp"
#include "voxray/edit/edit_op.hpp"
#include "voxray/edit/regions.hpp"

namespace voxray {

template <class Structure, class Payload>
class region_shortcuts {
public:
    void fill_box(box3i b, Payload v, unsigned threads = 1) { self().apply(regions::box{b}, edit_op::fill, v, threads); }
    void erase_box(box3i b, unsigned threads = 1) { self().apply(regions::box{b}, edit_op::erase, Payload(0), threads); }
    void paint_box(box3i b, Payload v, unsigned threads = 1) { self().apply(regions::box{b}, edit_op::paint, v, threads); }
    void fill_sphere(glm::ivec3 c, int r, Payload v, unsigned threads = 1) {
        self().apply(regions::sphere{c, r}, edit_op::fill, v, threads);
    }
    void erase_sphere(glm::ivec3 c, int r, unsigned threads = 1) {
        self().apply(regions::sphere{c, r}, edit_op::erase, Payload(0), threads);
    }
    void paint_sphere(glm::ivec3 c, int r, Payload v, unsigned threads = 1) {
        self().apply(regions::sphere{c, r}, edit_op::paint, v, threads);
    }

private:
    Structure& self() { return static_cast<Structure&>(*this); }
};

}  // namespace voxray
