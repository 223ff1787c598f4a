# Registers the `consumer_package` test: install this build, then build and run a user project
# (this directory's CMakeLists.txt) against the installation. Included from tests/CMakeLists.txt.
# The consumer compiles at -O1 whatever this build's flags: the test checks the installed package
# (find_package, pogear_add_simulator, linking, the CSV), not the simulator's speed, and its two
# simulators, one header-only with every solver, take about three times as long at -O3 (the
# longest test of the suite; instrumented at -O3, five minutes). Optimization flags do not change
# the ABI the package checks.
add_test(NAME consumer_package
  COMMAND "${CMAKE_COMMAND}"
    "-DPOGEAR_BUILD_DIR=${PROJECT_BINARY_DIR}"
    "-DPOGEAR_CONFIG=$<CONFIG>"
    "-DCONSUMER_SOURCE_DIR=${CMAKE_CURRENT_LIST_DIR}"
    "-DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/consumer_package"
    "-DSCENE=${PROJECT_SOURCE_DIR}/models/scenes/paper_one_stage.toml"
    # The scene samples 2 s at 1 ms: rows at 0, 1, ..., 2000 ms.
    -DEXPECTED_CSV=paper_one_stage.csv
    -DEXPECTED_ROWS=2001
    "-DGENERATOR=${CMAKE_GENERATOR}"
    "-DCXX_COMPILER=${CMAKE_CXX_COMPILER}"
    "-DCONSUMER_OPT_FLAGS=-O1 -DNDEBUG"
    -P "${CMAKE_CURRENT_LIST_DIR}/run_consumer_test.cmake")
# Installing needs pogear built first (ctest does not build); the consumer compiles an Eigen-heavy
# simulator (~15 s), hence the generous timeout.
set_tests_properties(consumer_package PROPERTIES LABELS consumer TIMEOUT 600)

# A renamed scene leaves no header of its old name behind for a program to compile against.
add_test(NAME simulator_stale_outputs
  COMMAND "${CMAKE_COMMAND}" "-DPOGEAR=$<TARGET_FILE:pogear>"
    "-DSCRIPT=${PROJECT_SOURCE_DIR}/cmake/pogear_generate_simulator.cmake"
    "-DSCENE=${PROJECT_SOURCE_DIR}/models/scenes/paper_one_stage.toml"
    "-DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/simulator_stale_outputs"
    -P "${CMAKE_CURRENT_LIST_DIR}/stale_outputs_test.cmake")
set_tests_properties(simulator_stale_outputs PROPERTIES LABELS consumer)
