// `pogear modes` and `pogear response` as library functions: the file read, the analysis asked
// for, and what is wrong with the request as an InputError located in the file or command line.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vibrate/campbell.hpp"
#include "vibrate/frequency_response.hpp"
#include "vibrate/vibration_modes.hpp"

namespace pogear {

// A scene file names its model (`model = "..."`); a model file does not.
bool is_scene_file(const std::string& path);

// Modes of a model file (every damping it defines) or of a scene (its parameters and the damping
// its effects call for), with the brakes and clutches `engaged` names ("B1,C2") stuck and the
// others open. A rigid scene has no elastic modes and is refused.
VibrationModes modes_of_file(const std::string& path, const std::optional<std::string>& engaged = std::nullopt);

// `pogear modes ... --campbell FILE`: the operating line and the speed axis, as the user wrote them.
struct CampbellRequest {
  std::string input;                  // the input body
  std::optional<std::string> hold;    // bodies held at rest, comma-separated, as given
  std::optional<std::string> to;      // the highest input speed, e.g. "6000*rpm"; none: from the modes
  int harmonics = 3;
};

// The modes of modes_of_file and, along the request's operating line, the Campbell diagram.
struct ModesWithCampbell {
  VibrationModes modes;
  CampbellDiagram campbell;
};
ModesWithCampbell campbell_of_file(const std::string& path, const std::optional<std::string>& engaged,
                                   const CampbellRequest& request);

struct ResponseRequest {
  std::string scene_file;
  std::vector<std::string> inputs, outputs;  // tau_<body>; omega_<body>, F_<mesh> or T_<shaft>
  std::string from = "1*Hz", to = "10*kHz";   // quantities with units
  int points = 1000;
  std::optional<std::string> engaged;         // brakes and clutches stuck, comma-separated
};
struct SceneResponse {
  std::string scene_name;
  std::vector<TransferFunction> pairs;  // input-major
  std::vector<std::string> open_in_scene;  // the scene's brakes and clutches, open in the response
};
SceneResponse response_of(const ResponseRequest& request);

// "warning: the scene's brakes and clutches (...) are open in these modes: ..." for the elements a
// scene commands that an analysis leaves open ("" when none); `what` is "modes" or "responses".
std::string open_elements_warning(const std::vector<std::string>& open, std::string_view what);

}  // namespace pogear
