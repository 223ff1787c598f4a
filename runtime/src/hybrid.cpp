// libpogear_runtime: the hybrid engine of brakes and clutches (hybrid.hpp), compiled once.
#include "pogear/hybrid.ipp"
