# Build step of the reference tests: `pogear generate SCENE -o OUT_DIR`, then OUT_DIR/scene_under_test.hpp,
# which includes the generated header under whatever name the scene gives it and says which systems
# it holds (cmake -DPOGEAR=... -DSCENE=... -DOUT_DIR=... -P generate_scene_header.cmake).
file(REMOVE_RECURSE "${OUT_DIR}")  # a renamed scene must not leave its old header behind
file(MAKE_DIRECTORY "${OUT_DIR}")
execute_process(COMMAND "${POGEAR}" generate "${SCENE}" -o "${OUT_DIR}" RESULT_VARIABLE status OUTPUT_QUIET)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "pogear generate ${SCENE} failed (${status})")
endif()

# pogear names the files it writes; the header is the first, <scene name>.hpp, and its namespace
# pogear_generated::<scene name>.
execute_process(COMMAND "${POGEAR}" generate "${SCENE}" -o "${OUT_DIR}" --list-outputs
                RESULT_VARIABLE status OUTPUT_VARIABLE outputs)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "pogear generate ${SCENE} --list-outputs failed (${status})")
endif()
string(STRIP "${outputs}" outputs)
string(REPLACE "\n" ";" outputs "${outputs}")
list(GET outputs 0 headers)
file(READ "${headers}" text)
get_filename_component(name "${headers}" NAME_WE)
set(has_elastic 0)
set(has_rigid 0)
if(text MATCHES "\nstruct Elastic {")
  set(has_elastic 1)
endif()
if(text MATCHES "\nstruct Rigid {")
  set(has_rigid 1)
endif()

get_filename_component(header_name "${headers}" NAME)
file(WRITE "${OUT_DIR}/scene_under_test.hpp"
  "// Written by tests/reference/generate_scene_header.cmake for ${SCENE}.\n"
  "#pragma once\n"
  "#include \"${header_name}\"\n"
  "namespace scene_under_test = pogear_generated::${name};\n"
  "#define POGEAR_SCENE_HAS_ELASTIC ${has_elastic}\n"
  "#define POGEAR_SCENE_HAS_RIGID ${has_rigid}\n")
