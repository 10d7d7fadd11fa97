#include "host/chart.h"

#include <algorithm>
#include <cmath>

#include "host/canvas.h"

namespace tessera {
namespace {

void draw_lines(Canvas& c, Box b, const ChartSpec& spec) {
  double xmin = 1e300, xmax = 0, ymin = 1e300, ymax = 0;
  for (const Series& s : spec.lines) {
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (s.x[i] <= 0 || s.y[i] <= 0) continue;
      xmin = std::min(xmin, s.x[i]);
      xmax = std::max(xmax, s.x[i]);
      ymin = std::min(ymin, s.y[i]);
      ymax = std::max(ymax, s.y[i]);
    }
  }
  if (xmax == 0) return;
  const LogAxes axes = log_axes(b, xmin, xmax, ymin, ymax);
  draw_log_axes(c, axes, spec.x_label, spec.y_label);
  auto px = [&](double x) { return axes.px(x); };
  auto py = [&](double y) { return axes.py(y); };
  for (size_t k = 0; k < spec.lines.size(); ++k) {
    const Series& s = spec.lines[k];
    const Colour col = palette(k);
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (s.y[i] <= 0) continue;
      c.rect(px(s.x[i]) - 3, py(s.y[i]) - 3, 6, 6, col);
      if (i + 1 < s.x.size() && s.y[i + 1] > 0)
        c.line(px(s.x[i]), py(s.y[i]), px(s.x[i + 1]), py(s.y[i + 1]), col, 2);
    }
    c.rect(b.x + 10, b.y + 10 + 18 * k, 14, 10, col);
    c.text(b.x + 30, b.y + 15 + 18 * k, s.name, 12, kInk, 0);
  }
}

void draw_bars(Canvas& c, Box b, const ChartSpec& spec) {
  const StackedBars& bars = spec.bars;
  double ymax = 0;
  for (const auto& v : bars.values) {
    double sum = 0;
    for (double x : v) sum += std::max(0.0, x);
    ymax = std::max(ymax, sum);
  }
  if (ymax <= 0) ymax = 1;
  // Round the axis up to 1, 2 or 5 times a power of ten.
  const double step = std::pow(10.0, std::floor(std::log10(ymax)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * step >= ymax) {
      ymax = m * step;
      break;
    }
  }
  c.text(b.x + b.w / 2, b.y - 14, spec.bars_title, 14, kInk, 1);
  for (int i = 0; i <= 4; ++i) {
    const double v = ymax * i / 4, y = b.y + b.h - b.h * i / 4;
    c.line(b.x, y, b.x + b.w, y, kGrid, 1);
    c.text(b.x - 6, y, format_number(v), 12, kInk, 2);
  }
  c.text(b.x - 58, b.y + b.h / 2, spec.bars_y_label, 13, kInk, 1, true);
  const double slot = b.w / std::max<size_t>(1, bars.categories.size());
  for (size_t i = 0; i < bars.categories.size(); ++i) {
    double base = 0;
    for (size_t l = 0; l < bars.layers.size() && l < bars.values[i].size(); ++l) {
      const double v = std::max(0.0, bars.values[i][l]);
      const double y0 = b.y + b.h - (base + v) / ymax * b.h;
      c.rect(b.x + slot * (i + 0.15), y0, slot * 0.7, v / ymax * b.h, palette(l));
      base += v;
    }
    c.text(b.x + slot * (i + 0.5), b.y + b.h + 14, bars.categories[i], 12, kInk, 1);
  }
  c.line(b.x, b.y + b.h, b.x + b.w, b.y + b.h, kInk, 1);
  c.text(b.x + b.w / 2, b.y + b.h + 34, spec.x_label, 13, kInk, 1);
  for (size_t l = 0; l < bars.layers.size(); ++l) {
    c.rect(b.x + b.w + 12, b.y + 18 * l, 14, 10, palette(l));
    c.text(b.x + b.w + 32, b.y + 5 + 18 * l, bars.layers[l], 12, kInk, 0);
  }
}

void draw(Canvas& c, double width, double height, const ChartSpec& spec) {
  c.rect(0, 0, width, height, {255, 255, 255});
  draw_title(c, width, spec.title);
  const bool two = !spec.bars.categories.empty();
  const double panel = two ? (width - 80) / 2 : width - 80;
  draw_lines(c, {80, 60, panel - 60, height - 130}, spec);
  if (two) draw_bars(c, {80 + panel + 20, 60, panel - 150, height - 130}, spec);
}

}  // namespace

void write_chart(const std::string& path, const ChartSpec& spec) {
  const double width = spec.bars.categories.empty() ? 700 : 1300, height = 520;
  write_canvas(path, width, height, [&](Canvas& c) { draw(c, width, height, spec); });
}

}  // namespace tessera
