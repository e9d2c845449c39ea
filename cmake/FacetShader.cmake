# facet_add_shader(NAME FILE): builds FILE, a shader of one's own (src/shaders/user_shader.h, ending with
# FACET_SHADER(Name)), into the module NAME.so that `facet render MODEL --shader NAME.so` loads
# (docs/install.md, "Shader modules"). Included by the installed package (FacetConfig.cmake) and by
# Facet's own build (the top CMakeLists.txt), which set first:
#   FACET_SHADER_INCLUDE_DIRS    the folders of facet's headers ("shaders/user_shader.h", "pipeline.h")
#                                and of the generated facet_shader_abi.h
#   FACET_SHADER_FLOAT_FLAGS     the floating-point flags facet is built with (-ffp-contract=off
#                                -fno-math-errno): a shader's arithmetic rounds as the built-in ones'
#   FACET_SHADER_COMPILER_ID, FACET_SHADER_COMPILER_VERSION   the compiler facet was built with
# The module is built for plain x86-64, which every CPU facet runs on has, and is refused by a facet
# built from other headers (its key, facet_shader_abi.h, says which it was built against). It links
# nothing: the pipeline's functions it calls are the facet program's own, which exports them.
function(facet_add_shader name file)
    # The key a module carries names the compiler that built facet, taken on trust: a module compiled by
    # another one could lay out the same structs differently and still carry a matching key.
    if(NOT CMAKE_CXX_COMPILER_ID STREQUAL FACET_SHADER_COMPILER_ID
       OR NOT CMAKE_CXX_COMPILER_VERSION STREQUAL FACET_SHADER_COMPILER_VERSION)
        message(FATAL_ERROR
            "facet_add_shader(${name}): this project compiles with ${CMAKE_CXX_COMPILER_ID} "
            "${CMAKE_CXX_COMPILER_VERSION} and facet was built with ${FACET_SHADER_COMPILER_ID} "
            "${FACET_SHADER_COMPILER_VERSION}: a shader module must be built by the same compiler "
            "(configure with -DCMAKE_CXX_COMPILER=...)")
    endif()
    add_library(${name} MODULE ${file})
    set_target_properties(${name} PROPERTIES
        PREFIX "" SUFFIX ".so"  # NAME.so, as --shader names it
        CXX_STANDARD 20 CXX_STANDARD_REQUIRED ON CXX_EXTENSIONS OFF  # -std=c++20
        POSITION_INDEPENDENT_CODE ON  # -fPIC
        # -fvisibility=hidden: the module exports facet_shader_abi() and facet_shader_module() alone
        # (FACET_SHADER marks them), so its copies of the pipeline's inline code stay its own.
        CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
    target_include_directories(${name} PRIVATE ${FACET_SHADER_INCLUDE_DIRS})
    # GLM's headers (header-only: nothing is linked).
    target_include_directories(${name} SYSTEM PRIVATE $<TARGET_PROPERTY:glm::glm,INTERFACE_INCLUDE_DIRECTORIES>)
    target_compile_definitions(${name} PRIVATE $<TARGET_PROPERTY:glm::glm,INTERFACE_COMPILE_DEFINITIONS>)
    # An unoptimised shader draws many times slower: -O2 when the project chose no build type.
    # -Wno-psabi: GCC's note on the 32-byte vectors' calling convention (docs/install.md) is noise here.
    target_compile_options(${name} PRIVATE ${FACET_SHADER_FLOAT_FLAGS} $<$<CONFIG:>:-O2>
                                           $<$<CXX_COMPILER_ID:GNU,Clang>:-Wno-psabi>)
    if(TARGET facet_shader_abi)  # Facet's own build: the key's header is generated
        add_dependencies(${name} facet_shader_abi)
    endif()
endfunction()
