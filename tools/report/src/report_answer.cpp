#include "roadload/report/report_answer.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

#include "roadload/report/html_blocks.hpp"
#include "roadload/report/svg_chart.hpp"

namespace roadload::report {
namespace {

using results::JsonValue;

std::string text_of(const JsonValue* v) { return v != nullptr && !v->string().empty() ? v->string() : std::string(); }

// "The mnroad-truck (VIN ...) on mnroad-mainline-westbound, driven 2014-10-20T15:00:00Z ..."
std::string provenance_paragraph(const JsonValue& p) {
  const auto field = [&](const char* key) { return text_of(p.find(key)); };
  const std::string date = field("drive_start_utc");
  const std::string end = field("drive_end_utc");
  std::string s = "Truck <b>" + escape_html(field("vehicle").empty() ? "not named" : field("vehicle")) + "</b>";
  if (!field("vin").empty()) s += " (VIN " + escape_html(field("vin")) + ")";
  s += ", described by " + escape_html(field("vehicle_source")) + "; route <b>" + escape_html(field("route")) + "</b>; driven " +
       (date.empty() ? std::string("at a time no GNSS fix told")
                     : "<b>" + escape_html(date) + "</b>" + (end.empty() ? "" : " to " + escape_html(end))) +
       ".";
  s += " Calibration: engine losses from " + escape_html(field("engine_losses")) + ", drag area " + escape_html(field("cda"));
  if (!field("torque_scale").empty()) s += ", engine torque scale " + escape_html(field("torque_scale"));
  s += ". Recording";
  const JsonValue* recs = p.find("recordings");
  std::string names;
  for (std::size_t i = 0; recs != nullptr && i < recs->items().size(); ++i) names += (i ? ", " : " ") + recs->items()[i].string();
  s += "<code>" + escape_html(names) + "</code>";
  if (!field("recording_id").empty()) s += " (logger run " + escape_html(field("recording_id")) + ")";
  return "<p class=\"provenance\">" + s + "; " + escape_html(field("program")) + ".</p>\n";
}

// Five decimals, as CRR is compared between pavements: "0.00587 [0.00370, 0.00804]".
std::string crr_text(double crr, double lo, double hi) {
  char text[64];
  std::snprintf(text, sizeof text, "%.5f [%.5f, %.5f]", crr, lo, hi);
  return text;
}

std::vector<std::string> pavement_row(const JsonValue& p) {
  const auto n = [&](const char* key) { return p.number_at(key).value_or(std::nan("")); };
  const JsonValue* ident = p.find("crr_identified");
  const bool identified = ident != nullptr && ident->boolean();
  const double crr = n("crr");
  const std::string reason = text_of(p.find("reason"));
  std::string verdict = identified ? "identified" : reason.empty() ? "not identified" : reason;
  const std::string prefix = "CRR not identified: ";
  if (verdict.rfind(prefix, 0) == 0) verdict = "not identified: " + verdict.substr(prefix.size());
  return {text_of(p.find("pavement")), std::isfinite(crr) ? crr_text(crr, n("crr_lo"), n("crr_hi")) : "\u2013",
          format_number(n("rolling_l_per_100km"), 3), format_number(n("distance_m") / 1000, 3), verdict};
}

}  // namespace

std::string answer_section(const JsonValue& trip) {
  std::string out;
  if (const JsonValue* p = trip.find("provenance")) out += provenance_paragraph(*p);
  const JsonValue* pavements = trip.find("pavements");
  if (pavements == nullptr || pavements->items().empty()) {
    return out +
           "<p class=\"warn\">No answer per pavement: these results name no pavement types (a route file's cells "
           "give them; results that `roadload analyze` wrote before it gave one need analysing again).</p>\n";
  }
  std::vector<std::vector<std::string>> rows;
  for (const JsonValue& p : pavements->items()) rows.push_back(pavement_row(p));
  return out +
         table_html({"pavement", "CRR [90 % interval]", "rolling resistance (L/100 km)", "driven (km)", "verdict"}, rows, "answer");
}

}  // namespace roadload::report
