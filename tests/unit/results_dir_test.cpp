// A results folder read back for the report: cells.csv's numbers (NaN where a cell has none),
// its text columns, the PSD files by group, and errors naming file, line and column.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "roadload/results/results_dir.hpp"

namespace roadload::results {
namespace {

namespace fs = std::filesystem;

fs::path results_folder(const char* tag, const std::string& cells) {
  const fs::path d = fs::temp_directory_path() / ("roadload-results-" + std::to_string(::getpid()) + "-" + tag);
  fs::remove_all(d);
  fs::create_directories(d);
  std::ofstream(d / "cells.csv") << cells;
  std::ofstream(d / "trip.json") << "{\"crr\": 0.006}\n";
  std::ofstream(d / "psd.csv") << "freq_hz,TLR2,TLF1\n0,1e-3,2e-3\n1.5,4e-3,nan\n";
  std::ofstream(d / "psd-concrete-4.6m.csv") << "freq_hz,TLR2\n0,1\n";
  std::ofstream(d / "psd-spatial-concrete-4.6m.csv") << "cycles_per_m,TLR2\n0,1\n";
  return d;
}

TEST(ResultsDir, ReadsCellsTripAndSpectra) {
  const fs::path d = results_folder("ok", "cell,start_m,crr,reason\n1,0,0.0061,\n2,100,nan,no usable samples\n3,200,,\n");
  const auto r = read_results_dir(d.string());
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  const NumberTable& cells = r.value().cells;
  ASSERT_EQ(cells.rows(), 3u);
  EXPECT_EQ(cells.text(0, *cells.column("cell")), "1");
  EXPECT_EQ(cells.text(1, *cells.column("reason")), "no usable samples");
  const std::vector<double> crr = cells.values("crr");
  EXPECT_DOUBLE_EQ(crr[0], 0.0061);
  EXPECT_TRUE(std::isnan(crr[1]));
  EXPECT_TRUE(std::isnan(crr[2]));
  EXPECT_DOUBLE_EQ(*r.value().trip.number_at("crr"), 0.006);
  ASSERT_EQ(r.value().spectra.size(), 2u);
  EXPECT_EQ(r.value().spectra[0].group, "trip");
  EXPECT_EQ(r.value().spectra[1].group, "concrete-4.6m");
  const Spectrum& trip = r.value().spectra[0];
  EXPECT_EQ(trip.sensors, (std::vector<std::string>{"TLR2", "TLF1"}));
  EXPECT_DOUBLE_EQ(trip.x[1], 1.5);
  EXPECT_DOUBLE_EQ(trip.psd[0][1], 4e-3);
  EXPECT_TRUE(std::isnan(trip.psd[1][1]));
  fs::remove_all(d);
}

// Reasons hold commas and quotes: the writer quotes them (RFC 4180), and every reader must too.
TEST(ResultsDir, QuotedFieldsKeepTheirCommasAndQuotes) {
  const fs::path d = results_folder("quoted",
                                    "cell,crr,reason\n1,nan,\"not identified: 12 updates, mean NIS 0.4\"\n"
                                    "2,nan,\"the \"\"model\"\", as said\"\n3,0.006,\n");
  const auto r = read_results_dir(d.string());
  ASSERT_TRUE(r.ok()) << r.error().to_string();
  const NumberTable& cells = r.value().cells;
  ASSERT_EQ(cells.rows(), 3u);
  EXPECT_EQ(cells.text(0, *cells.column("reason")), "not identified: 12 updates, mean NIS 0.4");
  EXPECT_EQ(cells.text(1, *cells.column("reason")), "the \"model\", as said");
  EXPECT_EQ(cells.text(2, *cells.column("reason")), "");
  EXPECT_DOUBLE_EQ(cells.values("crr")[2], 0.006);
  fs::remove_all(d);
}

TEST(ResultsDir, AnOpenQuoteNamesFileAndLine) {
  const fs::path d = results_folder("open-quote", "cell,crr,reason\n1,nan,\"cut, short\n");
  const auto r = read_results_dir(d.string());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().file, (d / "cells.csv").string());
  EXPECT_EQ(r.error().line, 2);
  EXPECT_NE(r.error().message.find("quoted field"), std::string::npos) << r.error().message;
  fs::remove_all(d);
}

TEST(ResultsDir, ABadNumberNamesFileLineAndColumn) {
  const fs::path d = results_folder("bad", "cell,start_m,crr,reason\n1,0,0.0061,\n2,100,0.00x7,\n");
  const auto r = read_results_dir(d.string());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().file, (d / "cells.csv").string());
  EXPECT_EQ(r.error().line, 3);
  EXPECT_EQ(r.error().field, "crr");
  fs::remove_all(d);
}

TEST(ResultsDir, ARowWithTheWrongFieldCountIsAnError) {
  const fs::path d = results_folder("short", "cell,start_m,crr,reason\n1,0\n");
  const auto r = read_results_dir(d.string());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().line, 2);
  fs::remove_all(d);
}

TEST(ResultsDir, CellsWithoutACrrColumnAreNotResults) {
  const fs::path d = results_folder("nocrr", "cell,start_m\n1,0\n");
  const auto r = read_results_dir(d.string());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().field, "header");
  fs::remove_all(d);
}

}  // namespace
}  // namespace roadload::results
