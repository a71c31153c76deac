# voxray::gltf — not a tracer backend: the optional component that reads coloured meshes
# (voxray/gltf/, in its own include folder: the core's headers need no image or glTF
# library). glTF 2.0 through Debian's shared TinyGLTF (libtinygltf-dev, which decodes the
# images), and the texture files of OBJ materials through stb_image (libstb-dev). The
# tool and the tests link it; without it the library builds and meshes load without colour.
find_package(TinyGLTF CONFIG QUIET)
find_library(VOXRAY_STB_LIBRARY stb)
find_path(VOXRAY_STB_INCLUDE_DIR stb/stb_image.h)
if(TinyGLTF_FOUND AND VOXRAY_STB_LIBRARY AND VOXRAY_STB_INCLUDE_DIR)
    add_library(voxray_gltf INTERFACE)
    add_library(voxray::gltf ALIAS voxray_gltf)
    set_target_properties(voxray_gltf PROPERTIES EXPORT_NAME gltf)
    target_include_directories(voxray_gltf ${VOXRAY_SYSTEM} INTERFACE
        $<BUILD_INTERFACE:${CMAKE_CURRENT_LIST_DIR}/include>
        $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    target_link_libraries(voxray_gltf INTERFACE voxray::voxray TinyGLTF::TinyGLTF ${VOXRAY_STB_LIBRARY})
    if(VOXRAY_INSTALL)
        install(DIRECTORY ${CMAKE_CURRENT_LIST_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    endif()
    voxray_backend_added(gltf voxray_gltf)
else()
    voxray_backend_missing(gltf "TinyGLTF or stb_image not found (Debian: libtinygltf-dev libstb-dev)")
endif()
