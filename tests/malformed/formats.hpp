// The input formats the malformed-input test covers: valid samples built here (small,
// so every mutant loads in microseconds), where each one's structure starts, and its
// loader. A new format is one more function returning an input_format and one more
// entry in all_formats() (NAADF's .vxna is one: vxna_format).
#pragma once
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unordered_set>

#include <unistd.h>

#include "mutations.hpp"
#include "vox_bytes.hpp"
#include "voxray/brickmap/brickmap.hpp"
#include "voxray/naadf/serialize.hpp"
#include "voxray/brickmap/serialize.hpp"
#include "voxray/io/mesh_loader.hpp"
#include "voxray/io/obj_reader.hpp"
#include "voxray/io/ply_reader.hpp"
#include "voxray/io/vox_reader.hpp"
#include "voxray/world/build/model_source.hpp"
#include "voxray/world/build/world_build.hpp"
#include "voxray/world/chunk_file.hpp"
#include "voxray/world/manifest.hpp"

namespace voxray::test::malformed {

inline bytes as_bytes(const std::string& s) { return bytes(s.begin(), s.end()); }

// A file under the temp folder, for loaders that only read paths; removed by the caller.
inline std::filesystem::path scratch_path(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("voxray_malformed_" + std::to_string(::getpid()) + "_" + name);
}
inline void write_file(const std::filesystem::path& p, const bytes& b) {
    std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}
inline bytes read_file(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return bytes(std::istreambuf_iterator<char>(in), {});
}

// A scratch file or folder, removed when this goes out of scope.
struct removed_at_exit {
    std::filesystem::path p;
    ~removed_at_exit() {
        std::error_code ignored;
        std::filesystem::remove_all(p, ignored);
    }
};

// Small models to save in a structure's file format: scattered colours, a full block,
// negative coordinates.
inline std::vector<voxel_model> sample_models() {
    std::vector<voxel_model> out(3);
    for (int i = 0; i < 60; ++i) out[0].set({i % 13, (i * 7) % 11, (i * 5) % 9}, std::uint8_t(1 + i % 9));
    for (int z = 0; z < 8; ++z)
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) out[1].set({x, y, z}, 3);
    out[2].set({-20, -3, 5}, 200), out[2].set({17, 40, -9}, 1);
    return out;
}

// A structure saved to a file and loaded back through a path: the samples are the
// files that save() writes for sample_models(). Boundaries: every 4-byte word of the
// first `header_bytes` (fields, counts, the start of the content).
template <class Structure, class Save, class Load>
input_format saved_structure_format(std::string name, Save save, Load load, std::size_t header_bytes = 128) {
    input_format f;
    f.name = name;
    for (auto& model : sample_models()) {
        auto p = scratch_path("sample." + name);
        save(Structure(model), p);
        f.samples.push_back(read_file(p));
        std::filesystem::remove(p);
    }
    f.load = [name, load](const bytes& b) {
        auto p = scratch_path("mutant." + name);
        write_file(p, b);
        removed_at_exit cleanup{p};
        load(p);
    };
    f.boundaries = [header_bytes](const bytes& b) {
        std::vector<std::size_t> out;
        for (std::size_t at = 0; at < header_bytes && at < b.size(); at += 4) out.push_back(at);
        return out;
    };
    return f;
}

inline input_format vxbm_format() {
    using map = brickmap<>;
    auto f = saved_structure_format<map>(
        "vxbm", [](const map& m, const std::filesystem::path& p) { save(m, p); },
        [](const std::filesystem::path& p) { (void)load_brickmap<map>(p); });
    // Most mutants would stop at the checksum; resealed, they reach the content checks.
    f.reseal = [](bytes& b) {
        if (b.size() < brickmap_file_header_bytes) return;
        std::uint64_t words;
        std::memcpy(&words, b.data() + 16, 8);
        if (words > (b.size() - brickmap_file_header_bytes) / 4) return;
        fnv64 sum;
        sum.bytes(b.data(), 40);
        std::vector<std::uint32_t> w(words);
        if (words) std::memcpy(w.data(), b.data() + 48, words * 4);
        sum.words(w.data(), words);
        sum.bytes(b.data() + 48 + 4 * words, b.size() - 48 - 4 * words);
        std::memcpy(b.data() + 40, &sum.h, 8);
    };
    return f;
}

