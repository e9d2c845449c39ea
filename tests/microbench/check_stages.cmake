# Runs facet_microbench briefly (one short run of every benchmark) and checks that it exits 0 and
# reports every pipeline stage's benchmark: a stage dropped from the binary, or one that fails, fails
# this test. Run by ctest as Microbench.ReportsEveryStage with -DMICROBENCH=<the binary>.
set(stages VertexStage Clip Setup Rasterize Interpolate DepthTest FragmentShader TextureFilter Fog Blend
           SupersampleResolve MsaaResolve FragmentLists)
execute_process(COMMAND ${MICROBENCH} --benchmark_min_time=0.001 --benchmark_format=json
                OUTPUT_VARIABLE report ERROR_VARIABLE errors RESULT_VARIABLE status)
if(NOT status EQUAL 0)
    message(FATAL_ERROR "facet_microbench exited with ${status}:\n${errors}")
endif()
foreach(stage IN LISTS stages)
    string(FIND "${report}" "\"name\": \"BM_${stage}/" found)
    if(found EQUAL -1)
        message(FATAL_ERROR "facet_microbench reported no benchmark of the stage ${stage} (BM_${stage})")
    endif()
endforeach()
# A benchmark that calls state.SkipWithError still exits 0: none may.
string(FIND "${report}" "\"error_occurred\": true" failed)
if(NOT failed EQUAL -1)
    message(FATAL_ERROR "a facet_microbench benchmark reported an error:\n${report}")
endif()
