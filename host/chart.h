#pragma once
// Charts of benchmark sweeps, written as SVG or PNG (chosen by the file's extension).

#include <string>
#include <vector>

namespace tessera {

struct Series {
  std::string name;
  std::vector<double> x;  // > 0 (log axis)
  std::vector<double> y;  // > 0 (log axis); entries <= 0 are gaps
};

struct StackedBars {
  std::vector<std::string> categories;      // one bar each (e.g. object counts)
  std::vector<std::string> layers;          // stacked parts (e.g. passes)
  std::vector<std::vector<double>> values;  // values[category][layer], >= 0
};

struct ChartSpec {
  std::string title;
  // Left panel: log-log lines.
  std::string x_label, y_label;
  std::vector<Series> lines;
  // Right panel: stacked bars (skipped if it has no categories).
  std::string bars_title, bars_y_label;
  StackedBars bars;
};

/// A scatter chart of settings: one series per knob, each point a setting, log-log axes.
struct ScatterPoint {
  double x = 0.0, y = 0.0;  // > 0; other points are left out of the drawing
  std::string label;
  bool on_front = false;  // marked, and joined to the series' other front points
};
struct ScatterSeries {
  std::string name;
  std::vector<ScatterPoint> points;
};
struct ScatterChart {
  std::string title, x_label, y_label;
  std::vector<ScatterSeries> series;
  std::vector<std::string> notes;  // lines under the legend (e.g. what was left out, and why)
};

/// Writes `chart` to `path` (.svg or .png; throws Error otherwise or if it cannot be written):
/// 1000 px wide, 600 high or taller where the legend's list needs it. Each point is labelled
/// beside its mark or at the end of a leader line, clear of the other labels and marks; a label
/// with no such room is replaced by a number, listed with the label under the legend.
void write_scatter_chart(const std::string& path, const ScatterChart& chart);

/// Writes `spec` to `path`, which must end in .svg or .png. Throws Error otherwise or if the
/// file cannot be written.
void write_chart(const std::string& path, const ChartSpec& spec);

}  // namespace tessera
