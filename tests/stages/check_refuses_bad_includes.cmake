# cmake -DSTAGES_FILE=... -DCHECK=<check_includes.cmake> -DFIXTURE=<bad_includes> -P check_refuses_bad_includes.cmake
#
# check_includes.cmake on a fixture that breaks each of its rules once must fail and name all four.
cmake_minimum_required(VERSION 3.25)
execute_process(COMMAND ${CMAKE_COMMAND} -DSTAGES_FILE=${STAGES_FILE} -DSOURCE_DIR=${FIXTURE} -P ${CHECK}
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(result EQUAL 0)
  message(FATAL_ERROR "check_includes.cmake accepted the bad includes:\n${out}${err}")
endif()
foreach(expected IN ITEMS
    "#include \"../vibrate/vibration_modes.hpp\" climbs out of its folder"
    "#include \"kept_velocities.hpp\" does not name its folder"
    "#include \"vibrate/vibration_modes.hpp\": derive may not use vibrate"
    "a stage's header in <...>: write it in quotes")
  string(FIND "${out}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "check_includes.cmake did not name: ${expected}\n${out}${err}")
  endif()
endforeach()
