// Reads a model file (TOML) into the gear's Topology (names/model.hpp), with the limits that keep
// hostile input bounded.
#pragma once

#include <string>

#include "names/model.hpp"

namespace pogear {

// Limits that keep hostile input bounded.
inline constexpr std::size_t max_model_file_bytes = 1 << 20;
// The closed forms grow like n^4 in size for a chain of stages (L1 of a chain of k stages is
// (k+1)^2 sums of O(k) terms of O(k) factors). 128 admits scripts/make_chain.sh's 40-stage chain
// in seconds (timings in docs/accuracy-vs-time.md); the paper's gears have 6 and 7 bodies.
inline constexpr std::size_t max_bodies = 128;
// Two meshes per body, as for planets between a sun and a ring (the 40-stage chain has 80).
inline constexpr std::size_t max_meshes = 256;
// Above what a gear at the body and mesh limits can name (an inertia and a friction per body, a
// stiffness and a damping per mesh, a radius per wheel, an axis distance per planet: at most
// 1408; the 40-stage chain names 562), and a bound on how deep parameters may refer to one another.
inline constexpr std::size_t max_parameters = 2048;
// `pogear ratios` looks at every set of engaged elements (2^k of them); automatic transmissions
// have 5 to 7 shift elements.
inline constexpr std::size_t max_friction_elements = 12;


// Reads a model file (TOML). Throws InputError for anything wrong, located in the file.
Topology parse_topology(const std::string& path);
// The same from text already in memory; `path` names it in messages.
Topology parse_topology_text(const std::string& text, const std::string& path);

}  // namespace pogear
