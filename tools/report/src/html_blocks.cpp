#include "roadload/report/html_blocks.hpp"

namespace roadload::report {

std::string figure_html(const Figure& f) {
  return "<figure id=\"" + f.chart.id + "\">" + render_svg(f.chart) + "<figcaption>" + escape_html(f.caption) +
         "</figcaption></figure>\n";
}

std::string table_html(const std::vector<std::string>& head, const std::vector<std::vector<std::string>>& rows,
                       const std::string& cls) {
  std::string h = "<table" + (cls.empty() ? std::string() : " class=\"" + cls + "\"") + "><tr>";
  for (const std::string& c : head) h += "<th>" + escape_html(c) + "</th>";
  h += "</tr>\n";
  for (const auto& row : rows) {
    h += "<tr>";
    for (const std::string& c : row) h += "<td>" + escape_html(c) + "</td>";
    h += "</tr>\n";
  }
  return h + "</table>\n";
}

}  // namespace roadload::report
