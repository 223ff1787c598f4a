// libpogear_runtime: the size-independent part of every simulator's run (run_support.hpp), compiled once.
#include "pogear/run_support.ipp"
