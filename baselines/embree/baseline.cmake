# voxray::embree — Embree 3 baselines (exposed-face quads, per-voxel boxes) and
# Embree-based helpers such as solid fill by ray parity.
find_package(embree 3 CONFIG QUIET)
if(embree_FOUND)
    add_library(voxray_embree INTERFACE)
    add_library(voxray::embree ALIAS voxray_embree)
    set_target_properties(voxray_embree PROPERTIES EXPORT_NAME embree)
    target_include_directories(voxray_embree ${VOXRAY_SYSTEM} INTERFACE
        $<BUILD_INTERFACE:${CMAKE_CURRENT_LIST_DIR}/include>
        $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    target_link_libraries(voxray_embree INTERFACE voxray::voxray embree)
    if(VOXRAY_INSTALL)
        install(DIRECTORY ${CMAKE_CURRENT_LIST_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    endif()
    voxray_backend_added(embree voxray_embree)
else()
    voxray_backend_missing(embree "find_package(embree 3) failed (Debian: libembree-dev)")
endif()
