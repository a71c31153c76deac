# The consumer's targets, shared by the consumer projects (find_package, add_subdirectory,
# FetchContent). Each is what a user meets:
#   consumer       traces one ray on every backend target there is; checks the version
#                  macros; compiled with a strict project's flags (-Wpedantic -Wold-style-cast
#                  -Wsign-conversion -Werror) together with a file that includes every public
#                  header. voxray's headers must be system headers for such a project: the
#                  kernel dialect is full of C casts, which those flags reject.
#   cpu_opt_out    links voxray::cpu with VOXRAY_CPU_ARCH=none and VOXRAY_CPU_KEEP_FP_CONTRACT
#                  (consume.cmake checks its compile command holds neither flag).
#   linked_kernels the consumer's program with voxray::kernels linked (where the package has
#                  it): its CPU streams come compiled from the library, and it must link
#                  and trace as the header-only build does.
#   forgot_vulkan  includes voxray/vulkan.hpp without linking voxray::vulkan: must not compile
#                  (EXCLUDE_FROM_ALL; consume.cmake builds it and expects the message).
# EXPECT_VERSION (the version voxray was configured with) is checked against voxray/version.hpp.
set(CMAKE_EXPORT_COMPILE_COMMANDS ON)
set(strict -Wall -Wextra -Wpedantic -Wold-style-cast -Wsign-conversion -Werror)
set(backends "")
set(defines "")
foreach(b cpu opencl vulkan)
    string(TOUPPER ${b} upper)
    if(TARGET voxray::${b})
        list(APPEND backends voxray::${b})
        list(APPEND defines CONSUMER_WITH_${upper}=1)
    else()
        list(APPEND defines CONSUMER_WITH_${upper}=0)
    endif()
endforeach()
if(NOT backends)
    message(FATAL_ERROR "no voxray backend target was found")
endif()

# Every public header of the core and of the backends and the glTF component linked here (not
# the Embree and NanoVDB baselines nor the MPI component, not the generated tables that the
# backends include themselves).
if(VOXRAY_SOURCE_DIR)
    file(GLOB roots ${VOXRAY_SOURCE_DIR}/include ${VOXRAY_SOURCE_DIR}/backends/*/include)
else()
    get_target_property(roots voxray::voxray INTERFACE_INCLUDE_DIRECTORIES)
endif()
set(includes "#include \"voxray/version.hpp\"\n")
foreach(root ${roots})
    file(GLOB_RECURSE headers RELATIVE ${root} ${root}/voxray/*.hpp)
    foreach(h ${headers})
        string(REGEX MATCH "^voxray/(cpu|opencl|vulkan|gltf)" backend "${h}")
        if(h MATCHES "^voxray/(generated|embree|nanovdb|mpi)/" OR (backend AND NOT TARGET voxray::${CMAKE_MATCH_1}))
            continue()
        endif()
        # Core headers that run on the CPU's lanes (the world's frame passes where no device
        # runs them, the scenes' brute-force reference, a world's appearance tables) say so
        # in an #error without voxray::cpu: that line is the list.
        file(STRINGS ${root}/${h} needs_cpu REGEX "^#error \".* needs voxray::cpu")
        if(needs_cpu AND NOT backend AND NOT TARGET voxray::cpu)
            continue()
        endif()
        string(APPEND includes "#include \"${h}\"\n")
    endforeach()
endforeach()
file(CONFIGURE OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/all_headers.cpp CONTENT "@includes@" @ONLY)

set(src ${CMAKE_CURRENT_LIST_DIR}/consumer)
add_executable(consumer ${src}/main.cpp ${CMAKE_CURRENT_BINARY_DIR}/all_headers.cpp)
target_link_libraries(consumer PRIVATE voxray::voxray ${backends})
if(TARGET voxray::gltf)  # the coloured-mesh readers' headers are in all_headers.cpp too
    target_link_libraries(consumer PRIVATE voxray::gltf)
endif()
target_compile_definitions(consumer PRIVATE ${defines} EXPECT_VERSION="${EXPECT_VERSION}")
target_compile_options(consumer PRIVATE ${strict})

if(TARGET voxray::cpu)
    add_executable(cpu_opt_out ${src}/cpu_opt_out.cpp)
    target_link_libraries(cpu_opt_out PRIVATE voxray::voxray voxray::cpu)
    set_target_properties(cpu_opt_out PROPERTIES VOXRAY_CPU_ARCH none VOXRAY_CPU_KEEP_FP_CONTRACT ON)
endif()

if(TARGET voxray::kernels AND NOT VOXRAY_SOURCE_DIR)  # installed only: from source it would build the library again
    add_executable(linked_kernels ${src}/main.cpp)
    target_link_libraries(linked_kernels PRIVATE voxray::voxray ${backends} voxray::kernels)
    target_compile_definitions(linked_kernels PRIVATE ${defines} EXPECT_VERSION="${EXPECT_VERSION}")
    target_compile_options(linked_kernels PRIVATE ${strict})
endif()

add_executable(forgot_vulkan EXCLUDE_FROM_ALL ${src}/forgot_vulkan.cpp)
target_link_libraries(forgot_vulkan PRIVATE voxray::voxray)
