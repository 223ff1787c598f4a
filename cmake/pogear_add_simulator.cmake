# pogear_add_simulator(TARGET SCENE): builds an executable TARGET that simulates a scene file, from
# the C++ that `pogear generate` writes at build time into ${CMAKE_CURRENT_BINARY_DIR}/pogear_TARGET/
# (the target property POGEAR_GENERATED_DIR, for programs of one's own that include the generated
# header: docs/simulator-api.md). Installed with the pogear package; in-tree use is
# `include(${PROJECT_SOURCE_DIR}/cmake/pogear_add_simulator.cmake)`.
include_guard(GLOBAL)

function(pogear_add_simulator target scene)
  if(ARGN)
    message(FATAL_ERROR "pogear_add_simulator(${target} ${scene}): unexpected arguments: ${ARGN}")
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
  get_filename_component(scene_dir "${scene}" DIRECTORY)

  # The generated files are named after the scene, and their names must be known now to declare
  # them as outputs; pogear takes the top-level `name` key, else the file stem. Only lines before
  # the first [table] header are top-level keys, so a `name` inside a table is not mistaken for it.
  file(STRINGS "${scene}" lines REGEX "^[ \t]*(\\[|(name|model)[ \t]*=)")
  get_filename_component(scene_name "${scene}" NAME_WE)
  set(model "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^[ \t]*\\[")
      break()
    elseif(line MATCHES "^[ \t]*name[ \t]*=[ \t]*[\"']([^\"']*)[\"']")
      set(scene_name "${CMAKE_MATCH_1}")
    elseif(line MATCHES "^[ \t]*model[ \t]*=[ \t]*[\"']([^\"']*)[\"']")
      get_filename_component(model "${CMAKE_MATCH_1}" ABSOLUTE BASE_DIR "${scene_dir}")
    endif()
  endforeach()
  # Editing the scene may rename it or point it at another model: re-read it then.
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${scene}")

  # Regenerate when the scene, its model (when found and present; pogear reports a missing one)
  # or the generator itself changes. A target name in DEPENDS resolves to its file.
  set(depends "${scene}" ${generator})
  if(model AND EXISTS "${model}")
    list(APPEND depends "${model}")
  endif()

  set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/pogear_${target}")
  set(generated "${out_dir}/${scene_name}.hpp" "${out_dir}/${scene_name}_main.cpp")
  add_custom_command(
    OUTPUT ${generated}
    COMMAND ${generator} generate "${scene}" -o "${out_dir}"
    DEPENDS ${depends}
    COMMENT "pogear: generating the simulator of scene '${scene_name}' for ${target}"
    VERBATIM)

  add_executable(${target} "${out_dir}/${scene_name}_main.cpp")
  target_sources(${target} PRIVATE "${out_dir}/${scene_name}.hpp")
  target_include_directories(${target} PRIVATE "${out_dir}")
  target_link_libraries(${target} PRIVATE ${runtime})
  target_compile_features(${target} PRIVATE cxx_std_20)
  # Where the header is, for a program of one's own (which then depends on TARGET, whose build
  # generates it): one custom command must not feed several independent targets.
  set_target_properties(${target} PROPERTIES POGEAR_GENERATED_DIR "${out_dir}")
  # Generated code is held to warning-free; a warning here is a generator bug worth failing on.
  if(MSVC)
    target_compile_options(${target} PRIVATE /W4 /WX)
  else()
    target_compile_options(${target} PRIVATE -Wall -Wextra -Werror)
  endif()
endfunction()
