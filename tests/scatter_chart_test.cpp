// The scatter chart (host/chart.h, write_scatter_chart) that `tessera tradeoff` draws: every
// point's label is on the chart, beside its mark or at the end of a leader, or, where a
// cluster leaves no room for it, as a number (or a pile's range of numbers) beside the mark
// that the list under the legend pairs with the label. The list makes the chart taller rather
// than run off it.
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/image.h"
#include "host/canvas.h"
#include "host/chart.h"
#include "tests/vulkan_fixture.h"

namespace tessera {
namespace {

struct SvgText {
  double y;
  std::string text;
};

std::vector<SvgText> texts_of(const std::string& svg) {
  std::vector<SvgText> out;
  const std::regex text("<text x='[^']*' y='([^']*)'[^>]*>([^<]*)</text>");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), text); it != std::sregex_iterator();
       ++it)
    out.push_back({std::stod((*it)[1]), (*it)[2]});
  return out;
}

// Sixty settings of three knobs piled within a few pixels, and one far off that spans the axes:
// far more labels than the pile has room for.
ScatterChart crowded_chart() {
  ScatterChart chart;
  chart.title = "crowded";
  chart.x_label = "ms";
  chart.y_label = "error";
  for (int k = 0; k < 3; ++k) {
    ScatterSeries s{"knob" + std::to_string(k), {}};
    for (int i = 0; i < 20; ++i) {
      s.points.push_back({100.0 + 0.05 * i + 0.3 * k, 0.05 + 0.0002 * i,
                          "setting " + std::to_string(k) + "." + std::to_string(i), i == 0});
    }
    chart.series.push_back(s);
  }
  chart.series[0].points.push_back({1000.0, 0.009, "far", false});  // no tick reads as a number
  return chart;
}

TEST(ScatterChart, EveryLabelIsBesideItsMarkOrNumberedInTheList) {
  const ScatterChart chart = crowded_chart();
  const std::string path = test::output_path("scatter_chart") + ".svg";
  write_scatter_chart(path, chart);
  std::ifstream f(path);
  const std::string svg(std::istreambuf_iterator<char>(f), {});
  const std::vector<SvgText> texts = texts_of(svg);
  std::smatch size;
  ASSERT_TRUE(std::regex_search(svg, size, std::regex("height='([0-9.]+)'")));
  const double height = std::stod(size[1]);
  std::map<std::string, int> shown;  // each text's count
  for (const SvgText& t : texts) ++shown[t.text];
  int numbered = 0;
  for (const ScatterSeries& s : chart.series) {
    for (const ScatterPoint& p : s.points) {
      if (shown[p.label] == 1) continue;  // beside its mark, once
      EXPECT_EQ(shown[p.label], 0) << p.label;
      // Else listed as "N knob: label", and N shown once on the plot: alone, or in a range
      // "A-B" that a pile's labels share.
      const std::regex entry("([0-9]+) " + s.name + ": " + p.label);
      bool listed = false;
      for (const SvgText& t : texts) {
        std::smatch m;
        if (!std::regex_match(t.text, m, entry)) continue;
        listed = true;
        const int n = std::stoi(m[1]);
        int on_plot = shown[m[1]];
        for (const SvgText& r : texts) {
          std::smatch range;
          if (std::regex_match(r.text, range, std::regex("([0-9]+)-([0-9]+)")))
            on_plot += std::stoi(range[1]) <= n && n <= std::stoi(range[2]);
        }
        EXPECT_EQ(on_plot, 1) << "the number " << n << " on the plot, for " << p.label;
      }
      EXPECT_TRUE(listed) << p.label << " is neither beside its mark nor listed";
      ++numbered;
    }
  }
  EXPECT_GT(numbered, 29) << "the pile has room for fewer than half of the labels";
  // The list does not fit under the legend of a 600 px chart: the chart is taller, and every
  // line of text is inside it.
  EXPECT_GT(height, 600);
  for (const SvgText& t : texts) EXPECT_LT(t.y, height - 5) << t.text;
}

