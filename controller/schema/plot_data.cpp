#include "schema/plot_data.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

namespace cellctl::schema {
namespace {

using nlohmann::json;

json rounded(double v) {
  if (std::isnan(v)) return nullptr;
  return std::round(v * 1e4) / 1e4;
}

json model_json(const PlotModel& m) {
  json j;
  j["title"] = m.title;
  j["subtitle"] = m.subtitle;
  j["t_lo"] = m.t_lo;
  j["t_hi"] = m.t_hi;
  // The geometry the labels were laid out for: the plot area is never drawn narrower.
  j["geometry"] = {{"plot_px", kPlotAreaPx},   {"font_px", kLabelFontPx}, {"lane_px", kLaneHeightPx},
                   {"mark_px", kMarkNumberPx}, {"lanes", m.lanes},        {"mark_levels", m.mark_levels}};
  // Series with the same time stamps (one run's, or a long run's curves bucketed alike) share them:
  // written once, referred to by index.
  std::vector<const std::vector<double>*> times;
  j["times"] = json::array();
  j["panels"] = json::array();
  for (const auto& p : m.panels) {
    json panel{{"title", p.title}, {"unit", p.unit}, {"axis", p.value_axis}, {"series", json::array()}};
    for (const auto& s : p.series) {
      std::size_t ti = 0;
      while (ti < times.size() && *times[ti] != s.t) ++ti;
      if (ti == times.size()) {
        times.push_back(&s.t);
        json t = json::array();
        for (const double v : s.t) t.push_back(rounded(v));
        j["times"].push_back(std::move(t));
      }
      json v = json::array();
      for (const double x : s.v) v.push_back(rounded(x));
      panel["series"].push_back(
          {{"name", s.name}, {"colour", s.colour}, {"dash", s.dash}, {"t", ti}, {"v", v}});
    }
    j["panels"].push_back(std::move(panel));
  }
  j["steps"] = json::array();
  for (const auto& s : m.steps)
    j["steps"].push_back({{"t", s.t},
                          {"step", s.step},
                          {"full", s.full},
                          {"label", s.label},
                          {"lane", s.lane},
                          {"box_left", s.box_left},
                          {"box_right", s.box_right}});
  j["marks"] = json::array();
  for (const auto& mk : m.marks)
    j["marks"].push_back({{"t", rounded(mk.t)},
                          {"kind", mk.kind},
                          {"text", mk.text},
                          {"colour", mk.colour},
                          {"level", mk.level}});
  j["holds"] = json::array();
  for (const auto& h : m.holds) j["holds"].push_back({{"from", rounded(h.from)}, {"to", rounded(h.to)}});
  return j;
}

}  // namespace

std::string plot_data_json(const PlotModel& model) {
  // "</" inside the data would end the script element early.
  std::string data = model_json(model).dump();
  for (auto pos = data.find("</"); pos != std::string::npos; pos = data.find("</", pos + 3))
    data.replace(pos, 2, "<\\/");
  return data;
}

}  // namespace cellctl::schema
