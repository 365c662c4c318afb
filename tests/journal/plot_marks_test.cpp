// The run plot's marks, read back from both drawings: every step has its boundary and its label whole
// (the full text, a box inside the plot area, overlapping no other label), every panel its axis titles
// with units, and resets, holds and commands are marked — in plot.svg and in plot.html alike.

#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "journal/plot_html.hpp"
#include "journal/plot_model.hpp"
#include "journal/plot_svg.hpp"

namespace cellctl::journal {
namespace {

// As the demo recipe runs: many short steps (preconditions and dwells at one instant, moves of a few
// seconds), long names, a step right at the end; held once, reset while held, commands typed.
RunRecord crowded_run() {
  RunRecord r;
  schema::RecordHeader h;
  h.recipe = "crowded";
  h.recipe_file = "crowded.yaml";
  h.axes = {{"x", true}, {"z", false}};
  r.set_header(h);
  r.add({0.0, RunStarted{"crowded", "c", "virtual-time", 25}});
  static const std::vector<std::string> labels = [] {
    std::vector<std::string> l;
    for (int i = 0; i < 25; ++i)
      l.push_back(i % 5 == 0   ? fmt::format("check the cell is homed and the encoder ready (line {})", i + 3)
                  : i % 5 == 1 ? fmt::format("drill hole {} 1/2 › spindle up (line {})", i, i + 3)
                               : fmt::format("drill hole {} 2/2 › peck in (line {})", i, i + 3));
    return l;
  }();
  // Steps 1–5 start at one instant; the others 3.6 s apart; the last 0.05 s before the end.
  double t = 0.5;
  for (std::uint32_t i = 0; i < 25; ++i) {
    if (i >= 5) t += i == 24 ? 1.0 : 3.6;
    r.add({t, StepStarted{i, labels[i]}});
    Sample s;
    s.axes = 2;
    s.planned_mm = {static_cast<float>(i), 1.0f};
    s.scu_mm = {static_cast<float>(i), 1.0f};
    r.add({t, s});
    r.add({t, StepEnded{i, labels[i], true, {}}});
  }
  r.add({20.0, Command{"hold", Text::format("terminal")}});
  r.add({20.0, StateChanged{"Execute", "Holding", Text::format("hold by terminal")}});
  r.add({20.4, StateChanged{"Holding", "Held", Text::format("cell at rest")}});
  r.add({22.0, Note{Text::format("faults reset in state Held"), false}});
  r.add({23.0, Command{"unhold", Text::format("terminal")}});
  r.add({23.0, StateChanged{"Held", "Unholding", {}}});
  r.add({23.2, StateChanged{"Unholding", "Execute", {}}});
  r.add({t + 0.05, RunEnded{"complete"}});
  r.finish();
  return r;
}

struct Label {
  int step = 0;
  std::string text;
  double left = 0.0, right = 0.0, y = 0.0;
};

// No two labels of one row overlap.
void expect_apart(const std::vector<Label>& labels) {
  for (std::size_t i = 0; i < labels.size(); ++i)
    for (std::size_t k = i + 1; k < labels.size(); ++k)
      if (labels[i].y == labels[k].y) {
        EXPECT_TRUE(labels[i].right <= labels[k].left || labels[k].right <= labels[i].left)
            << "steps " << labels[i].step << " and " << labels[k].step << " overlap";
      }
}

void expect_every_step_labelled_whole(const RunRecord& run, const std::vector<Label>& labels, double lo,
                                      double hi) {
  ASSERT_EQ(labels.size(), run.steps().size());
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const auto& l = labels[i];
    const auto& step = run.steps()[i];
    EXPECT_EQ(l.step, step.step);
    EXPECT_EQ(l.text, fmt::format("{} {}", step.step, short_step_name(step.label)));
    EXPECT_GE(l.left, lo - 1e-6) << l.text;
    EXPECT_LE(l.right, hi + 1e-6) << l.text;
    EXPECT_GE(l.right - l.left, label_width_px(l.text) - 1e-6) << l.text << ": squeezed";
  }
  expect_apart(labels);
}

// The SVG's elements that start with `open`, each up to and with `close`. (No std::regex: g++ 12 warns
// inside it under the asan preset's -O1.)
std::vector<std::string> elements(const std::string& svg, std::string_view open, std::string_view close) {
  std::vector<std::string> out;
  for (auto from = svg.find(open); from != std::string::npos; from = svg.find(open, from + 1)) {
    const auto to = svg.find(close, from);
    out.push_back(svg.substr(from, to == std::string::npos ? std::string::npos : to + close.size() - from));
  }
  return out;
}

// An attribute of the element's first tag that has it.
std::string attr(const std::string& element, const std::string& name) {
  const auto key = " " + name + "=\"";
  const auto at = element.find(key);
  if (at == std::string::npos) return {};
  const auto from = at + key.size();
  return element.substr(from, element.find('"', from) - from);
}

// The text of the element's first <text> from `open` on (its <title> aside).
std::string text_of(const std::string& element, std::string_view open = "<text") {
  const auto tag = element.find(open);
  const auto from = element.find('>', tag) + 1;
  return element.substr(from, element.find('<', from) - from);
}

TEST(PlotMarks, SvgMarksAndLabelsEveryStepWholeInsideThePlotArea) {
  const auto run = crowded_run();
  const auto svg = render_svg({&run});
  // The panels' frames: the first one's left and right edges are the plot area's.
  std::vector<std::string> frames;
  for (const auto& r : elements(svg, "<rect ", "/>"))
    if (r.find(R"(fill="none")") != std::string::npos) frames.push_back(r);
  ASSERT_EQ(frames.size(), 3u);
  const double left = std::stod(attr(frames[0], "x")), right = left + std::stod(attr(frames[0], "width"));
  const double first_top = std::stod(attr(frames[0], "y"));
  std::vector<Label> labels;
  for (const auto& g : elements(svg, R"(<g class="step")", "</g>")) {
    ASSERT_NE(g.find(R"(<line class="step-mark")"), std::string::npos) << g;
    const auto label = g.substr(g.find(R"(<text class="step-label")"));
    const double x = std::stod(attr(label, "x"));
    labels.push_back({std::stoi(attr(g, "data-step")), text_of(label), x,
                      x + std::stod(attr(label, "textLength")), std::stod(attr(label, "y"))});
    EXPECT_LT(labels.back().y, first_top) << "above the panels";
  }
  expect_every_step_labelled_whole(run, labels, left, right);
  // Axis titles with units on every panel.
  std::map<std::string, int> titles;
  for (const auto& t : elements(svg, R"(<text class="axis-title")", "</text>")) ++titles[text_of(t)];
  EXPECT_EQ(titles["time [s]"], 3);
  EXPECT_EQ(titles["position [mm]"], 1);
  EXPECT_EQ(titles["following error [mm]"], 1);
  EXPECT_EQ(titles["frequency [Hz]"], 1);
  // The hold shaded in every panel; the hold, the reset and the unhold marked.
  EXPECT_EQ(elements(svg, R"(<rect class="hold")", "</rect>").size(), 3u);
  std::vector<std::string> listed;
  for (const auto& m : elements(svg, R"(<text class="mark")", "</text>")) listed.push_back(text_of(m));
  ASSERT_EQ(listed.size(), 4u);
  EXPECT_NE(listed[0].find("command: hold (terminal)"), std::string::npos) << listed[0];
  EXPECT_NE(listed[1].find("reset: faults reset in state Held"), std::string::npos) << listed[1];
  EXPECT_NE(listed[2].find("command: unhold (terminal)"), std::string::npos) << listed[2];
  EXPECT_NE(listed[3].find("held 20.000 s – 23.000 s"), std::string::npos) << listed[3];
  EXPECT_EQ(elements(svg, R"(<line class="mark-line")", "</line>").size(), 3u);
}

TEST(PlotMarks, HtmlGetsTheSameMarksAndLabelsFromTheModel) {
  const auto run = crowded_run();
  const auto html = render_html({&run});
  const std::string open = R"(<script id="data" type="application/json">)";
  const auto from = html.find(open);
  ASSERT_NE(from, std::string::npos);
  const auto to = html.find("</script>", from);
  auto data = html.substr(from + open.size(), to - from - open.size());
  for (auto p = data.find("<\\/"); p != std::string::npos; p = data.find("<\\/", p)) data.erase(p + 1, 1);
  const auto j = nlohmann::json::parse(data);
  const double plot_px = j["geometry"]["plot_px"];
  std::vector<Label> labels;
  for (const auto& s : j["steps"])
    labels.push_back({s["step"], s["label"], s["box_left"], s["box_right"], s["lane"].get<double>()});
  expect_every_step_labelled_whole(run, labels, 0.0, plot_px);
  EXPECT_GE(j["geometry"]["lanes"].get<int>(), 5) << "five steps at one instant, five lanes";
  // The page draws every label of the model whole, never narrower than the model's plot area.
  EXPECT_NE(html.find("g.fillText(s.label, left, base, w)"), std::string::npos);
  EXPECT_NE(html.find("Math.max(L + G.plot_px + R,"), std::string::npos);
  std::vector<std::string> axes;
  for (const auto& p : j["panels"]) axes.push_back(p["axis"]);
  EXPECT_EQ(axes, (std::vector<std::string>{"position [mm]", "following error [mm]", "frequency [Hz]"}));
  EXPECT_NE(html.find(R"(g.fillText("time [s]")"), std::string::npos);
  std::vector<std::string> kinds;
  for (const auto& m : j["marks"]) kinds.push_back(m["kind"]);
  EXPECT_EQ(kinds, (std::vector<std::string>{"command", "reset", "command"}));
  ASSERT_EQ(j["holds"].size(), 1u);
  EXPECT_DOUBLE_EQ(j["holds"][0]["from"].get<double>(), 20.0);
  EXPECT_DOUBLE_EQ(j["holds"][0]["to"].get<double>(), 23.0);
}

TEST(PlotMarks, ResetAndClearAnswersAreMarkedOtherNotesAreNot) {
  EXPECT_EQ(reset_of_note("faults reset in state Held"), "reset");
  EXPECT_EQ(reset_of_note("reset refused: the cause of operator_stop is still present"), "reset");
  EXPECT_EQ(reset_of_note("reset is not possible in state Aborted: clear first"), "reset");
  EXPECT_EQ(reset_of_note("clear refused: the cause of link_silent is still present"), "clear");
  EXPECT_EQ(reset_of_note("home record written: state/home.json"), "");
  EXPECT_EQ(reset_of_note("hold is not possible in state Idle"), "");
}

}  // namespace
}  // namespace cellctl::journal
