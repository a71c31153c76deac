# voxray::cpu — the portable kernels compiled as C++, multi-threaded, with SIMD lanes.
find_package(Threads REQUIRED)
add_library(voxray_cpu INTERFACE)
add_library(voxray::cpu ALIAS voxray_cpu)
set_target_properties(voxray_cpu PROPERTIES EXPORT_NAME cpu)
target_include_directories(voxray_cpu ${VOXRAY_SYSTEM} INTERFACE
    $<BUILD_INTERFACE:${CMAKE_CURRENT_LIST_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
target_link_libraries(voxray_cpu INTERFACE voxray::voxray Threads::Threads)
# Compile flags for each target that links voxray::cpu (the kernels are header-only, so
# they compile in the consumer's own files). Two target properties of the consumer opt out:
#   VOXRAY_CPU_ARCH  unset: -march=x86-64-v3 (native with VOXRAY_NATIVE); a value such as
#                    znver3: -march=<value>; "none": no -march at all (the project's own
#                    flags rule). The SIMD lanes need no -march: they are compiled with
#                    target pragmas and picked at run time; -march speeds up the scalar code.
#   VOXRAY_CPU_KEEP_FP_CONTRACT  ON: leave out -ffp-contract=off. Contraction (FMA) then
#                    fuses some products in one lane kind and not another, so SIMD, scalar
#                    and GPU results may differ in t's last bits and a tie may resolve
#                    differently; the conformance suite's bit-for-bit agreement assumes it off.
# To keep both flags off the rest of a program, link voxray::cpu from one small library
# that holds the tracing code.
if(VOXRAY_NATIVE)
    set(arch_default native)
else()
    set(arch_default x86-64-v3)
endif()
set(arch "$<TARGET_PROPERTY:VOXRAY_CPU_ARCH>")
target_compile_options(voxray_cpu INTERFACE
    "$<$<STREQUAL:${arch},>:-march=${arch_default}>"
    "$<$<NOT:$<OR:$<STREQUAL:${arch},>,$<STREQUAL:${arch},none>>>:-march=${arch}>"
    "$<$<NOT:$<BOOL:$<TARGET_PROPERTY:VOXRAY_CPU_KEEP_FP_CONTRACT>>>:-ffp-contract=off>")
if(VOXRAY_INSTALL)
    install(DIRECTORY ${CMAKE_CURRENT_LIST_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()
voxray_backend_added(cpu voxray_cpu)
