// What the window's panel says, as plain text: the failed reload's error (top, red), the last
// click's probe (below it) and the status line (bottom). The panel is drawn over the picture
// when the window presents (PanelDrawing.h); the picture itself, which screenshots and the
// test dump save, never contains it.
#pragma once

#include <string>
#include <vector>

namespace viewer::window {

struct Panel {
    std::string error;               // "file:line:col: error: message"; empty: the part is good
    std::vector<std::string> probe;  // the last click's probe, one line each; empty: none yet
    std::string status;              // refinement level, rays per second, effects plan
    bool visible = true;             // H hides and shows the whole panel

    bool operator==(const Panel&) const = default;
};

// The panel as the test hook writes it: one "visible: yes|no" line, then "error: ...",
// "status: ..." and one "probe: ..." line per probe line, each present only when non-empty.
std::string panelText(const Panel& panel);

}  // namespace viewer::window
