# voxray::mpi — not a tracer backend: the optional component for world builds over MPI
# ranks (voxray/mpi/world_build.hpp, in its own include folder: the core's headers need
# no MPI). Header-only; it carries MPI's flags and
# libraries (Debian: libopenmpi-dev openmpi-bin). Without it the library and the tool
# build, and a world is built by one process or by --shard K/N jobs.
find_package(MPI COMPONENTS CXX QUIET)
if(MPI_CXX_FOUND)
    add_library(voxray_mpi INTERFACE)
    add_library(voxray::mpi ALIAS voxray_mpi)
    set_target_properties(voxray_mpi PROPERTIES EXPORT_NAME mpi)
    target_include_directories(voxray_mpi ${VOXRAY_SYSTEM} INTERFACE
        $<BUILD_INTERFACE:${CMAKE_CURRENT_LIST_DIR}/include>
        $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    target_link_libraries(voxray_mpi INTERFACE voxray::voxray MPI::MPI_CXX)
    if(VOXRAY_INSTALL)
        install(DIRECTORY ${CMAKE_CURRENT_LIST_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    endif()
    voxray_backend_added(mpi voxray_mpi)
else()
    voxray_backend_missing(mpi "find_package(MPI COMPONENTS CXX) failed (Debian: libopenmpi-dev openmpi-bin)")
endif()
