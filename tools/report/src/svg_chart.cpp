#include "roadload/report/svg_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace roadload::report {
namespace {

constexpr double kWidth = 760, kHeight = 340;
constexpr double kLeft = 78, kRight = 16, kTop = 34;
// Okabe-Ito: told apart with the common colour-vision deficiencies.
constexpr const char* kColours[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442"};

const char* colour(std::size_t i) { return kColours[i % std::size(kColours)]; }

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v, bool log) {
    if (!std::isfinite(v) || (log && v <= 0)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool empty() const { return !(lo <= hi); }
};

// Maps data to pixels along one axis.
struct Scale {
  double lo, hi, p0, p1;
  bool log;
  double operator()(double v) const {
    const double f = log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) : (v - lo) / (hi - lo);
    return p0 + f * (p1 - p0);
  }
};

Range padded(Range r, const Axis& a) {
  if (r.empty()) r = {a.log ? 1.0 : 0.0, a.log ? 10.0 : 1.0};
  if (a.from_zero && !a.log) {
    r.lo = std::min(r.lo, 0.0);
    r.hi = std::max(r.hi, 0.0);
  }
  if (a.log) {
    r.lo = std::pow(10.0, std::floor(std::log10(r.lo)));
    r.hi = std::pow(10.0, std::ceil(std::log10(r.hi)));
    if (r.hi <= r.lo) r.hi = r.lo * 10;
    return r;
  }
  const double span = r.hi > r.lo ? r.hi - r.lo : std::max(std::abs(r.hi), 1e-12);
  if (!(a.from_zero && r.lo == 0)) r.lo -= 0.05 * span;
  r.hi += 0.05 * span;
  return r;
}

std::string text(double x, double y, const std::string& s, const char* anchor, const std::string& extra = "") {
  return "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" text-anchor=\"" + anchor + "\"" + extra + ">" + escape_html(s) + "</text>";
}

std::string tick_label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", std::abs(v) < 1e-15 ? 0.0 : v);
  return buf;
}

class Canvas {
 public:
  explicit Canvas(const Chart& c) : c_(c) {
    bottom_ = kHeight - (c.categories.empty() ? 46.0 : 78.0);
    const Range xr = padded(x_range(), c.x);
    x_ = {xr.lo, xr.hi, kLeft, kWidth - kRight, c.x.log};
    const Range yr = padded(y_range(), c.y);
    y_ = {yr.lo, yr.hi, bottom_, kTop, c.y.log};
  }

  std::string draw() {
    out_.clear();
    axes();
    for (std::size_t s = 0; s < c_.series.size(); ++s) series(s);
    const double height = kHeight + markers();
    legend();
    return "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " + num(kWidth) + " " + num(height) +
           "\" role=\"img\" font-family=\"sans-serif\" font-size=\"11\">" + out_ + "</svg>";
  }

 private:
  bool categorical() const { return !c_.categories.empty(); }
  double band() const { return (kWidth - kRight - kLeft) / static_cast<double>(std::max<std::size_t>(c_.categories.size(), 1)); }
  double centre(std::size_t i) const { return kLeft + (static_cast<double>(i) + 0.5) * band(); }

  Range x_range() const {
    Range r;
    if (categorical()) return {0, 1};
    for (const Series& s : c_.series) {
      for (double v : s.x) r.add(v, c_.x.log);
    }
    for (const Marker& m : c_.markers) r.add(m.x, c_.x.log);
    return r;
  }

  Range y_range() const {
    Range r;
    if (c_.stacked) {
      for (std::size_t i = 0; i < c_.categories.size(); ++i) {
        double up = 0, down = 0;
        for (const Series& s : c_.series) {
          const double v = i < s.y.size() && std::isfinite(s.y[i]) ? s.y[i] : 0.0;
          (v >= 0 ? up : down) += v;
        }
        r.add(up, false);
        r.add(down, false);
      }
      return r;
    }
    for (const Series& s : c_.series) {
      for (double v : s.y) r.add(v, c_.y.log);
      for (double v : s.lo) r.add(v, c_.y.log);
      for (double v : s.hi) r.add(v, c_.y.log);
    }
    return r;
  }

