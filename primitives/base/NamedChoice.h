// The choices an option names (a root solver, a polisher): the lookup by name, and the list of
// names an error message offers, from one table per choice: its `all` array and its name
// function.
#pragma once

#include <cstddef>
#include <cstring>
#include <string>

namespace csg {

// The member of `all` that nameOf spells `name`; false (out untouched) when there is none.
template <class E, size_t N, class NameOf>
bool choiceFromName(const char* name, const E (&all)[N], NameOf nameOf, E* out) {
    for (const E c : all)
        if (std::strcmp(name, nameOf(c)) == 0) {
            *out = c;
            return true;
        }
    return false;
}

// "\"a\", \"b\", \"c\"": every name of `all`, quoted, for a message.
template <class E, size_t N, class NameOf>
std::string choiceNames(const E (&all)[N], NameOf nameOf) {
    std::string names;
    for (const E c : all) names += std::string(names.empty() ? "\"" : ", \"") + nameOf(c) + "\"";
    return names;
}

}  // namespace csg
