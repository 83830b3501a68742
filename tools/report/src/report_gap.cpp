#include "roadload/report/report_gap.hpp"

#include <cmath>

#include "roadload/report/html_blocks.hpp"

namespace roadload::report {
namespace {

using results::JsonValue;

std::string text(const JsonValue* v) { return v && v->kind() == JsonValue::Kind::string ? v->string() : std::string(); }
double number(const JsonValue& v, std::string_view key) { return v.number_at(key).value_or(std::nan("")); }

// The first rows of the answer: the model's truck against this one, fitted before any effect.
std::string nominal(const JsonValue& g) {
  const JsonValue* n = g.find("nominal");
  if (n == nullptr || n->items().empty()) return {};
  std::vector<std::vector<std::string>> rows;
  for (const JsonValue& p : n->items()) {
    rows.push_back({text(p.find("name")), format_number(number(p, "model"), 4) + " " + text(p.find("unit")),
                    format_number(number(p, "fitted"), 4),
                    format_number(number(p, "lo"), 4) + " to " + format_number(number(p, "hi"), 4),
                    format_number(number(p, "shift_sigma"), 2)});
  }
  return "<p>The model's truck against this one: its nominal parameters fitted on half of the cells, before any effect is "
         "named (90 % intervals; the shift in the vehicle file's prior sigmas).</p>\n" +
         table_html({"parameter", "model", "fitted", "90 % interval", "shift (sigma)"}, rows);
}

std::string diagnosis(const JsonValue& g) {
  std::string h = nominal(g);
  const std::string effect = text(g.find("effect"));
  std::vector<std::vector<std::string>> rows;
  if (effect.empty()) {
    rows.push_back({"effect", "none: no candidate explains the gap significantly"});
  } else if (const JsonValue* effects = g.find("effects")) {
    for (const JsonValue& e : effects->items()) {
      rows.push_back({"effect", text(e.find("name")) + " = " + format_number(number(e, "magnitude"), 4) + " " + text(e.find("unit")) +
                                    ", 90 % interval " + format_number(number(e, "lo"), 3) + " to " +
                                    format_number(number(e, "hi"), 3)});
    }
  }
  if (const JsonValue* rivals = g.find("rivals"); rivals != nullptr && !effect.empty() && !rivals->items().empty()) {
    std::string names;
    for (const JsonValue& r : rivals->items()) names += (names.empty() ? "" : ", ") + text(r.find("name"));
    rows.push_back({"not told apart from", names + " (held-out gains within what noise alone gives)"});
  }
  rows.push_back({"held-out residual (RMS z) as modelled", format_number(number(g, "residual_raw"), 3)});
  rows.push_back({"with the truck fitted", format_number(number(g, "residual_before"), 3)});
  rows.push_back({"and the effect added", format_number(number(g, "residual_after"), 3)});
  if (const JsonValue* runs = g.find("runs")) {
    for (const JsonValue& r : runs->items()) rows.push_back({"drive", r.string()});
  }
  h += table_html({"diagnosis", ""}, rows, "summary");
  if (const JsonValue* where = g.find("where")) {
    std::vector<std::vector<std::string>> w;
    for (const JsonValue& item : where->items()) {
      w.push_back({text(item.find("run")), text(item.find("channel")), format_number(number(item, "features"), 4),
                   format_number(number(item, "sigma"), 3),
                   text(item.find("worst")) + " (z " + format_number(number(item, "worst_z"), 2) + ")"});
    }
    h +=
        "<p>Where the gap lies, most significant first (sigma: excess chi-square over the noise floor in standard deviations).</p>\n";
    h += table_html({"drive", "channel", "features", "sigma", "worst place"}, w);
  }
  if (const JsonValue* channels = g.find("channels")) {
    Chart c{"gap-channels", {"channel", false, false}, {"held-out residual, RMS z", false, true}, {}, false, {}, {}};
    Series raw{"model as it was", Series::Style::bars, {}, {}, {}, {}};
    Series before{"with the truck fitted", Series::Style::bars, {}, {}, {}, {}};
    Series after{"and the effect", Series::Style::bars, {}, {}, {}, {}};
    for (const JsonValue& ch : channels->items()) {
      c.categories.push_back(text(ch.find("channel")));
      raw.y.push_back(number(ch, "raw"));
      before.y.push_back(number(ch, "before"));
      after.y.push_back(number(ch, "after"));
    }
    c.series = {std::move(raw), std::move(before), std::move(after)};
    h += figure_html({std::move(c),
                      "The residual between the drive and its re-simulation on held-out cells, per channel: as modelled, with "
                      "the truck's nominal parameters fitted, and with the chosen effect added as well (1: as close as the "
                      "noise floor allows)."});
  }
  return h;
}

// The truck's nominal parameters against the tables: which move the suspension power, and the
// choice made again at both ends of their 90 % interval.
std::string tables_truck(const JsonValue& t) {
  const JsonValue* nominal = t.find("nominal");
  if (!nominal || nominal->items().empty()) return {};
  std::vector<std::vector<std::string>> rows;
  for (const JsonValue& n : nominal->items()) {
    std::vector<std::string> row{
        text(n.find("name")),
        format_number(number(n, "value"), 5) + " ± " + format_number(number(n, "sigma"), 3) + " " + text(n.find("unit")),
        format_number(100 * number(n, "power_per_sigma"), 2) + " %"};
    std::string ends;
    if (const JsonValue* e = n.find("ends")) {
      for (const JsonValue& end : e->items()) {
        const std::string effect = text(end.find("effect"));
        ends += (ends.empty() ? "" : "; ") + format_number(number(end, "value"), 5) + ": " +
                (effect.empty() ? std::string("none reaches the ratio") : effect + " " + format_number(number(end, "magnitude"), 3));
      }
    }
    row.push_back(ends.empty() ? "left at its value" : ends);
    rows.push_back(std::move(row));
  }
  return "<p>The truck's nominal parameters: the four powers cannot fit them (each road's level is the report's Eq. 2.7 "
         "against the simulator's damper dissipation, a scale the ratios take out), so each keeps its vehicle file's "
         "spread; where one moves the suspension power, the choice is made again at both ends of its 90 % interval.</p>\n" +
         table_html({"parameter", "vehicle file", "Mainline power per sigma", "chosen at the interval's ends"}, rows);
}

std::string report_tables(const JsonValue& t) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> names;
  Chart c{"gap-tables", {"pavement", false, false}, {"suspension power (W)", false, true}, {}, false, {}, {}};
  Series report{"seed report", Series::Style::bars, {}, {}, {}, {}};
  Series before{"IRI only", Series::Style::bars, {}, {}, {}, {}};
  Series after{"with the effect", Series::Style::bars, {}, {}, {}, {}};
  if (const JsonValue* r = t.find("rows")) {
    for (const JsonValue& row : r->items()) {
      rows.push_back({text(row.find("pavement")), format_number(number(row, "report_w"), 4),
                      format_number(number(row, "before_w"), 4), format_number(number(row, "after_w"), 4)});
      c.categories.push_back(text(row.find("pavement")));
      report.y.push_back(number(row, "report_w"));
      before.y.push_back(number(row, "before_w"));
      after.y.push_back(number(row, "after_w"));
    }
  }
  c.y.log = true;
  c.y.from_zero = false;
  c.series = {std::move(report), std::move(before), std::move(after)};
  const std::string effect = text(t.find("effect"));
  std::string h = "<p>The seed report's Tables 6.5 and 6.6 against a simulation that knows only each pavement's IRI, and with " +
                  (effect.empty() ? std::string("no candidate (none reaches the report's Mainline ratio)")
                                  : "<b>" + escape_html(effect) + "</b>") +
                  " fitted to the Mainline and judged on the highways.</p>\n";
  h += figure_html({std::move(c), "Suspension power by pavement: report, IRI-only simulation, and with the fitted effect."});
  h += table_html({"pavement", "report (W)", "IRI only (W)", "with the effect (W)"}, rows);
  std::vector<std::vector<std::string>> cands;
  if (const JsonValue* cs = t.find("candidates")) {
    for (const JsonValue& cand : cs->items()) {
      const JsonValue* reached = cand.find("reaches_mainline_ratio");
      cands.push_back({text(cand.find("effect")), reached && reached->boolean() ? "yes" : "no",
                       format_number(number(cand, "magnitude"), 3), format_number(number(cand, "highway_ratio"), 3),
                       format_number(100 * number(cand, "holdout_error"), 2) + " %"});
    }
  }
  h += table_html({"candidate", "reaches the Mainline ratio", "magnitude", "TH 10 / TH 66 (held out)", "error"}, cands);
  return h + tables_truck(t);
}

}  // namespace

std::string gap_section(const JsonValue* gap, const JsonValue* tables) {
  if (!gap && !tables) return {};
  std::string h = "<h2 id=\"gap\">Sim-to-real gap</h2>\n";
  if (gap) h += diagnosis(*gap);
  if (tables) h += "<h3>The seed report's tables</h3>\n" + report_tables(*tables);
  return h;
}

}  // namespace roadload::report
