// world-build over MPI ranks: when this voxray was built with voxray::mpi and mpirun (or
// another MPI launcher) started it, every rank runs world-build and the ranks share the
// work (voxray/mpi/world_build.hpp). Started so without MPI support, it says so.
#pragma once
#include <filesystem>
#include <memory>
#include <string>

#include "voxray/world/build/mesh_source.hpp"
#include "voxray/world/build/model_source.hpp"
#include "voxray/world/build/world_build.hpp"

namespace voxray::tool {

class mpi_ranks {
public:
    // The ranks when an MPI launcher started this process (MPI initialized), else nullptr.
    static std::unique_ptr<mpi_ranks> if_launched();
    ~mpi_ranks();  // MPI_Finalize

    int rank() const { return rank_; }
    int size() const { return size_; }
    // Whether e is a failure every rank threw alike (then rank 0 alone reports it).
    static bool failed_on_every_rank(const std::exception& e);
    // schedule: "dynamic" or "static" (--mpi-schedule).
    world_build_report build(const model_source& s, const std::filesystem::path& dir, const world_build_options& o,
                             const std::string& schedule) const;
    world_build_report build(const mesh_source& s, const std::filesystem::path& dir, const world_build_options& o,
                             const std::string& schedule) const;

private:
    mpi_ranks() = default;
    int rank_ = 0, size_ = 1;
};

}  // namespace voxray::tool
