#pragma once
// Scripts of `tessera view --script FILE`: input events replayed at frame numbers, so that
// every interaction can be tested and demonstrated without a person. One event a line:
//
//   FRAME key NAME [ctrl] [shift]        NAME: A..Z, 0..9, F1..F12, Delete, Escape, Space,
//                                        Left, Right, Up, Down, Home
//   FRAME drag left|middle X0 Y0 X1 Y1 [shift]
//   FRAME click X Y
//   FRAME wheel NOTCHES                  positive zooms in
//   FRAME resize W H
//   FRAME minimise | FRAME restore
//   FRAME screenshot PATH                the frame presented at FRAME, as PNG
//   FRAME save [PATH]                    the scene, as a scene file
//   FRAME exit
//   FRAME memory                         prints the resident memory, for leak checks
//   FRAME material preset NAME           the selected object's material, as the panel edits
//   FRAME material base_color|emissive R G B
//   FRAME material metallic|roughness X
//   FRAME light add                      a point light at the eye, as the panel's button
//   FRAME light N delete | position X Y Z | color R G B | intensity X
//                                        light N (0-based), as the panel's light list edits it
//   FRAME brdf classic|filament|blinn-phong    the panel's render options, as undoable edits
//   FRAME tonemap aces|reinhard|clamp
//   FRAME exposure EV                    -64..64
//   FRAME energy_compensation on|off
//   FRAME view shaded|normal|uv|triangle|object
//
// FRAME counts presented-or-skipped loop iterations from 0; frames never decrease from one line
// to the next. Positions are window pixels from the top left. '#' starts a comment.

#include <cstdint>
#include <string>
#include <vector>

#include "host/view_events.h"

namespace tessera {

struct ScriptEvent {
  uint64_t frame = 0;
  InputEvent event;
};

/// Parses a script's `text`; `file` names it in messages. Throws Error "FILE:LINE: what is
/// wrong" for an unknown event or key, a missing or extra value, a bad number or size, or a
/// frame smaller than the line before's.
std::vector<ScriptEvent> parse_view_script(const std::string& text, const std::string& file);

/// Reads and parses the script at `path`. Throws Error "script file 'PATH' not found" or
/// naming why it cannot be read, or as above.
std::vector<ScriptEvent> load_view_script(const std::string& path);

}  // namespace tessera
