# Run by the build on each wider copy of the frame's code (src/render/CMakeLists.txt, frame_kernels.h),
# after objcopy: cmake -DOBJECT=… -DENTRY=… -DNM=… -P check_frame_kernels.cmake
#  1. The entry point is its only global definition: every other symbol is local, so no copy of an
#     inline function compiled for AVX can stand in for the baseline's in the final link.
#  2. It calls no function outside itself with a vector (Float8, Int8) by value: such an argument
#     travels in a YMM register from AVX code and in memory from baseline code, so the callee, compiled
#     for baseline, would read garbage. (Pass the lanes by reference, as RayScene::occluded8 does.)
#  3. With -DCHECK_INLINING=1 (GCC release builds): the per-texel and per-lane helpers below were
#     inlined, none left as a function of its own. Out of line, each returns a vec4 through memory; when
#     GCC's unit-growth limit left glm::mix and Texture::texel out of line, a textured 4K frame took 65%
#     longer and no test noticed.
execute_process(COMMAND ${NM} --defined-only --extern-only ${OBJECT} OUTPUT_VARIABLE globals COMMAND_ERROR_IS_FATAL ANY)
string(REGEX MATCHALL "[^\n]+" global_lines "${globals}")
foreach(line IN LISTS global_lines)
    if(NOT line MATCHES " ${ENTRY}$")
        message(FATAL_ERROR "${OBJECT}: ${line} is global; only ${ENTRY} may be (objcopy --keep-global-symbol)")
    endif()
endforeach()
if(NOT globals MATCHES " T ${ENTRY}\n")
    message(FATAL_ERROR "${OBJECT}: the entry point ${ENTRY} is not defined")
endif()
execute_process(COMMAND ${NM} --undefined-only --demangle ${OBJECT} OUTPUT_VARIABLE undefined COMMAND_ERROR_IS_FATAL ANY)
string(REGEX MATCHALL "[^\n]*[(,] ?(float|int|unsigned int|double) __vector\\([0-9]+\\)[,)][^\n]*" by_value "${undefined}")
if(by_value)
    string(REPLACE ";" "\n" by_value "${by_value}")
    message(FATAL_ERROR "${OBJECT} calls baseline code with vector lanes by value (pass them by reference):\n${by_value}")
endif()
if(CHECK_INLINING)
    execute_process(COMMAND ${NM} --defined-only --demangle ${OBJECT} OUTPUT_VARIABLE defined COMMAND_ERROR_IS_FATAL ANY)
    set(out_of_line "")
    foreach(helper "glm::detail::compute_mix" "facet::Texture::texel" "facet::sampleBilinear(" "facet::safeNormalize<"
                   "facet::fastExp2<" "facet::fastLog2<")
        string(FIND "${defined}" " ${helper}" at)
        if(NOT at EQUAL -1)
            list(APPEND out_of_line "${helper}")
        endif()
    endforeach()
    if(out_of_line)
        message(FATAL_ERROR "${OBJECT}: hot helpers left out of line (raise the inlining limits of "
                            "src/render/CMakeLists.txt, or force them inline): ${out_of_line}")
    endif()
endif()
