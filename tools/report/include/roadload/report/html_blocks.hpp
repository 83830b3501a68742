#pragma once
// The page's building blocks: a figure with its caption, a table.
#include <string>
#include <vector>

#include "roadload/report/report_figures.hpp"

namespace roadload::report {

std::string figure_html(const Figure& f);
std::string table_html(const std::vector<std::string>& head, const std::vector<std::vector<std::string>>& rows,
                       const std::string& cls = "");

}  // namespace roadload::report
