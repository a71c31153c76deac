# voxray::nanovdb — NanoVDB baseline: the same voxels in a NanoVDB grid, traced on the CPU
# with an exact hierarchical DDA over NanoVDB's tree (see hdda_scene.hpp). Header-only;
# NanoVDB ships no CMake config, so its header is found by path (Debian: libnanovdb-dev).
find_path(NANOVDB_INCLUDE_DIR nanovdb/NanoVDB.h)
find_package(Threads)
if(NANOVDB_INCLUDE_DIR AND Threads_FOUND)
    add_library(voxray_nanovdb INTERFACE)
    add_library(voxray::nanovdb ALIAS voxray_nanovdb)
    set_target_properties(voxray_nanovdb PROPERTIES EXPORT_NAME nanovdb)
    target_include_directories(voxray_nanovdb ${VOXRAY_SYSTEM} INTERFACE
        $<BUILD_INTERFACE:${CMAKE_CURRENT_LIST_DIR}/include>
        $<BUILD_INTERFACE:${NANOVDB_INCLUDE_DIR}>
        $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    target_link_libraries(voxray_nanovdb INTERFACE voxray::voxray Threads::Threads)
    if(VOXRAY_INSTALL)
        install(DIRECTORY ${CMAKE_CURRENT_LIST_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    endif()
    voxray_backend_added(nanovdb voxray_nanovdb)
else()
    voxray_backend_missing(nanovdb "nanovdb/NanoVDB.h not found (Debian: libnanovdb-dev)")
endif()
