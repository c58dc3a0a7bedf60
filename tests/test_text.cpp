// Text from users and files, read one way everywhere (include/packbed/text.hpp), and the
// named choices (include/packbed/registry.hpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <gtest/gtest.h>

#include "packbed/error.hpp"
#include "packbed/lammps_engine.hpp"
#include "packbed/lattice.hpp"
#include "packbed/openfoam.hpp"
#include "packbed/read.hpp"
#include "packbed/registry.hpp"
#include "packbed/sizes.hpp"
#include "packbed/soft_sphere.hpp"
#include "packbed/surface.hpp"
#include "packbed/text.hpp"

using namespace packbed;

TEST(Text, TrimTakesEveryKindOfWhiteSpaceFromBothEndsOnly) {
    EXPECT_EQ(trim(" \t\r\n\v\fa b\t\r\n"), "a b");
    EXPECT_EQ(trim("a"), "a");
    EXPECT_EQ(trim(" \t "), "");
    EXPECT_EQ(trim(""), "");
}

TEST(Text, SplitKeepsEmptyPartsSplitSpacesDropsThem) {
    EXPECT_EQ(split("a,,b", ','), (std::vector<std::string_view>{"a", "", "b"}));
    EXPECT_EQ(split("", ','), (std::vector<std::string_view>{""}));
    EXPECT_EQ(split("a,", ','), (std::vector<std::string_view>{"a", ""}));
    EXPECT_EQ(split_spaces("  x\t y \n"), (std::vector<std::string_view>{"x", "y"}));
    EXPECT_TRUE(split_spaces(" \t ").empty());
}

TEST(Text, ANumberIsTheWholeTextInFromCharsSyntax) {
    EXPECT_EQ(parse_number("1.5e-3"), 1.5e-3);
    EXPECT_EQ(parse_number("-0.25"), -0.25);
    EXPECT_TRUE(std::isinf(*parse_number("inf")));
    EXPECT_TRUE(std::isnan(*parse_number("nan")));
    for (const char* bad : {"", "+1", " 1", "1 ", "1,5", "1.5x", "0x10", "1e999", "e5", "-"})
        EXPECT_FALSE(parse_number(bad).has_value()) << "'" << bad << "'";
    EXPECT_EQ(parse_finite("2.5"), 2.5);
    for (const char* bad : {"inf", "-inf", "nan", "1e999", ""})
        EXPECT_FALSE(parse_finite(bad).has_value()) << "'" << bad << "'";
}

TEST(Text, AWholeNumberFitsItsTypeOrIsNone) {
    EXPECT_EQ(parse_whole<std::uint64_t>("18446744073709551615"),
              std::numeric_limits<std::uint64_t>::max());
    EXPECT_FALSE(parse_whole<std::uint64_t>("18446744073709551616").has_value()); // 2^64
    EXPECT_FALSE(parse_whole<std::uint64_t>("-1").has_value());
    EXPECT_EQ(parse_whole<long long>("-1"), -1);
    for (const char* bad : {"", "+1", "1.0", "1e3", " 7", "7 ", "0x7"})
        EXPECT_FALSE(parse_whole<long long>(bad).has_value()) << "'" << bad << "'";
}

TEST(Text, AListIsFiniteNumbersAndNothingElse) {
    EXPECT_EQ(parse_finite_list("1,2.5,-3"), (std::vector<double>{1.0, 2.5, -3.0}));
    EXPECT_EQ(parse_finite_list("4 5", ' '), (std::vector<double>{4.0, 5.0}));
    for (const char* bad : {"", "1,", ",1", "1,,2", "1,inf", "1;2", "1, 2"})
        EXPECT_FALSE(parse_finite_list(bad).has_value()) << "'" << bad << "'";
}

TEST(Text, ASpecIsItsKindAndWhatFollowsTheFirstColon) {
    const KindSpec caps = split_kind("caps:0.01");
    EXPECT_EQ(caps.kind, "caps");
    EXPECT_EQ(caps.parameters, "0.01");
    const KindSpec discrete = split_kind("discrete:1:0.5,2:0.5");
    EXPECT_EQ(discrete.kind, "discrete");
    EXPECT_EQ(discrete.parameters, "1:0.5,2:0.5");
    const KindSpec none = split_kind("none");
    EXPECT_EQ(none.kind, "none");
    EXPECT_FALSE(none.parameters.has_value());
    const KindSpec empty = split_kind("box:");
    EXPECT_EQ(empty.kind, "box");
    EXPECT_EQ(empty.parameters, "");
}

namespace {

enum class Colour { red, green, blue };

template <class T> void round_trips(const Registry<T>& registry) {
    std::vector<std::string> seen;
    for (const auto& [name, value] : registry) {
        const auto found = registry.find(name);
        ASSERT_TRUE(found.has_value()) << registry.option() << " " << name;
        EXPECT_TRUE(*found == value) << registry.option() << " " << name;
        EXPECT_EQ(registry.name(value), name) << registry.option();
        EXPECT_EQ(std::count(seen.begin(), seen.end(), name), 0) << registry.option() << name;
        seen.push_back(name);
    }
    EXPECT_EQ(registry.names(), seen);
    EXPECT_FALSE(registry.find("").has_value());
}

} // namespace

TEST(Registry, NamesValuesAndTheOneRefusal) {
    const Registry<Colour> colours("colour", {{"red", Colour::red}, {"green", Colour::green}});
    EXPECT_EQ(colours.at("green"), Colour::green);
    EXPECT_EQ(colours.name(Colour::red), "red");
    EXPECT_EQ(colours.name(Colour::blue), "unknown");
    EXPECT_FALSE(colours.find("Red").has_value()); // names are exact
    EXPECT_EQ(colours.allowed(), "red, green");
    try {
        colours.at("blue\n");
        ADD_FAILURE() << "no refusal";
    } catch (const InvalidInput& e) {
        EXPECT_STREQ(e.what(), "--colour: 'blue\\n' is not allowed; allowed: red, green");
    }
}

TEST(Registry, EveryNamedChoiceOfTheProductRoundTrips) {
    round_trips(solvers());
    round_trips(update_orders());
    round_trips(engines());
    round_trips(lattice_types());
    round_trips(lattice_keeps());
    round_trips(size_kinds());
    round_trips(fraction_bases());
    round_trips(contact_treatments());
    round_trips(turbulence_models());
    round_trips(particle_formats());
    EXPECT_EQ(particle_formats().at("auto"), std::nullopt);
    EXPECT_EQ(solvers().at("fire"), Solver::fire);
}