  void axes() {
    out_ += "<g stroke=\"#ddd\">";
    for (double t : ticks(y_.lo, y_.hi, y_.log)) {
      out_ += "<line x1=\"" + num(kLeft) + "\" x2=\"" + num(kWidth - kRight) + "\" y1=\"" + num(y_(t)) + "\" y2=\"" + num(y_(t)) +
              "\"/>";
    }
    out_ += "</g><g fill=\"#333\">";
    for (double t : ticks(y_.lo, y_.hi, y_.log)) out_ += text(kLeft - 4, y_(t) + 4, tick_label(t), "end");
    if (categorical()) {
      for (std::size_t i = 0; i < c_.categories.size(); ++i) {
        const double x = centre(i), y = bottom_ + 12;
        out_ += text(x, y, c_.categories[i], "end", " transform=\"rotate(-40 " + num(x) + " " + num(y) + ")\"");
      }
    } else {
      for (double t : ticks(x_.lo, x_.hi, x_.log)) {
        out_ += "<line x1=\"" + num(x_(t)) + "\" x2=\"" + num(x_(t)) + "\" y1=\"" + num(bottom_) + "\" y2=\"" + num(bottom_ + 4) +
                "\" stroke=\"#333\"/>" + text(x_(t), bottom_ + 16, tick_label(t), "middle");
      }
    }
    out_ += text(kLeft + (kWidth - kRight - kLeft) / 2, kHeight - 6, c_.x.label, "middle");
    out_ += text(16, (kTop + bottom_) / 2, c_.y.label, "middle", " transform=\"rotate(-90 16 " + num((kTop + bottom_) / 2) + ")\"");
    out_ += "</g><rect x=\"" + num(kLeft) + "\" y=\"" + num(kTop) + "\" width=\"" + num(kWidth - kRight - kLeft) + "\" height=\"" +
            num(bottom_ - kTop) + "\" fill=\"none\" stroke=\"#333\"/>";
    if (!y_.log && y_.lo < 0 && y_.hi > 0) {
      out_ += "<line x1=\"" + num(kLeft) + "\" x2=\"" + num(kWidth - kRight) + "\" y1=\"" + num(y_(0)) + "\" y2=\"" + num(y_(0)) +
              "\" stroke=\"#333\"/>";
    }
  }

  bool drawable(double v) const { return std::isfinite(v) && (!y_.log || v > 0); }

  void series(std::size_t s) {
    const Series& sr = c_.series[s];
    out_ += "<g fill=\"" + std::string(colour(s)) + "\" stroke=\"" + colour(s) + "\"><title>" + escape_html(sr.name) + "</title>";
    if (sr.style == Series::Style::line) {
      line(sr);
    } else if (sr.style == Series::Style::bars) {
      bars(s);
    } else {
      points(s);
    }
    out_ += "</g>";
  }

  void line(const Series& sr) {
    std::string path;
    for (std::size_t i = 0; i < sr.y.size() && i < sr.x.size(); ++i) {
      const bool ok = drawable(sr.y[i]) && std::isfinite(sr.x[i]) && (!x_.log || sr.x[i] > 0) && sr.x[i] >= x_.lo && sr.x[i] <= x_.hi;
      if (!ok) continue;
      path += (path.empty() ? "M" : "L") + num(x_(sr.x[i])) + "," + num(y_(std::max(sr.y[i], y_.lo)));
    }
    if (!path.empty()) out_ += "<path class=\"datum\" fill=\"none\" stroke-width=\"1.3\" d=\"" + path + "\"/>";
  }

  // Series `s`'s place among the series drawn in its style, and how many there are: series of one
  // style share each category's band.
  std::pair<std::size_t, std::size_t> place_among_style(std::size_t s) const {
    std::size_t index = 0, count = 0;
    for (std::size_t k = 0; k < c_.series.size(); ++k) {
      if (c_.series[k].style != c_.series[s].style) continue;
      if (k == s) index = count;
      ++count;
    }
    return {index, count};
  }

  // Bars side by side within each category, or stacked (positive parts up, negative down).
  void bars(std::size_t s) {
    const Series& sr = c_.series[s];
    const auto [index, nbars] = place_among_style(s);
    const double width = c_.stacked ? band() * 0.7 : band() * 0.8 / static_cast<double>(nbars);
    for (std::size_t i = 0; i < sr.y.size() && i < c_.categories.size(); ++i) {
      if (!std::isfinite(sr.y[i])) continue;
      double base = 0;
      if (c_.stacked) {
        for (std::size_t k = 0; k < s; ++k) {
          const double v = i < c_.series[k].y.size() && std::isfinite(c_.series[k].y[i]) ? c_.series[k].y[i] : 0.0;
          if ((v >= 0) == (sr.y[i] >= 0)) base += v;
        }
      }
      const double x = c_.stacked ? centre(i) - width / 2 : centre(i) - band() * 0.4 + width * static_cast<double>(index);
      // On a log axis a bar rises from the axis's foot, zero lying infinitely far below it; a
      // value that is not positive has no place on it.
      if (y_.log && base + sr.y[i] <= 0) continue;
      const double y0 = y_.log && base <= 0 ? y_(y_.lo) : y_(base), y1 = y_(base + sr.y[i]);
      out_ += "<rect class=\"datum\" stroke=\"none\" x=\"" + num(x) + "\" y=\"" + num(std::min(y0, y1)) + "\" width=\"" + num(width) +
              "\" height=\"" + num(std::max(std::abs(y1 - y0), 0.5)) + "\"><title>" +
              escape_html(c_.categories[i] + " " + sr.name + ": " + format_number(sr.y[i], 4)) + "</title></rect>";
    }
  }

