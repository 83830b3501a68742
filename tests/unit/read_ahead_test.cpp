// A recording read a batch ahead on a thread of its own hands out what the reader alone gives, in
// the same order, with the interface names and the errors of the lines read.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "roadload/recording/read_ahead.hpp"
#include "roadload/recording/reader.hpp"
#include "scratch.hpp"

namespace roadload::recording {
namespace {

namespace fs = std::filesystem;

class ReadAheadFolder : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratch_path("roadload-ahead", std::string("-") + testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  fs::path dir_;
};

// Several batches of frames; a second bus appears late, a bad line sits in the middle.
std::string can_log(int frames) {
  std::string text;
  for (int i = 0; i < frames; ++i) {
    const char* iface = i >= 3000 && i % 2 == 0 ? "can1" : "can0";
    char line[96];
    std::snprintf(line, sizeof line, "(%010d.%06d) %s 18FEF1%02X#%016X\n", 1700000000 + i / 100, (i % 100) * 10000, iface, i % 256,
                  static_cast<unsigned>(i));
    text += line;
    if (i == 2500) text += "(1700000025.000000) can0 18FEF1XY#00\n";
  }
  return text;
}

struct Seen {
  std::int64_t t_ns;
  std::uint32_t id;
  std::string iface;
  std::uint64_t data;
};

Seen seen(const Record& r, const InterfaceTable& ifaces) {
  const auto& f = std::get<CanFrame>(r);
  std::uint64_t data = 0;
  for (std::size_t i = 0; i < f.len; ++i) data = data << 8 | f.data[i];
  return {to_ns(f.t), f.id, std::string(ifaces.name(f.iface)), data};
}

TEST_F(ReadAheadFolder, HandsOutWhatTheReaderGivesInOrder) {
  std::ofstream(dir_ / "can.log") << can_log(5000);
  auto direct = RecordingReader::open(dir_.string(), kCanStream);
  auto ahead_reader = RecordingReader::open(dir_.string(), kCanStream);
  ASSERT_TRUE(direct && ahead_reader);
  std::vector<Seen> expected;
  while (const Record* r = direct.value().next()) expected.push_back(seen(*r, direct.value().interfaces()));
  ASSERT_EQ(expected.size(), 5000u);
  ASSERT_EQ(expected.back().iface, "can0");
  ASSERT_EQ(expected[3000].iface, "can1");

  ReadAhead ahead(ahead_reader.value());
  std::size_t i = 0;
  while (const Record* r = ahead.next()) {
    ASSERT_LT(i, expected.size());
    const Seen s = seen(*r, ahead.interfaces());
    EXPECT_EQ(s.t_ns, expected[i].t_ns) << "record " << i;
    EXPECT_EQ(s.id, expected[i].id) << "record " << i;
    EXPECT_EQ(s.iface, expected[i].iface) << "record " << i;
    EXPECT_EQ(s.data, expected[i].data) << "record " << i;
    ++i;
  }
  EXPECT_EQ(i, expected.size());
  EXPECT_EQ(ahead.next(), nullptr);
  ASSERT_EQ(ahead_reader.value().errors().count(), 1u);
  EXPECT_EQ(ahead_reader.value().errors().kept().front().line, 2502);
  EXPECT_EQ(ahead_reader.value().errors().kept().front().field, "identifier");
}

TEST_F(ReadAheadFolder, StopsWhenLeftBeforeTheEnd) {
  std::ofstream(dir_ / "can.log") << can_log(20000);
  auto reader = RecordingReader::open(dir_.string(), kCanStream);
  ASSERT_TRUE(reader);
  {
    ReadAhead ahead(reader.value());
    for (int i = 0; i < 10; ++i) ASSERT_NE(ahead.next(), nullptr);
  }  // joins its thread, which is waiting for room or still reading
  SUCCEED();
}

TEST_F(ReadAheadFolder, AnEmptyLogEndsAtOnce) {
  std::ofstream(dir_ / "can.log") << "";
  auto reader = RecordingReader::open(dir_.string(), kCanStream);
  ASSERT_TRUE(reader);
  ReadAhead ahead(reader.value());
  EXPECT_EQ(ahead.next(), nullptr);
  EXPECT_EQ(ahead.next(), nullptr);
}

}  // namespace
}  // namespace roadload::recording
