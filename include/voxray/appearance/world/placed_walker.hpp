// Several appearance walkers placed side by side in one space, walked as one: the chunks of a
// world's LOD cut (world coordinates), or the 8 children a coarser chunk is re-sampled from
// (appearance/world/chunk_tables.hpp). Each piece is a walker of its own structure and table
// over the cube [0, edge)^3 of its own voxels, placed at `origin` with voxels `scale` wide.
//
// A ray visits the pieces its line crosses, nearest entry first, and the walk goes on from
// piece to piece (appearance/walk.inc, whose state each piece's walk hands to the next), so
// a ray blends its voxels exactly as through one structure: a surface that crosses a face
// between pieces of one voxel size stays one run of touching voxels. Pieces must not overlap
// (a world's cut does not). In a piece the ray is the same line in the piece's own voxels: origin
// (o - origin) / scale, the same unit direction, t / scale; its walk cannot leave the piece's
// cube, since the piece's structure holds nothing outside it.
//
//   voxray::appearance::placed_walker<voxray::appearance_walker<K>> w;
//   w.add({origin, scale, edge}, std::make_shared<const appearance_walker<K>>(blob, table, 1));
//   appearance_pixel p = w.walk_one(ray, light);
// A Walker offers kind(), and a walk that goes on from a state: state, start(), walk_on
// (cpu/appearance_walk.hpp).
#pragma once
#include <algorithm>
#include <bit>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/common.hpp>

#include "voxray/appearance/pixel.hpp"
#include "voxray/appearance/walk_inputs.hpp"
#include "voxray/core/error.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/model/build_threads.hpp"

namespace voxray::appearance {

// Where a piece sits: its cube [0, edge)^3 of its own voxels covers
// origin + [0, edge * scale)^3 of the space the rays are in.
struct piece_placement {
    glm::ivec3 origin{0};
    int scale = 1;
    int edge = 1;
};

template <class Walker>
class placed_walker {
public:
    void add(const piece_placement& p, std::shared_ptr<const Walker> walker) {
        if (!walker) fail("appearance placed walk: a piece without a walker");
        if (p.scale < 1 || p.edge < 1) fail("appearance placed walk: a piece of scale ", p.scale, " and edge ", p.edge);
        pieces_.push_back({p, std::move(walker)});
    }

    std::size_t size() const { return pieces_.size(); }
    // The pieces' record kind (VX_APP_KIND_*): six directions where any piece has those
    // (colours lit when made, which a coarser level cannot be re-sampled from), else the
    // first piece's (pieces may hold other kinds: a cut's LODs may); averages when empty.
    std::uint32_t kind() const {
        for (const piece& p : pieces_)
            if (p.walker->kind() == VX_APP_KIND_SIX) return VX_APP_KIND_SIX;
        return pieces_.empty() ? std::uint32_t(VX_APP_KIND_AVERAGES) : pieces_.front().walker->kind();
    }

    // One ray on the calling thread (safe from many threads at once). Its direction must be
    // a unit vector. t and the first voxel are in the rays' space: (x, y, z) is the min
    // corner of a voxel `scale` wide.
    appearance_pixel walk_one(const ray& r, const appearance_light& light) const {
        struct crossing {
            float enter, leave;
            std::size_t piece;
        };
        std::vector<crossing> crossings;
        for (std::size_t i = 0; i < pieces_.size(); ++i) {
            const piece_placement& p = pieces_[i].where;
            glm::vec3 lo(p.origin), hi = lo + float(p.edge) * float(p.scale);
            float enter = r.tmin, leave = r.tmax;
            for (int a = 0; a < 3; ++a) {
                float inv = 1.0f / r.direction[a];  // +-inf on an axis the ray runs along: the slab test still holds
                float t0 = (lo[a] - r.origin[a]) * inv, t1 = (hi[a] - r.origin[a]) * inv;
                if (std::isnan(t0) || std::isnan(t1)) {  // the ray lies on a face's plane
                    if (r.origin[a] < lo[a] || r.origin[a] > hi[a]) enter = leave + 1.0f;
                    continue;
                }
                enter = std::max(enter, std::min(t0, t1)), leave = std::min(leave, std::max(t0, t1));
            }
            if (enter < leave) crossings.push_back({enter, leave, i});
        }
        std::sort(crossings.begin(), crossings.end(), [](const crossing& a, const crossing& b) {
            return a.enter != b.enter ? a.enter < b.enter : a.piece < b.piece;
        });
        typename Walker::state s = Walker::start();
        const piece_placement* last = nullptr;  // the piece whose voxels s's last voxel is in
        for (const crossing& c : crossings) {
            if (s.w.transmittance < light.cutoff || s.w.visits >= light.max_visits) break;
            const piece_placement& where = pieces_[c.piece].where;
            if (last) last_voxel_into(s, *last, where);
            const bool had_hit = s.w.status == VX_STATUS_HIT;
            const float scale = float(where.scale);
            ray local;
            local.origin = (r.origin - glm::vec3(where.origin)) / scale;
            local.direction = r.direction;
            local.tmin = c.enter / scale, local.tmax = c.leave / scale;
            pieces_[c.piece].walker->walk_on(s, local, light);
            if (!had_hit && s.w.status == VX_STATUS_HIT) {  // the first voxel, in the rays' space
                s.w.t *= scale;
                glm::ivec3 voxel = where.origin + glm::ivec3(s.w.x, s.w.y, s.w.z) * where.scale;
                s.w.x = voxel.x, s.w.y = voxel.y, s.w.z = voxel.z;
            }
            if (s.w.visits > 0) last = &where;
        }
        return std::bit_cast<appearance_pixel>(s.w);
    }

    // Many rays on `threads` threads (0: all), in their order.
    std::vector<appearance_pixel> walk(std::span<const ray> rays, const appearance_light& light,
                                       unsigned threads = 0) const {
        std::vector<appearance_pixel> out(rays.size());
        constexpr std::size_t batch = 256;
        std::atomic<std::size_t> next{0};
        run_build_threads(resolve_build_threads(threads, (rays.size() + batch - 1) / batch), [&](unsigned) {
            for (std::size_t first; (first = next.fetch_add(batch)) < rays.size();)
                for (std::size_t i = first; i < std::min(rays.size(), first + batch); ++i)
                    out[i] = walk_one(rays[i], light);
        });
        return out;
    }

private:
    struct piece {
        piece_placement where;
        std::shared_ptr<const Walker> walker;
    };

    // The last voxel blended (in piece `from`'s voxels) in piece `to`'s voxels, so that a run
    // of touching voxels goes on across their common face. Pieces of other voxel sizes never
    // touch voxel to voxel: there the run ends.
    static void last_voxel_into(typename Walker::state& s, const piece_placement& from, const piece_placement& to) {
        glm::ivec3 p = from.origin + glm::ivec3(s.px, s.py, s.pz) * from.scale - to.origin;
        if (from.scale != to.scale || p % to.scale != glm::ivec3(0))
            p = glm::ivec3(-2 * to.scale);  // apart from every voxel of `to`
        p /= to.scale;
        s.px = p.x, s.py = p.y, s.pz = p.z;
    }

    std::vector<piece> pieces_;
};

}  // namespace voxray::appearance
