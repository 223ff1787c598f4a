# The generator's stages (the folders of generator/src/) and which stages each builds on directly
# (docs/architecture.md). Read by generator/CMakeLists.txt, which builds one library per stage with
# an include root of what it may use, and by tests/stages/check_includes.cmake.
set(POGEAR_STAGES common names read derive engage specialize vibrate codegen report run commands)
set(POGEAR_STAGE_USES_common "")
set(POGEAR_STAGE_USES_names common)
set(POGEAR_STAGE_USES_read names)
set(POGEAR_STAGE_USES_derive read)
set(POGEAR_STAGE_USES_engage derive)
set(POGEAR_STAGE_USES_specialize derive)
set(POGEAR_STAGE_USES_vibrate specialize)
set(POGEAR_STAGE_USES_codegen specialize)
set(POGEAR_STAGE_USES_report engage vibrate codegen)
set(POGEAR_STAGE_USES_run report)
set(POGEAR_STAGE_USES_commands run)
# The stages that include the build's configuration (build_config/build_config.hpp).
set(POGEAR_STAGES_WITH_BUILD_CONFIG codegen run commands)

# POGEAR_STAGE_ALLOWED_<stage>: the stage and every stage it builds on, directly or not.
foreach(stage IN LISTS POGEAR_STAGES)
  set(allowed ${stage})
  set(pending ${POGEAR_STAGE_USES_${stage}})
  while(pending)
    list(POP_FRONT pending next)
    if(NOT next IN_LIST allowed)
      list(APPEND allowed ${next})
      list(APPEND pending ${POGEAR_STAGE_USES_${next}})
    endif()
  endwhile()
  set(POGEAR_STAGE_ALLOWED_${stage} ${allowed})
endforeach()
