# cmake -DWORK_DIR=... -DCONSUMER_DIR=... [-DBUILD_DIR=...] [-DCONFIGURE_ARGS=a|b] -P consume.cmake
# Configures, builds and runs a consumer project. With BUILD_DIR, voxray is first installed
# from that build into WORK_DIR/prefix and the consumer finds it there (find_package).
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
    execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
    endif()
endfunction()
string(REPLACE "|" ";" configure_args "${CONFIGURE_ARGS}")
if(BUILD_DIR)
    run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
    list(APPEND configure_args -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix)
endif()
run(${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${WORK_DIR}/build -DCMAKE_BUILD_TYPE=Release ${configure_args})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build -j2 --target consumer)
run(${WORK_DIR}/build/consumer)
message(STATUS "the consumer in ${CONSUMER_DIR} was built against voxray and ran")
