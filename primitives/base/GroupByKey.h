// The counting sort: values grouped by a small integer key, each group in the order its values
// were given. What a mesh's edges, corners and triangles by vertex, a triangle's links and a grid's
// cells are built by.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace csg {

template <class T>
struct Grouped {
    std::vector<uint32_t> start;  // group k is values[start[k], start[k + 1])
    std::vector<T> values;
};

// forEach(emit) calls emit(key, value) for every value, key < keys. It is run twice, to count
// and then to place, so it must emit the same sequence both times.
template <class T, class ForEach>
Grouped<T> groupByKey(size_t keys, ForEach&& forEach) {
    Grouped<T> g;
    g.start.assign(keys + 1, 0);
    forEach([&](size_t key, const T&) { ++g.start[key + 1]; });
    for (size_t k = 0; k < keys; ++k) g.start[k + 1] += g.start[k];
    g.values.resize(g.start[keys]);
    std::vector<uint32_t> next(g.start.begin(), g.start.end() - 1);
    forEach([&](size_t key, const T& value) { g.values[next[key]++] = value; });
    return g;
}

}  // namespace csg
