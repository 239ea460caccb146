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

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "csg/Scene.h"
#include "io/Model.h"

namespace viewer {

class ProbeJson {
public:
    ProbeJson(const io::Model& model, const csg::Scene& scene);

    // Appends the ray's JSON object (no newline) to out. d must be unit length. Allocates
    // nothing once out and ctx have grown to their largest size and the leaves the ray meets
    // have been written once. Safe to call from several threads at once.
    void append(std::string& out, const csg::Vec3& origin, const csg::Vec3& d,
                csg::QueryContext& ctx) const;

private:
    // A leaf's OBJECT text, formatted on its first use and kept, so writing a ray formats
    // numbers and nothing else. Not formatted up front: a chain of n nested modules has n
    // leaves whose module paths are O(n) long each.
    const std::string& leafObject(uint32_t leaf) const;

    const io::Model& model_;
    const csg::Scene& scene_;
    std::unique_ptr<std::once_flag[]> formatted_;   // per leaf
    mutable std::vector<std::string> leafObjects_;  // indexed by leaf
};

}  // namespace viewer