inline input_format vxna_format() {
    auto f = saved_structure_format<naadf>(
        "vxna", [](const naadf& s, const std::filesystem::path& p) { save(s, p); },
        [](const std::filesystem::path& p) { (void)load_naadf(p); });
    f.reseal = [](bytes& b) {  // as vxbm's: past the checksum to the content checks
        if (b.size() < naadf_file_header_bytes) return;
        std::uint64_t words;
        std::memcpy(&words, b.data() + 8, 8);
        if (words > (b.size() - naadf_file_header_bytes) / 4) return;
        fnv64 sum;
        sum.bytes(b.data(), 24);
        std::vector<std::uint32_t> w(words);
        if (words) std::memcpy(w.data(), b.data() + naadf_file_header_bytes, words * 4);
        sum.words(w.data(), words);
        sum.bytes(b.data() + naadf_file_header_bytes + 4 * words, b.size() - naadf_file_header_bytes - 4 * words);
        std::memcpy(b.data() + 24, &sum.h, 8);
    };
    return f;
}

// A small world built once into a scratch folder (removed at exit): its manifest and
// chunk files are the world formats' samples.
inline const std::filesystem::path& sample_world() {
    struct built {
        std::filesystem::path dir = scratch_path("world");
        built() {
            world_build_options o;
            o.chunk_bits = 4, o.threads = 1, o.replace = true;
            build_world(model_source(sample_models()[0]), dir, o);
        }
        ~built() {
            std::error_code ignored;
            std::filesystem::remove_all(dir, ignored);
        }
    };
    static built world;
    return world.dir;
}


// One chunk file (.vxck) read back through its path, as the streamed world reads them.
inline input_format vxck_format() {
    input_format f;
    f.name = "vxck";
    auto manifest = read_manifest(sample_world());
    for (auto& c : manifest.chunks)
        if (f.samples.size() < 3) f.samples.push_back(read_file(chunk_file_path(sample_world(), c.key)));
    f.load = [](const bytes& b) {
        auto p = scratch_path("mutant.vxck");
        write_file(p, b);
        removed_at_exit cleanup{p};
        (void)read_chunk_file(p);
    };
    f.boundaries = [](const bytes& b) {
        std::vector<std::size_t> out;
        for (std::size_t at = 0; at < chunk_file_header_bytes + 4 * VX_SV_HEADER_WORDS && at < b.size(); at += 4)
            out.push_back(at);
        return out;
    };
    f.reseal = [](bytes& b) {  // the header's bytes before the sum, then the DAG word by word
        if (b.size() < chunk_file_header_bytes || (b.size() - chunk_file_header_bytes) % 4) return;
        blob_words dag((b.size() - chunk_file_header_bytes) / 4);
        if (!dag.empty()) std::memcpy(dag.data(), b.data() + chunk_file_header_bytes, dag.size() * 4);
        std::uint64_t sum = chunk_file_detail::checksum(b.data(), dag);
        std::memcpy(b.data() + chunk_file_offset::checksum, &sum, 8);
    };
    return f;
}

// The world's manifest (world.vxwm), read from a scratch folder.
inline input_format vxwm_format() {
    input_format f;
    f.name = "vxwm";
    f.samples.push_back(read_file(manifest_path(sample_world())));
    f.load = [](const bytes& b) {
        auto dir = scratch_path("mutant_world");
        std::filesystem::create_directories(dir);
        write_file(manifest_path(dir), b);
        removed_at_exit cleanup{dir};
        (void)read_manifest(dir);
    };
    f.boundaries = [](const bytes& b) {
        std::vector<std::size_t> out;
        for (std::size_t at = 0; at < b.size() && at < manifest_header_bytes + 4 * manifest_chunk_bytes; at += 4) out.push_back(at);
        return out;
    };
    f.reseal = [](bytes& b) {  // bytes [0, 88), then the chunk table
        if (b.size() < manifest_header_bytes) return;
        fnv64 sum;
        sum.bytes(b.data(), 88);
        sum.bytes(b.data() + manifest_header_bytes, b.size() - manifest_header_bytes);
        std::memcpy(b.data() + 88, &sum.h, 8);
    };
    return f;
}

