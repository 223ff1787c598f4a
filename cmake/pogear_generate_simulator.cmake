# Build step of pogear_add_simulator (cmake -P, with POGEAR, SCENE, OUT_DIR, MAIN and optionally SOLVERS defined): asks
# pogear which files the scene writes, generates them into OUT_DIR/staging and copies into OUT_DIR
# those that changed, then writes MAIN, a file of a fixed name that includes the generated main.
cmake_minimum_required(VERSION 3.25)

foreach(var POGEAR SCENE OUT_DIR MAIN)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "pogear_generate_simulator.cmake: pass -D${var}=...")
  endif()
endforeach()

set(staging "${OUT_DIR}/staging")
# SOLVERS (optional): the solvers to compile in, as `pogear generate --solvers` takes them.
set(solvers_option "")
if(DEFINED SOLVERS AND NOT SOLVERS STREQUAL "")
  set(solvers_option --solvers "${SOLVERS}")
endif()
# pogear's own message (FILE:LINE:COL: error: ...) is what the user needs to see when it fails.
execute_process(COMMAND "${POGEAR}" generate "${SCENE}" -o "${staging}" --list-outputs
  RESULT_VARIABLE status OUTPUT_VARIABLE listed ERROR_VARIABLE errors)
if(NOT status STREQUAL "0")
  message(FATAL_ERROR "${errors}")
endif()
execute_process(COMMAND "${POGEAR}" generate "${SCENE}" -o "${staging}" ${solvers_option}
  RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE errors)
if(NOT status STREQUAL "0")
  message(FATAL_ERROR "${errors}")
endif()

# One path per line: the header, then the main.
string(REGEX REPLACE "\n$" "" listed "${listed}")
string(REPLACE "\n" ";" listed "${listed}")
list(LENGTH listed count)
if(NOT count EQUAL 2)
  message(FATAL_ERROR "pogear generate --list-outputs printed ${count} files, expected a header and a main: ${listed}")
endif()
set(names "")
foreach(path IN LISTS listed)
  get_filename_component(name "${path}" NAME)
  list(APPEND names "${name}")
  # Unchanged files keep their time stamps: the simulator is recompiled only when the code changed.
  file(COPY_FILE "${staging}/${name}" "${OUT_DIR}/${name}" ONLY_IF_DIFFERENT)
endforeach()

# What an earlier build generated here and this one no longer writes (the header and main of a
# scene since renamed) is removed, so that no program goes on compiling against a model that is
# gone. Only names this script wrote into its own list are touched, never another file, and only
# plain file names: the list lives in a build directory, which is no place to trust a path from.
set(manifest "${OUT_DIR}/pogear_generated_files.txt")
if(EXISTS "${manifest}")
  file(STRINGS "${manifest}" previous)
  foreach(name IN LISTS previous)
    if(name MATCHES "^[A-Za-z0-9_][A-Za-z0-9_.+-]*$" AND NOT name IN_LIST names)
      file(REMOVE "${OUT_DIR}/${name}" "${staging}/${name}")
    endif()
  endforeach()
endif()
string(JOIN "\n" manifest_text ${names})
file(WRITE "${manifest}" "${manifest_text}\n")
list(GET listed 1 generated_main)
get_filename_component(generated_main "${generated_main}" NAME)
file(CONFIGURE OUTPUT "${MAIN}" CONTENT "#include \"${generated_main}\"\n" @ONLY)
