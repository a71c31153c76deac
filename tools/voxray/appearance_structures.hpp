// The structures whose first-hit kernels the appearance benchmarks' compositing walk
// re-enters (appearance-bench, appearance-walk-bench), by name, and the CPU backends the
// walk runs on.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "voxray/brickmap/brickmap.hpp"
#include "voxray/cpu/cpu_backend.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/naadf/naadf.hpp"

namespace voxray::tool {

inline const std::vector<std::string> walk_structures = {"dense", "brickmap", "naadf"};
// voxray::cpu (SIMD lanes) and voxray::cpu_scalar, by their names.
inline const std::vector<std::string> walk_backends = {cpu::name, cpu_scalar::name};

// The structure the walk traces: its name and its words.
struct walk_structure {
    std::string name;
    std::vector<std::uint32_t> blob;
};

inline walk_structure build_walk_structure(const std::string& name, const voxel_model& model) {
    auto words = [](std::span<const std::uint32_t> b) { return std::vector<std::uint32_t>(b.begin(), b.end()); };
    if (name == "brickmap") return {name, words(brickmap<>(model).blob())};
    if (name == "naadf") return {name, words(naadf(model).blob())};
    return {name, words(dense_grid(model).blob())};
}

// Calls f.template operator()<Kernel>() with the kernel of structure `name` (walk_structures).
template <class F>
decltype(auto) with_walk_kernel(const std::string& name, F&& f) {
    if (name == "naadf") return f.template operator()<kernels::naadf_kernel>();
    if (name == "brickmap") return f.template operator()<kernels::brickmap_kernel>();
    return f.template operator()<kernels::dense_grid_kernel>();
}

// Calls f.template operator()<Backend>() with the CPU backend named `name` (walk_backends).
template <class F>
decltype(auto) with_walk_backend(const std::string& name, F&& f) {
    if (name == cpu_scalar::name) return f.template operator()<cpu_scalar>();
    return f.template operator()<cpu>();
}

}  // namespace voxray::tool