TEST(ScatterChart, APngIsAsTallAsItsList) {
  const std::string path = test::output_path("scatter_chart") + ".png";
  write_scatter_chart(path, crowded_chart());
  const Image8 png = read_png(path);
  EXPECT_EQ(png.width, 1000u);
  EXPECT_GT(png.height, 600u);
  // The last line of the list is drawn: ink in the legend's column near the bottom.
  bool ink = false;
  for (uint32_t y = png.height - 30; y < png.height; ++y)
    for (uint32_t x = 780; x < png.width; ++x) ink |= png.at(x, y).r < 200;
  EXPECT_TRUE(ink);
}

TEST(ScatterChart, ASparseChartKeepsItsSizeAndLabels) {
  ScatterChart chart;
  chart.series.push_back({"brdf", {{1, 0.1, "classic", true}, {10, 0.01, "filament", true}}});
  const std::string path = test::output_path("scatter_chart_sparse") + ".svg";
  write_scatter_chart(path, chart);
  std::ifstream f(path);
  const std::string svg(std::istreambuf_iterator<char>(f), {});
  EXPECT_NE(svg.find("height='600'"), std::string::npos);
  EXPECT_NE(svg.find(">classic</text>"), std::string::npos);
  EXPECT_NE(svg.find(">filament</text>"), std::string::npos);
  EXPECT_EQ(svg.find("numbered"), std::string::npos) << "no list where every label fits";
}

// `tradeoff --knob` takes fifteen knobs: each series keeps a look of its own. The first 20
// colours differ, and series 10 to 19 are outlined, so that a colour near one of the first
// ten's still reads as another series.
TEST(ScatterChart, FifteenSeriesLookDistinct) {
  for (size_t i = 0; i < 20; ++i) {
    for (size_t j = 0; j < i; ++j) {
      const Colour a = palette(i), b = palette(j);
      const int distance = std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b);
      EXPECT_GE(distance, 60) << "series " << j << " and " << i;
    }
    EXPECT_EQ(series_hollow(i), i >= 10) << i;
  }
  ScatterChart chart;
  for (int k = 0; k < 15; ++k) {
    chart.series.push_back(
        {"knob" + std::to_string(k), {{1.0 + k, 0.1 / (1 + k), "s" + std::to_string(k), true}}});
  }
  const std::string path = test::output_path("scatter_chart_fifteen") + ".svg";
  write_scatter_chart(path, chart);
  std::ifstream f(path);
  const std::string svg(std::istreambuf_iterator<char>(f), {});
  // Series 0's legend swatch is one filled 14 x 10 rectangle; series 10's (navy, #000080) is
  // four thin sides, none of them 14 x 10.
  EXPECT_NE(svg.find("width='14' height='10' fill='#1f77b4'"), std::string::npos);
  EXPECT_EQ(svg.find("width='14' height='10' fill='#000080'"), std::string::npos);
  EXPECT_NE(svg.find("width='14' height='1.5' fill='#000080'"), std::string::npos);
}

// A title too long for one line is broken in two at a ", " near its middle, each line at full
// size (an interrupted sweep's title was drawn on one line, shrunk to a quarter of its size).
TEST(ScatterChart, ALongTitleTakesTwoLines) {
  ScatterChart chart = crowded_chart();
  chart.title =
      "speed against accuracy: 'a scene with a long name', 1920x1080, a device with a "
      "long name (LLVM 15.0.6, 256 bits), interrupted (8 of 24 measured)";
  const std::string path = test::output_path("scatter_chart_title") + ".svg";
  write_scatter_chart(path, chart);
  std::ifstream f(path);
  const std::string svg(std::istreambuf_iterator<char>(f), {});
  const std::vector<SvgText> texts = texts_of(svg);
  ASSERT_GE(texts.size(), 2u);
  EXPECT_EQ(texts[0].text + " " + texts[1].text, chart.title);
  EXPECT_EQ(texts[0].text.back(), ',');
  EXPECT_NE(svg.find("font-size='16' fill='#282828' text-anchor='middle' "
                     "dominant-baseline='middle'>" +
                     texts[1].text),
            std::string::npos)
      << "full size: " << svg.substr(0, 600);
  EXPECT_LT(texts[0].y, texts[1].y);
  EXPECT_LE(texts[1].y + 8, 60.0) << "above the plot";
}

}  // namespace
}  // namespace tessera
