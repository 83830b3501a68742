// UTF-8 in a TOML file is taken inside strings and comments and refused elsewhere with its line,
// before toml++ sees it (Debian's toml++ 3.3 reaches undefined behaviour on some such bytes).
#include <gtest/gtest.h>

#include <toml++/toml.h>

#include <string>

#include "roadload/toml_text.hpp"

namespace roadload::detail {
namespace {

using roadload::toml_quoted;

TEST(TomlText, Utf8InsideStringsAndCommentsIsTakenOutsideIsRefusedWithItsLine) {
  EXPECT_FALSE(non_ascii_outside_strings("cda_m2 = 6.2  # 5.5-7.0 m\u00b2\nname = \"Gr\u00f6\u00dfe\"\n"));
  EXPECT_FALSE(non_ascii_outside_strings("a = '\u00b0C'\nb = \"\"\"\nx \\\" \u00b5\n\"\"\"\nc = '''\u00e9\n'''\n"));
  EXPECT_EQ(non_ascii_outside_strings("a = 1\nb\u00e9 = 2\n"), 2);
  EXPECT_EQ(non_ascii_outside_strings("\xce\x83"), 1);
  EXPECT_EQ(non_ascii_outside_strings("a = \"x\\\"\" \u00e9\n"), 1) << "an escaped quote does not end the string";
  EXPECT_EQ(non_ascii_outside_strings("# a comment ends at its line\n\xef\xbb\xbb = 1\n"), 2);
}

// Whatever a name or path holds, the quoted string reads back as itself.
TEST(TomlText, AQuotedStringReadsBackAsItselfWhateverItHolds) {
  std::string every;
  for (int c = 1; c < 0x80; ++c) every += static_cast<char>(c);
  for (const std::string& s :
       {every, std::string("C:\\trucks\\\"FD1\".toml"), std::string("Gr\u00f6\u00dfe m\u00b2"), std::string()}) {
    auto doc = toml::parse("v = " + toml_quoted(s) + "\n");
    ASSERT_TRUE(static_cast<bool>(doc)) << toml_quoted(s);
    EXPECT_EQ(doc["v"].value<std::string>(), s);
  }
  EXPECT_EQ(toml_quoted("plain"), "\"plain\"");
}

}  // namespace
}  // namespace roadload::detail
