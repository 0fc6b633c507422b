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
# MuJoCo is private to flexgait::twin: no installed header includes it, no twin/detail/ header is
# installed, and the package does not look for it.
file(GLOB_RECURSE headers "${WORK_DIR}/prefix/include/flexgait/*.hpp")
foreach(h ${headers})
  file(STRINGS "${h}" lines REGEX "#include <mujoco/")
  if(lines OR h MATCHES "/detail/")
    message(FATAL_ERROR "installed header exposes MuJoCo: ${h}")
  endif()
endforeach()
file(STRINGS "${WORK_DIR}/prefix/lib/cmake/flexgait/flexgaitConfig.cmake" lines REGEX "mujoco")
if(lines)
  message(FATAL_ERROR "flexgaitConfig.cmake looks for MuJoCo: ${lines}")
endif()
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
foreach(program consumer twin_consumer)
  execute_process(COMMAND "${WORK_DIR}/build/${program}" RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "${program} run failed")
  endif()
endforeach()
execute_process(COMMAND "${WORK_DIR}/prefix/bin/flexgait" --version RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "installed flexgait does not run")
endif()
# `schema` is one of the commands of the module that the program loads on demand (installed in lib/).
execute_process(COMMAND "${WORK_DIR}/prefix/bin/flexgait" schema RESULT_VARIABLE rc OUTPUT_VARIABLE schema)
if(rc OR NOT schema MATCHES "humanoid-walk")
  message(FATAL_ERROR "installed flexgait does not find its commands' module: ${rc}")
endif()
# The README's tour from an empty directory with only the install prefix on the PATH: the bundled
# configurations are found by name from the install's share directory, not from the source tree.
foreach(f share/flexgait/configs/rimless.yaml share/flexgait/configs/walk-dynamic.yaml share/doc/flexgait/LICENSE)
  if(NOT EXISTS "${WORK_DIR}/prefix/${f}")
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
file(MAKE_DIRECTORY "${WORK_DIR}/elsewhere")
set(only_prefix ${CMAKE_COMMAND} -E env "PATH=${WORK_DIR}/prefix/bin")
execute_process(COMMAND ${only_prefix} flexgait configs --paths WORKING_DIRECTORY "${WORK_DIR}/elsewhere"
                RESULT_VARIABLE rc OUTPUT_VARIABLE listing ERROR_VARIABLE err)
if(rc OR NOT listing MATCHES "rimless-stagnation +The stagnation interval")
  message(FATAL_ERROR "flexgait configs from the PATH failed (${rc}): ${listing}${err}")
endif()
if(NOT listing MATCHES "${WORK_DIR}/prefix/share/flexgait/configs/walk-dynamic.yaml")
  message(FATAL_ERROR "flexgait configs does not list the installed configurations: ${listing}")
endif()
execute_process(COMMAND ${only_prefix} flexgait rimless simulate --config rimless --steps 2 --no-plot --out run
                WORKING_DIRECTORY "${WORK_DIR}/elsewhere" RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(rc OR NOT EXISTS "${WORK_DIR}/elsewhere/run/summary.json")
  message(FATAL_ERROR "rimless simulate --config rimless from an empty directory failed (${rc}): ${err}")
endif()
# The Python package: flexgait/ (__init__.py, the compiled _flexgait, the stubs, py.typed) in the
# prefix's dist-packages, imported by the system python3 from there (not from the build tree) and
# run: a rimless simulation, and `import flexgait.rimless` as a submodule.
if(PYTHON_DIR)
  foreach(f __init__.py __init__.pyi rimless.pyi humanoid.pyi env.py py.typed)
    if(NOT EXISTS "${WORK_DIR}/prefix/${PYTHON_DIR}/flexgait/${f}")
      message(FATAL_ERROR "not installed: ${PYTHON_DIR}/flexgait/${f}")
    endif()
  endforeach()
  set(script [=[
import os, sys
import flexgait, flexgait.rimless
prefix = os.path.realpath(sys.argv[1])
assert os.path.realpath(flexgait.__file__).startswith(prefix), flexgait.__file__
assert os.path.realpath(flexgait._flexgait.__file__).startswith(prefix), flexgait._flexgait.__file__
run = flexgait.rimless.simulate({"sim": {"steps": 1}})
assert run["summary"]["steps"] == 1, run["summary"]
print(flexgait.__version__)
]=])
  execute_process(COMMAND ${CMAKE_COMMAND} -E env "PYTHONPATH=${WORK_DIR}/prefix/${PYTHON_DIR}" /usr/bin/python3 -c
                          "${script}" "${WORK_DIR}/prefix"
                  WORKING_DIRECTORY "${WORK_DIR}/elsewhere" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc)
    message(FATAL_ERROR "the installed Python package does not import and run: ${err}")
  endif()
endif()
