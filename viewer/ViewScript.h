// `bundlelab view --script FILE`: a camera path and key presses, one command per line (# starts a
// comment), run in order, for tests and for recording:
//   pose PX PY PZ TX TY TZ [UX UY UZ]   camera position, target (and up), in file coordinates
//   key NAME                            a key press: L, SHIFT+L, EQUAL, MINUS, C, P, O, R, SPACE, TAB, ...
//   drag DX DY [right]                  a mouse drag of DX, DY pixels (left button unless `right`)
//   scroll STEPS                        the mouse wheel
//   set KEY=VALUE                       change a mode setting, as the keys do (checked the same way)
//   iterate N                           run until the estimate holds N iterations
//   frames N                            show N more frames (each one iteration, or a played frame)
//   screenshot PATH.exr                 the estimate as `render` writes it (EXR, PNG, JSON) and the
//                                       window as shown (PATH.view.png)
//   quit                                close the window
// Errors name the file, the line and the value.
#pragma once

#include <string>
#include <vector>

namespace bl::viewer {

struct ScriptCommand {
    std::string verb;            // pose, key, drag, scroll, set, iterate, frames, screenshot, quit
    std::vector<double> numbers; // pose: 6 or 9; drag: 2; scroll: 1; iterate, frames: 1
    std::string text;            // key name, KEY=VALUE, the screenshot's path
    bool right = false;          // drag with the right button
    int line = 0;
};

std::vector<ScriptCommand> loadViewScript(const std::string& path);

} // namespace bl::viewer