inline input_format vox_format() {
    using namespace vox_bytes;
    input_format f;
    f.name = "vox";
    // A scene graph (transform, group, two shapes, rotation, a layer), palette, material.
    bytes rgba;
    for (int i = 0; i < 256; ++i) put_u32(rgba, 0xff000000u | std::uint32_t(i * 0x010203));
    bytes matl;
    put_u32(matl, 3), put_dict(matl, {{"_type", "_metal"}, {"_rough", "0.2"}, {"_ior", "0.3"}});
    bytes layr;
    put_u32(layr, 0), put_dict(layr, {{"_hidden", "0"}}), put_u32(layr, 0xffffffffu);
    f.samples.push_back(vox({size_chunk(3, 2, 2), xyzi_chunk({{0, 0, 0, 1}, {1, 0, 1, 2}, {2, 1, 0, 3}}),
                             size_chunk(2, 2, 1), xyzi_chunk({{0, 0, 0, 4}, {1, 1, 0, 5}}),
                             ntrn(0, 1, {}), ngrp(1, {2, 4}), ntrn(2, 3, {{"_t", "4 -2 1"}, {"_r", "20"}}),
                             nshp(3, {{0, {}}}), ntrn(4, 5, {{"_t", "-3 0 0"}}, {{"_name", "b"}}, 0),
                             nshp(5, {{1, {{"_f", "0"}}}}), chunk("LAYR", layr), chunk("RGBA", rgba),
                             chunk("MATL", matl)}));
    // PACK-era: two models, no scene graph, no palette.
    bytes pack;
    put_u32(pack, 2);
    f.samples.push_back(vox({chunk("PACK", pack), size_chunk(2, 1, 1), xyzi_chunk({{0, 0, 0, 7}, {1, 0, 0, 8}}),
                             size_chunk(1, 1, 3), xyzi_chunk({{0, 0, 2, 9}})}));
    // Version 200, animation frames on a transform and a shape.
    f.samples.push_back(vox({size_chunk(2, 2, 2), xyzi_chunk({{1, 1, 1, 1}}), size_chunk(1, 1, 1),
                             xyzi_chunk({{0, 0, 0, 2}}), ntrn(0, 1, {{"_t", "0 0 0"}}),
                             nshp(1, {{0, {{"_f", "0"}}}, {1, {{"_f", "5"}}}})},
                            200));
    f.load = [](const bytes& b) { (void)io::read_vox_scene(b, "mutant.vox"); };
    // Chunk starts and their size fields, walked without the reader.
    f.boundaries = [](const bytes& b) {
        std::vector<std::size_t> out{4, 8};
        for (std::size_t at = 20; at + 12 <= b.size();) {
            for (std::size_t k : {0u, 4u, 8u, 12u, 16u}) out.push_back(at + k);
            std::uint32_t n, m;
            std::memcpy(&n, &b[at + 4], 4), std::memcpy(&m, &b[at + 8], 4);
            at += 12 + std::size_t(n) + m;
        }
        return out;
    };
    return f;
}

// Meshes load through the reader and a small voxelization (the voxelizer sees the
// strange coordinates too), once per distinct mesh: many mutants read as the same mesh,
// and a voxelization costs a 2 MiB tile buffer (slow to map under ASan).
inline void load_and_voxelize(const io::triangle_mesh& mesh) {
    if (!mesh.triangle_count()) return;
    static std::unordered_set<std::uint64_t> seen;
    std::uint64_t h = 0xcbf29ce484222325ull;
    auto mix = [&](const void* p, std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<const std::uint8_t*>(p)[i]) * 0x100000001b3ull;
    };
    mix(mesh.positions.data(), mesh.positions.size() * sizeof(mesh.positions[0]));
    mix(mesh.triangles.data(), mesh.triangles.size() * sizeof(mesh.triangles[0]));
    mix(mesh.groups.data(), mesh.groups.size() * sizeof(std::uint32_t));
    mix(mesh.surface.triangle_materials.data(), mesh.surface.triangle_materials.size() * sizeof(std::uint32_t));
    mix(mesh.surface.corner_uvs.data(), mesh.surface.corner_uvs.size() * sizeof(glm::vec2));
    for (const auto& m : mesh.surface.materials) {
        mix(&m.base_colour, sizeof m.base_colour);
        mix(&m.alpha, sizeof m.alpha);
    }
    if (seen.insert(h).second) (void)io::voxelize(mesh, {24, 1});
}

inline input_format obj_format() {
    input_format f;
    f.name = "obj";
    f.text = true;
    f.samples.push_back(as_bytes("# a cube corner and a fan\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0\n"
                                 "v 0 1 0\nv 0.5 0.5 1.25\nvt 0 0\nvt 1 0\nvn 0 0 1\ng top\nusemtl red\ns 1\n"
                                 "f 1/1/1 2/2/1 3//1\nf 1 3 4\ng side\nf -5 -4 -1\nf 2 3 5 4\nl 1 2\n"));
    f.samples.push_back(as_bytes("v -1e3 2.5e2 3\r\nv 4 5 6\r\nv 7 8 -9.5\r\nf 1 2 3\r\n"));
    f.load = [](const bytes& b) {
        load_and_voxelize(io::parse_obj(std::string_view(reinterpret_cast<const char*>(b.data()), b.size()), "mutant.obj"));
    };
    f.boundaries = [](const bytes& b) { return line_starts(b); };
    return f;
}

