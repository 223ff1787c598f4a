// What `pogear response` writes: per input-output pair a CSV of the frequency response and a Bode
// figure, and a summary of the resonance peaks for the terminal.
#pragma once

#include <string>
#include <vector>

#include "vibrate/frequency_response.hpp"

namespace pogear {

// "f [Hz],magnitude [UNIT],magnitude [dB],phase [deg]" and one row per frequency; the phase is
// unwrapped along the frequency axis, starting from (-180, 180] at the first frequency.
std::string response_csv(const TransferFunction& t);

// DIR/<scene>.response.<input>.<output>.csv and, with gnuplot, .svg (the rigid model's response
// dashed on top for an elastic scene). Returns the files written, in order.
std::vector<std::string> write_response_files(const std::string& scene_name, const std::vector<TransferFunction>& h,
                                              const std::string& dir);

// The resonance peaks of each pair, one line each.
std::string response_summary(const std::vector<TransferFunction>& h);

}  // namespace pogear
