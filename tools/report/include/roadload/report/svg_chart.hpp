#pragma once
// Charts drawn as inline SVG, so the report is one file that opens from disk with no script and no
// network. Two kinds: along categories (cells, fuel uses) as bars or points with intervals, and
// along a numeric axis (frequency) as lines, optionally log-log, with labelled vertical markers.
#include <string>
#include <vector>

namespace roadload::report {

struct Axis {
  std::string label;
  bool log = false;
  bool from_zero = false;  // a linear axis that must include 0 (bars, powers, litres)
};

struct Series {
  enum class Style { line, points, bars };
  std::string name;
  Style style = Style::points;
  std::vector<double> x;       // numeric charts only
  std::vector<double> y;       // NaN: no value there
  std::vector<double> lo, hi;  // optional interval per value (drawn as a whisker)
};

struct Marker {
  double x = 0;
  std::string label;
  bool strong = false;  // drawn solid (a joint line) rather than dashed (a mode)
};

struct Chart {
  std::string id;  // the <figure>'s id
  Axis x, y;
  std::vector<std::string> categories;  // non-empty: a category chart
  bool stacked = false;                 // category bars stacked rather than side by side
  std::vector<Series> series;
  std::vector<Marker> markers;
};

// "Nice" tick positions (1, 2, 5 x 10^n steps; decades on a log axis) covering [lo, hi].
std::vector<double> ticks(double lo, double hi, bool log);

// The <svg> element; every drawn datum carries class "datum" so a test can count what was drawn.
std::string render_svg(const Chart& chart);

std::string escape_html(const std::string& text);
// A number for a table or a label: `digits` significant figures, "–" for NaN.
std::string format_number(double v, int digits);

}  // namespace roadload::report
