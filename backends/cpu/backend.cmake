# voxray::cpu — the portable kernels compiled as C++, multi-threaded, with SIMD lanes.
find_package(Threads REQUIRED)
add_library(voxray_cpu INTERFACE)
add_library(voxray::cpu ALIAS voxray_cpu)
set_target_properties(voxray_cpu PROPERTIES EXPORT_NAME cpu)
target_include_directories(voxray_cpu INTERFACE
    $<BUILD_INTERFACE:${CMAKE_CURRENT_LIST_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
target_link_libraries(voxray_cpu INTERFACE voxray::voxray Threads::Threads)
# SSE2-only builds run the SIMD lanes slower than scalar code: require x86-64-v3 (AVX2,
# FMA), or the build machine's own ISA. fp-contract=off keeps scalar and SIMD lanes
# bit-identical (no FMA fused in one and not the other).
if(VOXRAY_NATIVE)
    target_compile_options(voxray_cpu INTERFACE -march=native -ffp-contract=off)
else()
    target_compile_options(voxray_cpu INTERFACE -march=x86-64-v3 -ffp-contract=off)
endif()
install(DIRECTORY ${CMAKE_CURRENT_LIST_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
voxray_backend_added(cpu voxray_cpu)
