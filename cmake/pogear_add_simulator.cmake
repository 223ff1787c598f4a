# pogear_add_simulator(TARGET SCENE [SOLVERS LIST] [HEADER_ONLY]): builds an executable TARGET that
# simulates a scene file, with the solvers of LIST ("exact,dopri5" or "all"; default the scene's), from
# the C++ that `pogear generate` writes at build time into ${CMAKE_CURRENT_BINARY_DIR}/pogear_TARGET/
# (the target property POGEAR_GENERATED_DIR, for programs of one's own that include the generated
# header: docs/simulator-api.md). Installed with the pogear package; in-tree use is
# `include(${PROJECT_SOURCE_DIR}/cmake/pogear_add_simulator.cmake)`.
include_guard(GLOBAL)

# Run at build time by the commands below (cmake -P), installed next to this file.
set(_pogear_generate_script "${CMAKE_CURRENT_LIST_DIR}/pogear_generate_simulator.cmake")

# It links libpogear_runtime (pogear::runtime); with HEADER_ONLY the runtime is compiled into TARGET
# instead (POGEAR_RT_HEADER_ONLY; about 20 s more compile time).
function(pogear_add_simulator target scene)
  cmake_parse_arguments(PARSE_ARGV 2 arg "HEADER_ONLY" "SOLVERS" "")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "pogear_add_simulator(${target} ${scene}): unexpected arguments: ${arg_UNPARSED_ARGUMENTS}")
  endif()

  # The installed package's targets when present, otherwise pogear's own build tree.
  if(TARGET pogear::pogear AND TARGET pogear::runtime)
    set(generator pogear::pogear)
    set(runtime pogear::runtime)
  elseif(TARGET pogear AND TARGET pogear_runtime)
    set(generator pogear)
    set(runtime pogear_runtime)
  else()
    message(FATAL_ERROR "pogear_add_simulator: neither pogear::pogear (find_package(pogear)) nor the "
                        "in-tree pogear and pogear_runtime targets exist")
  endif()

  get_filename_component(scene "${scene}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  if(NOT EXISTS "${scene}")
    message(FATAL_ERROR "pogear_add_simulator(${target}): scene file '${scene}' does not exist")
  endif()

  # What the scene writes (file names after the scene's name) and what it reads (its model, its
  # tables) are pogear's to know: at every build a script asks it (`generate --list-outputs`),
  # generates into a staging directory and copies only what changed, so that an edit of the scene,
  # its model or a table rebuilds the simulator and nothing else does. The executable's source is a
  # file of a fixed name that includes the generated main. Generating costs a few ten milliseconds.
  set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/pogear_${target}")
  set(main "${out_dir}/pogear_simulator_main.cpp")
  add_custom_target(pogear_${target}_sources
    COMMAND "${CMAKE_COMMAND}" "-DPOGEAR=$<TARGET_FILE:${generator}>" "-DSCENE=${scene}" "-DOUT_DIR=${out_dir}"
            "-DMAIN=${main}" "-DSOLVERS=${arg_SOLVERS}" -P "${_pogear_generate_script}"
    BYPRODUCTS "${main}"
    COMMENT "pogear: generating the simulator of ${scene} for ${target}"
    VERBATIM)
  if(generator STREQUAL "pogear")
    add_dependencies(pogear_${target}_sources pogear)
  endif()

  add_executable(${target} "${main}")
  add_dependencies(${target} pogear_${target}_sources)
  target_include_directories(${target} PRIVATE "${out_dir}")
  target_link_libraries(${target} PRIVATE ${runtime})
  if(arg_HEADER_ONLY)
    target_compile_definitions(${target} PRIVATE POGEAR_RT_HEADER_ONLY)
  endif()
  target_compile_features(${target} PRIVATE cxx_std_20)
  # Where the header is, for a program of one's own (which then depends on TARGET, whose build
  # generates it).
  set_target_properties(${target} PROPERTIES POGEAR_GENERATED_DIR "${out_dir}")
  # Generated code is held to warning-free; a warning here is a generator bug worth failing on.
  if(MSVC)
    target_compile_options(${target} PRIVATE /W4 /WX)
  else()
    target_compile_options(${target} PRIVATE -Wall -Wextra -Werror)
  endif()
endfunction()