  // Points with their intervals; several series side by side within a category.
  void points(std::size_t s) {
    const Series& sr = c_.series[s];
    const auto [index, npoints] = place_among_style(s);
    for (std::size_t i = 0; i < sr.y.size(); ++i) {
      if (!drawable(sr.y[i])) continue;
      double x = 0;
      if (categorical()) {
        if (i >= c_.categories.size()) break;
        x = centre(i) +
            band() * 0.5 * (static_cast<double>(index) + 0.5 - static_cast<double>(npoints) / 2) / static_cast<double>(npoints);
      } else {
        if (i >= sr.x.size() || !std::isfinite(sr.x[i])) continue;
        x = x_(sr.x[i]);
      }
      if (i < sr.lo.size() && i < sr.hi.size() && drawable(sr.lo[i]) && drawable(sr.hi[i])) {
        out_ += "<path fill=\"none\" d=\"M" + num(x) + "," + num(y_(sr.lo[i])) + "V" + num(y_(sr.hi[i])) + "M" + num(x - 3) + "," +
                num(y_(sr.lo[i])) + "h6M" + num(x - 3) + "," + num(y_(sr.hi[i])) + "h6\"/>";
      }
      const std::string label = (categorical() ? c_.categories[i] + " " : "") + sr.name + ": " + format_number(sr.y[i], 4);
      const std::string shape = index % 2 == 0
                                    ? "<circle class=\"datum\" cx=\"" + num(x) + "\" cy=\"" + num(y_(sr.y[i])) + "\" r=\"3.5\">"
                                    : "<rect class=\"datum\" x=\"" + num(x - 3.5) + "\" y=\"" + num(y_(sr.y[i]) - 3.5) +
                                          "\" width=\"7\" height=\"7\">";
      out_ += shape + "<title>" + escape_html(label) + "</title>" + (index % 2 == 0 ? "</circle>" : "</rect>");
    }
  }

  // Each marker's line carries a number at the top, in the first of a few rows where it clears its
  // neighbours (modes a few hertz apart sit pixels apart on a log axis); the numbers' key runs
  // beneath the chart. Returns the height the key adds.
  double markers() {
    constexpr double kClear = 15, kRow = 14, kKeyRow = 15;
    std::vector<std::pair<double, const Marker*>> shown;
    for (const Marker& m : c_.markers) {
      if (std::isfinite(m.x) && m.x >= x_.lo && m.x <= x_.hi) shown.emplace_back(x_(m.x), &m);
    }
    std::sort(shown.begin(), shown.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<double> row_end;
    std::vector<std::string> key;
    for (const auto& [x, m] : shown) {
      out_ += "<line x1=\"" + num(x) + "\" x2=\"" + num(x) + "\" y1=\"" + num(kTop) + "\" y2=\"" + num(bottom_) + "\" stroke=\"" +
              (m->strong ? "#b00" : "#555") + "\"" + (m->strong ? "" : " stroke-dasharray=\"3 3\"") + "><title>" +
              escape_html(m->label) + "</title></line>";
      if (m->label.empty()) continue;
      const std::string number = std::to_string(key.size() + 1);
      key.push_back(number + " " + m->label);
      std::size_t row = 0;
      while (row < row_end.size() && x - row_end[row] < kClear) ++row;
      if (row == row_end.size()) row_end.push_back(-1e9);
      row_end[row] = x;
      out_ += text(x, kTop + 11 + kRow * static_cast<double>(row), number, "middle",
                   " class=\"marker-label\" fill=\"#333\" font-weight=\"bold\"");
    }
    // The key, wrapped to the chart's width.
    double y = kHeight, line_x = kLeft;
    for (const std::string& k : key) {
      const double width = 6.2 * static_cast<double>(k.size()) + 18;
      if (line_x + width > kWidth - kRight || y == kHeight) {
        y += kKeyRow;
        line_x = kLeft;
      }
      out_ += text(line_x, y, k, "start", " fill=\"#333\"");
      line_x += width;
    }
    return y - kHeight + (key.empty() ? 0 : 6);
  }

  void legend() {
    double x = kLeft;
    for (std::size_t s = 0; s < c_.series.size(); ++s) {
      out_ += "<rect x=\"" + num(x) + "\" y=\"10\" width=\"10\" height=\"10\" fill=\"" + colour(s) + "\"/>";
      out_ += text(x + 14, 19, c_.series[s].name, "start", " fill=\"#333\"");
      x += 24 + 6.2 * static_cast<double>(c_.series[s].name.size());
    }
  }

  const Chart& c_;
  double bottom_ = 0;
  Scale x_{}, y_{};
  std::string out_;
};

}  // namespace

std::vector<double> ticks(double lo, double hi, bool log) {
  std::vector<double> t;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return t;
  if (log) {
    if (lo <= 0) return t;
    for (double e = std::ceil(std::log10(lo) - 1e-9); e <= std::log10(hi) + 1e-9; ++e) t.push_back(std::pow(10.0, e));
    return t;
  }
  const double raw = (hi - lo) / 5;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / mag;
  const double step = (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * mag;
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step) t.push_back(v);
  return t;
}

std::string render_svg(const Chart& chart) { return Canvas(chart).draw(); }

std::string escape_html(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out.push_back(c);
    }
  }
  return out;
}

std::string format_number(double v, int digits) {
  if (!std::isfinite(v)) return "\u2013";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

}  // namespace roadload::report
