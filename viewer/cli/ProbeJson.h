// The JSON form of one probed ray, shared by `csgray probe` and `csgray probe --rays`:
//
//   {"ray": {"origin": [x,y,z], "dir": [x,y,z]},
//    "spans": [{"in": END, "out": END}, ...]}
//   END = {"t": distance, "point": [x,y,z], "normal": [x,y,z], "object": OBJECT}
//   OBJECT = {"leaf": index, "primitive": "cube", "module": "part() > cube",
//             "source": "file:line:col"}
//
// dir is unit length, so t is a distance along the ray. Spans are clipped to t >= 0: a ray
// that starts inside the solid has a first span whose "in" is {"t": 0, "inside": true,
// "normal": null, ...}; a span that never ends (a half-space) has an "out" with
// "unbounded": true and null t, point and normal. Numbers that are not finite print as null.
#pragma once

#include <string>
#include <vector>

#include "csg/Scene.h"
#include "io/Model.h"

namespace viewer {

class ProbeJson {
public:
    // Caches each leaf's OBJECT text, so writing a ray formats numbers and nothing else.
    ProbeJson(const io::Model& model, const csg::Scene& scene);

    // Appends the ray's JSON object (no newline) to out. d must be unit length. Allocates
    // nothing once out and ctx have grown to their largest size.
    void append(std::string& out, const csg::Vec3& origin, const csg::Vec3& d,
                csg::QueryContext& ctx) const;

private:
    const csg::Scene& scene_;
    std::vector<std::string> leafObjects_;  // indexed by leaf
};

}  // namespace viewer
