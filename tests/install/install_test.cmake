# Installs the build tree into a fresh prefix, then configures, builds and runs a consumer
# project that uses find_package(flexgait). Run with -DBUILD_DIR= -DSOURCE_DIR= -DWORK_DIR= -DCXX_FLAGS=
file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(COMMAND ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix"
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "cmake --install failed: ${rc}")
endif()
foreach(f include/flexgait/rimless/rigid_wheel.hpp include/flexgait/version.hpp bin/flexgait
          lib/cmake/flexgait/flexgaitConfig.cmake share/flexgait/python/plot_rimless.py
          share/flexgait/python/report.py share/flexgait/data/report/references.yaml
          share/flexgait/data/report/index.html.j2)
  if(NOT EXISTS "${WORK_DIR}/prefix/${f}")
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/install/consumer" -B "${WORK_DIR}/build"
                        "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix" "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
                        "-DCMAKE_EXE_LINKER_FLAGS=${CXX_FLAGS}"
                RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer configure failed")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build "${WORK_DIR}/build" RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer build failed")
endif()
execute_process(COMMAND "${WORK_DIR}/build/consumer" RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "consumer run failed")
endif()
execute_process(COMMAND "${WORK_DIR}/prefix/bin/flexgait" --version RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "installed flexgait does not run")
endif()
