// world-build over MPI ranks (world_mpi.hpp). VOXRAY_WITH_MPI: the tool links voxray::mpi.
#include "world_mpi.hpp"

#include <cstdlib>

#include "voxray/core/error.hpp"
#if VOXRAY_WITH_MPI
#include "voxray/mpi/world_build.hpp"
#endif

namespace voxray::tool {

namespace {

// The variable an MPI launcher sets for every process it starts (Open MPI, PMI as MPICH
// and Slurm's srun use it, PMIx), and its value; empty when none is set.
std::string launcher_variable() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
        if (const char* v = std::getenv(name)) return std::string(name) + "=" + v;
    return "";
}

}  // namespace

#if VOXRAY_WITH_MPI

std::unique_ptr<mpi_ranks> mpi_ranks::if_launched() {
    if (launcher_variable().empty()) return nullptr;
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);  // build threads never call MPI
    std::unique_ptr<mpi_ranks> r(new mpi_ranks);
    MPI_Comm_rank(MPI_COMM_WORLD, &r->rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &r->size_);
    return r;
}

mpi_ranks::~mpi_ranks() { MPI_Finalize(); }

bool mpi_ranks::failed_on_every_rank(const std::exception& e) { return dynamic_cast<const mpi_ranks_failed*>(&e) != nullptr; }

namespace {
mpi_schedule schedule_of(const std::string& s) {
    if (s == "dynamic") return mpi_schedule::dynamic;
    if (s == "static") return mpi_schedule::static_split;
    fail("--mpi-schedule '", s, "': expected dynamic or static");
}
}  // namespace

world_build_report mpi_ranks::build(const model_source& s, const std::filesystem::path& dir, const world_build_options& o,
                                    const std::string& schedule) const {
    return build_world_mpi(s, dir, o, MPI_COMM_WORLD, schedule_of(schedule));
}
world_build_report mpi_ranks::build(const mesh_source& s, const std::filesystem::path& dir, const world_build_options& o,
                                    const std::string& schedule) const {
    return build_world_mpi(s, dir, o, MPI_COMM_WORLD, schedule_of(schedule));
}

#else

std::unique_ptr<mpi_ranks> mpi_ranks::if_launched() {
    if (auto v = launcher_variable(); !v.empty())
        fail("an MPI launcher started this voxray (", v, "), but it was built without MPI: install Open MPI "
             "(Debian: libopenmpi-dev openmpi-bin) and build it again, or use --shard K/N");
    return nullptr;
}

mpi_ranks::~mpi_ranks() = default;

bool mpi_ranks::failed_on_every_rank(const std::exception&) { return false; }

world_build_report mpi_ranks::build(const model_source&, const std::filesystem::path&, const world_build_options&,
                                    const std::string&) const {
    fail("this voxray was built without MPI");
}
world_build_report mpi_ranks::build(const mesh_source&, const std::filesystem::path&, const world_build_options&,
                                    const std::string&) const {
    fail("this voxray was built without MPI");
}

#endif

}  // namespace voxray::tool
