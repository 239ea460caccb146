#include "viewer/window/Panel.h"

namespace viewer::window {

std::string panelText(const Panel& panel) {
    std::string text = panel.visible ? "visible: yes\n" : "visible: no\n";
    if (!panel.error.empty()) text += "error: " + panel.error + "\n";
    if (!panel.status.empty()) text += "status: " + panel.status + "\n";
    for (const std::string& line : panel.probe) text += "probe: " + line + "\n";
    return text;
}

}  // namespace viewer::window