// OBJ with materials (obj_options::materials): the mutant OBJ reads a fixed MTL; then the
// MTL mutated under a fixed OBJ. Textures are named, not decoded (the core has no image
// library), so the samples use colours and texture coordinates only.
inline const char* coloured_obj_sample =
    "mtllib c.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0.5\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0.5 1\n"
    "usemtl red\nf 1/1 2/2 3/3\nusemtl glass\nf 1/1 3/3 4/4\nf -1/-1 -2/-2 -3/-3\n";
inline const char* coloured_mtl_sample =
    "# two materials\nnewmtl red\nKa 0 0 0\nKd 0.8 0.1 0.05\nd 1\nnewmtl glass\nKd 0.5 0.6 0.9\nTr 0.7\nillum 2\n";

inline void load_coloured_obj(const std::string& obj, const std::string& mtl) {
    auto dir = scratch_path("coloured_obj");
    std::filesystem::create_directories(dir);
    removed_at_exit cleanup{dir};
    write_file(dir / "c.mtl", as_bytes(mtl));
    load_and_voxelize(io::parse_obj(obj, "mutant.obj", {.materials = true}, dir));
}

inline input_format coloured_obj_format() {
    input_format f;
    f.name = "obj_mtl";
    f.text = true;
    f.samples.push_back(as_bytes(coloured_obj_sample));
    f.load = [](const bytes& b) { load_coloured_obj(std::string(b.begin(), b.end()), coloured_mtl_sample); };
    f.boundaries = [](const bytes& b) { return line_starts(b); };
    return f;
}

inline input_format mtl_format() {
    input_format f;
    f.name = "mtl";
    f.text = true;
    f.samples.push_back(as_bytes(coloured_mtl_sample));
    f.load = [](const bytes& b) { load_coloured_obj(coloured_obj_sample, std::string(b.begin(), b.end())); };
    f.boundaries = [](const bytes& b) { return line_starts(b); };
    return f;
}

inline input_format ply_format() {
    input_format f;
    f.name = "ply";
    f.text = true;  // the header, and the body of the ASCII sample
    f.samples.push_back(as_bytes("ply\nformat ascii 1.0\ncomment hi\nelement vertex 4\nproperty float x\n"
                                 "property float y\nproperty float z\nproperty uchar red\nelement face 2\n"
                                 "property list uchar int vertex_indices\nend_header\n0 0 0 1\n1 0 0 2\n0 1 0 3\n"
                                 "0 0 1 4\n3 0 1 2\n4 0 1 3 2\n"));
    // Binary: double coordinates, an extra property, an int-counted list, a second element.
    std::string head = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\n"
                       "property double y\nproperty double z\nproperty short s\nelement face 1\n"
                       "property list int uint vertex_indices\nelement edge 1\nproperty int a\nend_header\n";
    bytes bin = as_bytes(head);
    auto put = [&](const void* p, std::size_t n) {
        auto* c = static_cast<const std::uint8_t*>(p);
        bin.insert(bin.end(), c, c + n);
    };
    const double coords[3][3] = {{0, 0, 0}, {2, 0, 0.5}, {0, 3, 1}};
    for (auto& c : coords) {
        put(c, 24);
        std::int16_t s = 7;
        put(&s, 2);
    }
    std::int32_t count = 3;
    put(&count, 4);
    for (std::uint32_t i : {0u, 1u, 2u}) put(&i, 4);
    put(&count, 4);
    f.samples.push_back(bin);
    f.load = [](const bytes& b) {
        load_and_voxelize(io::parse_ply(std::string_view(reinterpret_cast<const char*>(b.data()), b.size()), "mutant.ply"));
    };
    f.boundaries = [](const bytes& b) {
        auto out = line_starts(b, 400);  // header lines (and ASCII body lines)
        std::string_view s(reinterpret_cast<const char*>(b.data()), b.size());
        if (auto end = s.find("end_header\n"); end != s.npos && s.find("binary") != s.npos)
            for (std::size_t at = end + 11; at < b.size(); at += 4) out.push_back(at);  // binary fields
        return out;
    };
    return f;
}

// Every format the malformed-input test runs. Add a format here (one line).
inline std::vector<input_format> all_formats() {
    return {vox_format(),  obj_format(),  coloured_obj_format(), mtl_format(), ply_format(),
            vxbm_format(), vxna_format(), vxck_format(),         vxwm_format()};
}

}  // namespace voxray::test::malformed
