// Run-time choice of structure x backend for the tool. The library's tracer is a
// compile-time policy; the tool, which takes names on the command line, reaches every
// combination through this small virtual interface (outside the hot loop). The
// combinations themselves are compiled once, in registry.cpp, which walks the type list
// of registered structures (voxray/generated/structures.hpp), of backends and of
// baselines (backends.hpp); every other file of the tool sees only this header.
#pragma once
#include <cmath>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/edit/region_edit.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::tool {

class traceable {
public:
    virtual ~traceable() = default;
    virtual void closest_hit(std::span<const ray> rays, std::span<hit> hits) = 0;
    virtual void any_hit(std::span<const ray> rays, std::span<hit> hits) = 0;
    virtual std::string device() const { return "cpu"; }
    // Brings the backend up to date after edits: an editable structure was edited in place
    // (its slot holds the dirty ranges of the last edits); the others are rebuilt from the
    // edited model and sent whole.
    virtual void after_edits(const voxel_model& edited) = 0;
    virtual std::uint64_t bytes_uploaded_last_update() const { return 0; }
    // CPU threads tracing (0: a device does) and rays per lane group (1: scalar).
    virtual unsigned cpu_threads() const { return 0; }
    virtual unsigned simd_width() const { return 1; }
    // Device seconds of the last trace's kernels alone, without copies of rays and hits
    // (GPU backends); NaN where the backend does not measure them.
    virtual double kernel_seconds_last_trace() const { return NAN; }
    // Work-items per group of a GPU backend's trace kernels (0: a CPU backend).
    virtual unsigned work_group_size() const { return 0; }
};

// One built structure or baseline, shared by every backend that traces it.
class slot {
public:
    virtual ~slot() = default;
    virtual std::string name() const = 0;
    virtual std::size_t bytes() const = 0;
    virtual double build_seconds() const = 0;
    virtual bool editable() const { return false; }
    // A known limitation of a baseline (empty: none): its wrong answers on the rays it
    // names are labelled, not counted as mismatches.
    virtual std::string limitation() const { return ""; }
    virtual bool runs_on(const std::string& backend) const = 0;
    virtual std::unique_ptr<traceable> trace_on(const std::string& backend) = 0;
    // Edits the structure in place (editable ones only) and keeps the dirty ranges for
    // its traceables' after_edits().
    virtual void apply_edits(std::span<const region_edit>, unsigned /* threads */ = 1) {
        fail("structure ", name(), " is not editable");
    }
    // How long the last apply_edits spent regrowing distance fields (NAADF's refine).
    virtual double last_refine_seconds() const { return 0; }
    // Hits carry RGBA8 colours instead of palette indices (the DAG's colour blocks): how
    // far, per channel in [0, 1], a colour may be from the voxel's palette colour.
    virtual std::optional<double> colour_tolerance() const { return std::nullopt; }
    // Structure-specific figures (name, value) beside size and build time (the DAG's
    // geometry and attribute bytes, merging ratio, colour error).
    virtual std::vector<std::pair<const char*, double>> figures() const { return {}; }
};

// Every structure and baseline name the tool knows.
std::string structure_names(const char* separator = ", ");

// The structures and baselines that answer every ray of the contract (no known limitation):
// what `check` compares by default.
std::string exact_structure_names();

// The backends this build traces on, by name.
std::vector<std::string> backend_names();

// Builds structure or baseline `name` from the model.
std::shared_ptr<slot> build_structure(const std::string& name, const voxel_model& model);

}  // namespace voxray::tool
