# The `consumer_package` test (cmake -P): installs pogear's build tree into a fresh prefix, builds
# the user project in this directory against it with find_package(pogear), runs the simulator and
# checks its CSV. Registered by register.cmake, which passes the variables checked below.
cmake_minimum_required(VERSION 3.25)

foreach(var POGEAR_BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR SCENE EXPECTED_CSV EXPECTED_ROWS GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "run_consumer_test.cmake: pass -D${var}=...")
  endif()
endforeach()
# An empty configuration (single-config build without a build type) means the default one.
set(config "${POGEAR_CONFIG}")
set(consumer_config "${POGEAR_CONFIG}")
if(consumer_config STREQUAL "")
  set(consumer_config Release)
endif()

# Every step gets fresh directories, so nothing from an earlier run (an old install, a stale
# consumer cache) can make the test pass. They are kept after a failure for inspection.
set(prefix "${WORK_DIR}/prefix")
set(build "${WORK_DIR}/build")
set(out "${WORK_DIR}/out")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${prefix}" "${build}" "${out}")

# Runs one command; on failure stops the test with the command and everything it printed.
function(run_step what)
  string(JOIN " " shown ${ARGN})
  message(STATUS "${what}: ${shown}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT rc STREQUAL "0")
    message(FATAL_ERROR "${what} failed (${rc}).\ncommand: ${shown}\noutput:\n${output}\n"
                        "(work directory kept: ${WORK_DIR})")
  endif()
endfunction()

# Stops the test with a message given in one or more pieces.
function(fail)
  string(JOIN "" text ${ARGV})
  message(FATAL_ERROR "${text}\n(work directory kept: ${WORK_DIR})")
endfunction()

set(config_args "")
if(NOT config STREQUAL "")
  set(config_args --config "${config}")
endif()
run_step("installing pogear" "${CMAKE_COMMAND}" --install "${POGEAR_BUILD_DIR}" --prefix "${prefix}" ${config_args})

# CONSUMER_OPT_FLAGS (optional): the consumer's flags for its configuration, pogear's own.
set(opt_args "")
if(NOT "${CONSUMER_OPT_FLAGS}" STREQUAL "")
  string(TOUPPER "${consumer_config}" upper_config)
  set(opt_args "-DCMAKE_CXX_FLAGS_${upper_config}=${CONSUMER_OPT_FLAGS}")
endif()

# The package registry is off so that only the fresh prefix can satisfy find_package(pogear).
run_step("configuring the consumer" "${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE_DIR}" -B "${build}"
  -G "${GENERATOR}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" "-DCMAKE_BUILD_TYPE=${consumer_config}"
  "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF "-DPOGEAR_SCENE=${SCENE}" ${opt_args})
file(STRINGS "${build}/CMakeCache.txt" pogear_dir REGEX "^pogear_DIR:")
string(REGEX REPLACE "^pogear_DIR:[A-Z]+=" "" pogear_dir "${pogear_dir}")
string(FIND "${pogear_dir}" "${prefix}/" at)
if(NOT at EQUAL 0)
  fail("the consumer found pogear at '${pogear_dir}', not in the fresh install '${prefix}'")
endif()

run_step("building the consumer" "${CMAKE_COMMAND}" --build "${build}" --config "${consumer_config}")

# Single-config generators put the executable in the build directory, multi-config ones below it.
set(simulator "")
foreach(candidate "${build}/one_stage" "${build}/${consumer_config}/one_stage" "${build}/one_stage.exe"
                  "${build}/${consumer_config}/one_stage.exe")
  if(EXISTS "${candidate}" AND NOT IS_DIRECTORY "${candidate}")
    set(simulator "${candidate}")
    break()
  endif()
endforeach()
if(simulator STREQUAL "")
  fail("the consumer build produced no one_stage executable under ${build}")
endif()

run_step("running the simulator" "${simulator}" --out "${out}" --quiet)

# The CSV: one header line, then EXPECTED_ROWS lines of numbers with as many fields as the header.
# Lines are matched by pattern rather than split into a CMake list, since the header's unit
# brackets ("t [s]") would confuse list handling.
set(csv "${out}/${EXPECTED_CSV}")
if(NOT EXISTS "${csv}")
  file(GLOB written RELATIVE "${out}" "${out}/*")
  fail("the simulator wrote no ${EXPECTED_CSV}; ${out} holds: ${written}")
endif()
file(READ "${csv}" text)
string(REGEX MATCHALL "\n" newlines "${text}")
list(LENGTH newlines lines)
file(STRINGS "${csv}" header LIMIT_COUNT 1)
string(REGEX MATCHALL "," commas "${header}")
list(LENGTH commas columns)
math(EXPR columns "${columns} + 1")
file(STRINGS "${csv}" rows REGEX "^[-+0-9.eE]+(,[-+0-9.eE]+)*$")
list(LENGTH rows data_rows)
math(EXPR expected_lines "${EXPECTED_ROWS} + 1")
if(NOT lines EQUAL expected_lines OR NOT data_rows EQUAL EXPECTED_ROWS OR header MATCHES "^[-+0-9.]")
  string(SUBSTRING "${text}" 0 400 start)
  fail("${csv}: expected a header and ${EXPECTED_ROWS} numeric rows; found ${lines} lines, of which "
       "${data_rows} numeric rows. It starts:\n${start}")
endif()
foreach(row IN LISTS rows)
  string(REGEX MATCHALL "," commas "${row}")
  list(LENGTH commas fields)
  math(EXPR fields "${fields} + 1")
  if(NOT fields EQUAL columns)
    fail("${csv}: a row has ${fields} fields, the header ${columns}: ${row}")
  endif()
endforeach()

message(STATUS "consumer_package: ${EXPECTED_CSV} has a header and ${data_rows} rows of ${columns} columns")
file(REMOVE_RECURSE "${WORK_DIR}")
