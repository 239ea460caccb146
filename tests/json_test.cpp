// primitives/base/Json.h: the writer every JSON output of the command line goes through.
#include "primitives/base/Json.h"

#include <gtest/gtest.h>

#include <limits>

namespace csg {
namespace {

TEST(JsonWriter, CommasGoBetweenMembersAndElementsOnly) {
    std::string out;
    JsonWriter json(out);
    json.beginObject()
        .key("a")
        .value(1)
        .key("b")
        .beginArray()
        .value(1.5)
        .beginObject()
        .endObject()
        .beginArray()
        .endArray()
        .endArray()
        .key("c")
        .beginObject()
        .key("d")
        .value(true)
        .endObject()
        .endObject();
    EXPECT_EQ(out, R"({"a":1,"b":[1.5,{},[]],"c":{"d":true}})");
}

TEST(JsonWriter, NonFiniteNumbersAreNullAndNegativeZeroIsZero) {
    std::string out;
    JsonWriter json(out);
    json.beginArray()
        .value(std::numeric_limits<double>::infinity())
        .value(-std::numeric_limits<double>::infinity())
        .value(std::numeric_limits<double>::quiet_NaN())
        .value(-0.0)
        .endArray();
    EXPECT_EQ(out, "[null,null,null,0]");
}

TEST(JsonWriter, NumbersRoundTripExactly) {
    std::string out;
    JsonWriter json(out);
    const double x = 0.1 + 0.2;
    json.value(x);
    EXPECT_EQ(std::stod(out), x);
}

TEST(JsonWriter, StringsAreEscaped) {
    std::string out;
    JsonWriter json(out);
    json.value(std::string_view("q\"b\\n\n\t\x01 \xc3\xa9", 11));
    EXPECT_EQ(out, "\"q\\\"b\\\\n\\n\\t\\u0001 \xc3\xa9\"");
}

}  // namespace
}  // namespace csg
