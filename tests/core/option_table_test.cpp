// The option-table mechanism: parsing with one wording, ranges, flags, defaults, validation and the
// checkpoint value list (core/option_table.h).
#include "core/option_table.h"

#include <gtest/gtest.h>

namespace phos::options {
namespace {

struct Inner {
    unsigned count = 5;
};
enum class Mode { A, B, Unnamed };
struct Demo {
    float alpha = 0.7f;
    int n = 3;
    uint64_t big = 0;
    bool on = true;
    Mode mode = Mode::A;
    Inner inner;
};

Table demo_table() {
    TableBuilder<Demo> b("Demo", "a demo");
    b.number("alpha", &Demo::alpha, "A", Range{0, 1, true, false}, "alpha");
    b.number("n", &Demo::n, "N", between(1, 10), "n").effect = Effect::Budget;
    b.number("big", &Demo::big, "N", at_least(0), "big").pbrt = "bignumber";
    b.flag("no-on", &Demo::on, "turn off", false).effect = Effect::None;
    b.choice("mode", &Demo::mode, {{Mode::A, "a"}, {Mode::B, "b"}}, "mode");
    b.number(
        "count", [](auto& d) -> auto& { return d.inner.count; }, "C", between(1, 100), "nested");
    return b.build();
}

std::string set_error(const Table& t, Demo& d, const std::string& name, const std::vector<std::string>& v) {
    try {
        t.find(name)->set(&d, v);
    } catch (const ValueError& e) {
        return option_error(*t.find(name), e.what());
    }
    return "";
}

TEST(OptionTable, SetsFieldsThroughTheTable) {
    const Table t = demo_table();
    Demo d;
    t.find("alpha")->set(&d, {"0.25"});
    t.find("n")->set(&d, {"7"});
    t.find("big")->set(&d, {"18446744073709551615"});
    t.find("no-on")->set(&d, {"false"});
    t.find("mode")->set(&d, {"b"});
    t.find("count")->set(&d, {"42"});
    EXPECT_EQ(d.alpha, 0.25f);
    EXPECT_EQ(d.n, 7);
    EXPECT_EQ(d.big, 18446744073709551615ull);
    EXPECT_FALSE(d.on);
    EXPECT_EQ(d.mode, Mode::B);
    EXPECT_EQ(t.find("mode")->get(&d), "b");
    EXPECT_EQ(d.inner.count, 42u);
    EXPECT_EQ(t.find("big")->get(&d), "18446744073709551615");
    EXPECT_EQ(t.find_pbrt("bignumber"), t.find("big"));
}

TEST(OptionTable, OneWordingForBadValues) {
    const Table t = demo_table();
    Demo d;
    EXPECT_EQ(set_error(t, d, "alpha", {"0"}), "--alpha: 0 is not in (0, 1]");
    EXPECT_EQ(set_error(t, d, "alpha", {"1.5"}), "--alpha: 1.5 is not in (0, 1]");
    EXPECT_EQ(set_error(t, d, "alpha", {"abc"}), "--alpha: 'abc' is not a number");
    EXPECT_EQ(set_error(t, d, "alpha", {"nan"}), "--alpha: 'nan' is not a finite number");
    EXPECT_EQ(set_error(t, d, "n", {"2.5"}), "--n: '2.5' is not a whole number");
    EXPECT_EQ(set_error(t, d, "n", {"11"}), "--n: 11 is not in [1, 10]");
    EXPECT_EQ(set_error(t, d, "big", {"-1"}), "--big: -1 is negative");
    EXPECT_EQ(set_error(t, d, "mode", {"c"}), "--mode: 'c' is not one of a|b");
    EXPECT_EQ(set_error(t, d, "count", {"0"}), "--count: 0 is not in [1, 100]");
    // A refused value leaves the field as it was.
    EXPECT_EQ(d.alpha, 0.7f);
    EXPECT_EQ(d.n, 3);
}

TEST(OptionTable, DefaultsComeFromTheStruct) {
    const Table t = demo_table();
    EXPECT_EQ(t.default_text(*t.find("alpha")), "0.7");
    EXPECT_EQ(t.default_text(*t.find("n")), "3");
    EXPECT_EQ(t.default_text(*t.find("no-on")), "off");  // the switch is off: `on` stays true
    EXPECT_EQ(t.default_text(*t.find("count")), "5");
    EXPECT_EQ(t.default_text(*t.find("mode")), "a");
}

// A word-valued option stores the value its word stands for, lists the words in help and docs
// ("a|b"), and refuses a stored value that has no word.
TEST(OptionTable, ChoicesAreTyped) {
    const Table t = demo_table();
    const Option& mode = *t.find("mode");
    EXPECT_EQ(mode.value_name, "NAME");
    EXPECT_EQ(mode.range_text, "a|b");
    Demo d;
    EXPECT_EQ(set_error(t, d, "mode", {"B"}), "--mode: 'B' is not one of a|b");
    EXPECT_EQ(d.mode, Mode::A);
    d.mode = Mode::Unnamed;
    try {
        validate(t, &d);
        FAIL() << "no error";
    } catch (const ValueError& e) {
        EXPECT_STREQ(e.what(), "--mode: 2 is not one of a|b");
    }
    const Choices<Mode> choices{{Mode::A, "a"}, {Mode::B, "b"}};
    EXPECT_EQ(parse_choice(choices, "b"), Mode::B);
    EXPECT_EQ(choice_name(choices, Mode::A), "a");
    EXPECT_EQ(choice_list(choices), "a|b");
}

TEST(OptionTable, ValidateNamesTheFirstBadField) {
    const Table t = demo_table();
    Demo d;
    EXPECT_NO_THROW(validate(t, &d));
    d.inner.count = 0;
    try {
        validate(t, &d);
        FAIL() << "no error";
    } catch (const ValueError& e) {
        EXPECT_STREQ(e.what(), "--count: 0 is not in [1, 100]");
    }
}

TEST(OptionTable, ValuesListsOptionsByEffect) {
    const Table t = demo_table();
    Demo d;
    d.alpha = 0.5f;
    const auto image = values(t, &d, Effect::Image);
    ASSERT_EQ(image.size(), 4u);  // alpha, big, mode, count
    EXPECT_EQ(image[0], (std::pair<std::string, std::string>{"--alpha", "0.5"}));
    const auto budget = values(t, &d, Effect::Budget);
    ASSERT_EQ(budget.size(), 1u);
    EXPECT_EQ(budget[0].first, "--n");
}

// An option's integrators are a set of their numbers: values() for one integrator leaves out the
// options of others.
TEST(OptionTable, AppliesToASetOfIntegrators) {
    Table t = demo_table();
    Option& alpha = t.options[0];
    EXPECT_TRUE(alpha.applies(0) && alpha.applies(31));  // empty: every integrator
    alpha.applies_to.bits = 0b101;                       // integrators 0 and 2
    EXPECT_TRUE(alpha.applies(0));
    EXPECT_FALSE(alpha.applies(1));
    EXPECT_TRUE(alpha.applies(2));
    EXPECT_FALSE(alpha.applies(40));
    Demo d;
    EXPECT_EQ(values(t, &d, Effect::Image, 1u).size(), 3u);  // big, mode, count
    EXPECT_EQ(values(t, &d, Effect::Image, 2u).size(), 4u);
    EXPECT_EQ(values(t, &d, Effect::Image).size(), 4u);
}

TEST(OptionTable, NumbersPrintShortestRoundTrip) {
    EXPECT_EQ(format_number(0.7f, true), "0.7");
    EXPECT_EQ(format_number(0.1), "0.1");
    EXPECT_EQ(format_number(200000), "200000");
    EXPECT_EQ(format_number(-3), "-3");
    EXPECT_EQ(std::stod(format_number(1.0 / 3.0)), 1.0 / 3.0);
}

TEST(OptionTable, RangesPrintTheirEnds) {
    EXPECT_EQ(between(1, 8).text(), "[1, 8]");
    EXPECT_EQ(positive().text(), "(0, inf)");
    EXPECT_EQ(at_least(0).text(), "[0, inf)");
    EXPECT_TRUE(positive().contains(1e-30));
    EXPECT_FALSE(positive().contains(0));
}

}  // namespace
}  // namespace phos::options
