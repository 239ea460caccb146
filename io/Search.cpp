// OpenSCAD's search(match_value, string_or_vector, num_returns_per_match = 1,
// index_col_num = 0), as OpenSCAD 2021.01 defines it (func.cc, builtin_search):
//   number or other single value: the indices of the table entries equal to it (or whose
//       column index_col_num is), at most num_returns_per_match of them (0: all), as one list;
//   string: each of its characters is searched on its own, against the characters of a string
//       table or the first character of column index_col_num of a table of lists; with
//       num_returns_per_match = 1 the result is one index per character found (none for a
//       character not found), otherwise one list of indices per character;
//   list: each element is searched on its own like a number; with num_returns_per_match = 1
//       the result is one index per element ([] for an element not found), otherwise one list
//       of indices per element.
// OpenSCAD's warnings, word for word: "search term not found" for a character of a string
// found in no entry of a table that is not a string, and "Invalid entry in search vector" for
// an entry without the searched column (the search then gives []).
#include <cmath>

#include "io/Evaluator.h"

namespace io {

namespace {

// The code points of a UTF-8 string, each as its own bytes.
std::vector<std::string_view> codePointsOf(const std::string& s) {
    std::vector<std::string_view> out;
    for (size_t i = 0; i < s.size();) {
        size_t len = 1;
        while (i + len < s.size() && (static_cast<unsigned char>(s[i + len]) & 0xC0) == 0x80) ++len;
        out.emplace_back(s.data() + i, len);
        i += len;
    }
    return out;
}

// Argument i as OpenSCAD converts it to an unsigned int: `absent` when it is not given,
// 0 when it is not a non-negative number, at most 2^32 - 1.
size_t unsignedArg(const ArgValues& a, size_t i, size_t absent) {
    if (a.size() <= i) return absent;
    const Value& v = a[i].value;
    if (!v.isNumber() || !(v.number() >= 0)) return 0;
    return v.number() >= 4294967295.0 ? 4294967295u : static_cast<size_t>(v.number());
}

// The indices of table entries matching one value, collected as OpenSCAD does: with
// wanted == 1 the first index alone is appended to `single`; otherwise up to wanted
// (0: all) indices form one list appended to `out`.
class Collector {
public:
    Collector(size_t wanted, ValueList& out) : wanted_(wanted), out_(out) {}
    // Records index j; false when no more matches are wanted for this value.
    bool add(size_t j) {
        ++found_;
        if (wanted_ == 1) {
            out_.push_back(static_cast<double>(j));
            return false;
        }
        indices_.push_back(static_cast<double>(j));
        return !(wanted_ > 1 && found_ >= wanted_);
    }
    size_t found() const { return found_; }
    // Ends one searched value: its list of indices, unless one index per value is wanted.
    void finish() {
        if (wanted_ != 1) out_.push_back(Value(std::move(indices_)));
        indices_.clear();
        found_ = 0;
    }

private:
    size_t wanted_;
    ValueList& out_;
    ValueList indices_;
    size_t found_ = 0;
};

}  // namespace

Value builtinSearch(Evaluator& e, const ArgValues& a, Loc loc) {
    if (a.size() < 2) {
        e.warn(loc,
               "search() needs at least 2 arguments; expected search(match_value, "
               "string_or_vector, num_returns_per_match, index_col_num)");
        return Value();
    }
    const Value& find = a[0].value;
    const Value& table = a[1].value;
    // How many matches to return per searched value (0: all), and the column to compare.
    const size_t wanted = unsignedArg(a, 2, 1);
    const size_t column = unsignedArg(a, 3, 0);
    const ValueList noEntries;
    const ValueList& entries = table.isVector() ? table.list() : noEntries;
    ValueList out;
    Collector collect(wanted, out);

    // Whether entry j matches a single value: the entry itself (column 0 only), or its column.
    auto entryMatches = [&](const Value& value, const Value& entry) {
        WorkBudget b = e.budget();
        bool match = column == 0 && value.equals(entry, b);
        if (!match && entry.isVector() && column < entry.list().size())
            match = value.equals(entry.list()[column], b);
        e.settle(b, loc);
        return match;
    };

    if (find.isString()) {
        const auto characters = codePointsOf(find.string());
        // Each character of find against keys, one key per table entry. Against a table of
        // lists (or anything but a string), a character found nowhere is OpenSCAD's warning.
        auto searchCharacters = [&](const auto& keys, bool warnNotFound) {
            for (std::string_view c : characters) {
                e.spend(loc, keys.size());
                for (size_t j = 0; j < keys.size(); ++j)
                    if (keys[j] == c && !collect.add(j)) break;
                if (warnNotFound && collect.found() == 0)
                    e.warn(loc, "search term not found: \"" + std::string(c) + "\"");
                collect.finish();
            }
            return e.makeList(std::move(out), loc);
        };
        if (table.isString()) return searchCharacters(codePointsOf(table.string()), false);
        // Against a table of lists: the first character of each entry's column as str()
        // would print it. An entry without that column ends the search with [].
        std::vector<std::string> firsts;
        for (size_t j = 0; j < entries.size(); ++j) {
            const Value& entry = entries[j];
            if (!entry.isVector() || entry.list().size() <= column) {
                e.warn(loc, "Invalid entry in search vector at index " + std::to_string(j) +
                                ", required number of values in the entry: " +
                                std::to_string(column + 1) + ". Invalid entry: " + entry.brief());
                return ValueList{};
            }
            WorkBudget firstCharacters{8};  // enough to print the first character
            const std::string text = entry.list()[column].toString(firstCharacters);
            const auto cps = codePointsOf(text);
            firsts.emplace_back(cps.empty() ? std::string() : std::string(cps[0]));
        }
        return searchCharacters(firsts, true);
    }

    if (find.isVector()) {
        for (const Value& value : find.list()) {
            e.spend(loc, entries.size());
            for (size_t j = 0; j < entries.size(); ++j)
                if (entryMatches(value, entries[j]) && !collect.add(j)) break;
            if (wanted == 1 && collect.found() == 0) out.push_back(ValueList{});
            collect.finish();
        }
        return e.makeList(std::move(out), loc);
    }

    if (find.isNumber()) {
        // One flat list of indices, at most `wanted` of them.
        e.spend(loc, entries.size());
        size_t found = 0;
        for (size_t j = 0; j < entries.size(); ++j) {
            if (!entryMatches(find, entries[j])) continue;
            out.push_back(static_cast<double>(j));
            if (wanted != 0 && ++found >= wanted) break;
        }
        return e.makeList(std::move(out), loc);
    }
    // Anything else (undef, a bool, a range, a function) is undef, silently, as in OpenSCAD.
    return Value();
}

}  // namespace io
