# Installing Facet (docs/install.md): cmake --install puts the program, its modules, the bundled models,
# the documentation and the man page, and for programs of one's own the pipeline's library and headers
# with a CMake package (find_package(Facet)) and a pkg-config file (facet.pc). CPack makes the same files
# a .deb (cpack -G DEB). Every folder comes from GNUInstallDirs (included by the top CMakeLists.txt).
include(CMakePackageConfigHelpers)

# Installing (make install, cpack) installs what was built and builds nothing more: everything installed
# comes with the facet target, and a cpack run by the tests must not build the rest of the test suite.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)

set(facet_datadir ${CMAKE_INSTALL_DATADIR}/facet)
set(facet_docdir ${CMAKE_INSTALL_DATAROOTDIR}/doc/facet)
set(facet_includedir ${CMAKE_INSTALL_INCLUDEDIR}/facet)
set(facet_cmakedir ${CMAKE_INSTALL_LIBDIR}/cmake/Facet)

# The program and the modules it loads with dlopen, in the folder src/base/module.cpp looks in relative to
# the program's (FACET_INSTALL_MODULEDIR).
install(TARGETS facet RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(module facet_openimageio facet_opencv)
    if(TARGET ${module})  # sanitized builds link OpenCV into facet instead (src/trade/CMakeLists.txt)
        install(TARGETS ${module} LIBRARY DESTINATION ${FACET_INSTALL_MODULEDIR})
    endif()
endforeach()

# The models and scenes the documentation renders; the scene files name their OBJ files relative to
# themselves, so they work from here as from the repository.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/models/ DESTINATION ${facet_datadir}/models)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${facet_docdir})
# The pages with their images and the example files they name (docs/batch's job scripts), laid out as in
# the repository so that the README's links to docs/… and theirs to ../README.md hold; the man page's
# source goes to man1 instead.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${facet_docdir}/docs PATTERN facet.1 EXCLUDE)
install(FILES ${PROJECT_SOURCE_DIR}/docs/facet.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)

# The libraries a program needs to draw with shaders of its own, load OBJ models and write images:
# Facet::pipeline (draw<Shader>(), pipeline/*.h, GLM's types), Facet::shading (the lighting, fog and
# gamma formulas, header-only), Facet::scene (meshes, the scene model, the camera), Facet::io (OBJ + MTL
# import, image files) and Facet::base (InputError, which they throw). The renderer, the shaders and the
# commands stay inside the program. Sanitizer and fuzzing builds link an object library into every
# target, which no package could hand on: they install the program alone.
set(facet_exported facet_pipeline facet_base facet_shading facet_scene facet_io)
if(NOT (FACET_SANITIZE OR FACET_FUZZ))
    foreach(target ${facet_exported})
        string(REPLACE "facet_" "" name ${target})
        set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
    endforeach()
    # GCC notes at every inline function of wide.h taking or returning Float8 that the 32-byte vector's
    # ABI differs with AVX (the top CMakeLists.txt); in a program built, as the library is, for baseline
    # x86-64 (docs/install.md) that is noise, so the installed pipeline turns the note off (as facet.pc does).
    set_property(TARGET facet_pipeline APPEND PROPERTY INTERFACE_COMPILE_OPTIONS
                 $<INSTALL_INTERFACE:$<$<CXX_COMPILER_ID:GNU,Clang>:-Wno-psabi>>)
    install(TARGETS ${facet_exported} EXPORT FacetTargets
            ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
    install(EXPORT FacetTargets NAMESPACE Facet:: DESTINATION ${facet_cmakedir})
    # FacetConfig.cmake also defines facet_add_shader() (FacetShader.cmake), with this build's
    # floating-point flags and compiler.
    configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/FacetConfig.cmake.in
                                  ${PROJECT_BINARY_DIR}/FacetConfig.cmake INSTALL_DESTINATION ${facet_cmakedir}
                                  PATH_VARS facet_includedir)
    # 0.x: a minor version may change the interface.
    write_basic_package_version_file(${PROJECT_BINARY_DIR}/FacetConfigVersion.cmake
                                     COMPATIBILITY SameMinorVersion)
    install(FILES ${PROJECT_BINARY_DIR}/FacetConfig.cmake ${PROJECT_BINARY_DIR}/FacetConfigVersion.cmake
                  ${CMAKE_CURRENT_LIST_DIR}/FacetShader.cmake
            DESTINATION ${facet_cmakedir})

    # The headers, under include/facet/ with their folders, so that "pipeline/state.h" and
    # "shading/lighting.h" name them as in the repository; the pipeline's own headers name each other
    # alone ("state.h"), so include/facet/pipeline is an include folder too (Facet::pipeline, facet.pc).
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/pipeline/ DESTINATION ${facet_includedir}/pipeline
            FILES_MATCHING PATTERN "*.h")
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/shading/ DESTINATION ${facet_includedir}/shading
            FILES_MATCHING PATTERN "*.h")
    install(FILES ${PROJECT_SOURCE_DIR}/src/base/errors.h DESTINATION ${facet_includedir}/base)
    # Not the JSON reader's headers (json_reader.h, scene_sections.h): they need nlohmann's headers and
    # serve only loadScene().
    foreach(header mesh.h scene.h limits.h camera.h)
        install(FILES ${PROJECT_SOURCE_DIR}/src/scene/${header} DESTINATION ${facet_includedir}/scene)
    endforeach()
    # Not the OBJ reader's inner parts (obj_scan.h, obj_text.h, mtl_reader.h, mesh_builder.h), which
    # need tinyobjloader's header.
    foreach(header obj_import.h image_io.h image_file.h text_file.h)
        install(FILES ${PROJECT_SOURCE_DIR}/src/io/${header} DESTINATION ${facet_includedir}/io)
    endforeach()
    # What a shader of one's own compiles against (docs/install.md, "Shader modules"): the installed facet
    # compiles `--shader toon.cpp` with them (src/render/user_shaders.cpp finds them relative to the
    # program), and facet_add_shader() of the CMake package builds a module with them. shadowing.h names
    # the ray caster's header; facet_shader_abi.h, generated, holds the key the modules must carry.
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/shaders/ DESTINATION ${facet_includedir}/shaders
            FILES_MATCHING PATTERN "*.h")
    install(FILES ${PROJECT_SOURCE_DIR}/src/raycast/ray_scene.h DESTINATION ${facet_includedir}/raycast)
    install(FILES ${PROJECT_BINARY_DIR}/generated/facet_shader_abi.h DESTINATION ${facet_includedir})

    # facet.pc, for builds without CMake: the pipeline. Its prefix is found from the file's own folder
    # (${pcfiledir}), so that a prefix given to cmake --install, or one moved, is right.
    set(facet_pkgconfigdir ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
    file(RELATIVE_PATH facet_pc_prefix /${facet_pkgconfigdir} /)
    string(REGEX REPLACE "/$" "" facet_pc_prefix "${facet_pc_prefix}")
    configure_file(${CMAKE_CURRENT_LIST_DIR}/facet.pc.in ${PROJECT_BINARY_DIR}/facet.pc @ONLY)
    install(FILES ${PROJECT_BINARY_DIR}/facet.pc DESTINATION ${facet_pkgconfigdir})
endif()

# The .deb: cpack -G DEB in the build folder (or cpack --config <build>/CPackConfig.cmake). Its Depends
# are the Debian packages of the libraries the program and the modules link, found by dpkg-shlibdeps
# (Debian's dpkg-dev; CPack also runs file, to find the binaries).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME facet)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "Facet")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "software rasterizer: the real-time graphics pipeline on the CPU")
string(CONCAT CPACK_PACKAGE_DESCRIPTION
    "Facet renders OBJ models and JSON scene files to images with the whole rasterization pipeline "
    "(vertex shading, clipping, setup, tiled rasterization, depth test, fragment shading, blending) "
    "written in C++ and run on the CPU. The facet program renders (facet render), traces a pixel "
    "through every stage (facet step), compares against OpenGL (facet compare), times (facet bench) and "
    "scores accuracy knobs (facet trade). The package also holds the pipeline's library, headers, CMake "
    "package and pkg-config file for programs with shaders of their own.")
set(FACET_PACKAGE_MAINTAINER "Facet maintainers <maintainers@users.noreply.h-seed-bbdfcf9c.example>"
    CACHE STRING "The .deb's Maintainer field")
set(CPACK_PACKAGE_CONTACT ${FACET_PACKAGE_MAINTAINER})
set(CPACK_DEBIAN_PACKAGE_MAINTAINER ${FACET_PACKAGE_MAINTAINER})
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# Recommends: what `facet render --shader toon.cpp` needs to compile a shader of one's own: the compiler
# facet was built with (it runs that one, FACET_SHADER_COMPILER of src/render/CMakeLists.txt) and GLM's
# headers, which the installed shader headers include. Recommended, not required: facet draws with its
# built-in shaders and loads ready-built modules (.so) without them, and says what is missing when a
# .cpp cannot be compiled.
if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    set(facet_shader_compiler_package clang)
else()
    set(facet_shader_compiler_package g++)
endif()
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "${facet_shader_compiler_package}, libglm-dev")
# OSMesa: facet compare and facet bench --vs-mesa load it at run time (the rest runs without it). The
# others: what building against the installed headers needs besides a C++20 compiler (find_package(Facet)).
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "libosmesa6, libpng-dev, libdeflate-dev, libtinyobjloader-dev, nlohmann-json3-dev")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # facet_<version>_<architecture>.deb
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
include(CPack)
