#pragma once
// The check of one enum's {value, "name"} table (core/enum_names.hpp): every name unique and
// snake_case, every value once, name_of and enum_from_name inverse to each other.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <string_view>

#include "flexgait/core/enum_names.hpp"

namespace flexgait::testing {

template <NamedEnum E>
void expect_enum_table_round_trips() {
  std::set<std::string_view> names;
  std::set<E> values;
  for (const auto& e : enum_names(E{})) {
    SCOPED_TRACE(std::string(e.name));
    EXPECT_TRUE(names.insert(e.name).second) << "a name twice";
    EXPECT_TRUE(values.insert(e.value).second) << "a value twice";
    EXPECT_FALSE(e.name.empty());
    EXPECT_EQ(e.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_"), std::string_view::npos)
        << "not snake_case";
    EXPECT_EQ(name_of(e.value), e.name);
    EXPECT_EQ(enum_from_name<E>(e.name), e.value);
  }
  EXPECT_FALSE(enum_from_name<E>("no such name").has_value());
}

}  // namespace flexgait::testing
