#include "host/chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/check.h"
#include "core/file_extension.h"
#include "core/image.h"
#include "host/label_layout.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

namespace tessera {
namespace {

struct Colour {
  uint8_t r, g, b;
};

constexpr Colour kPalette[] = {{31, 119, 180},  {255, 127, 14}, {44, 160, 44},   {214, 39, 40},
                               {148, 103, 189}, {140, 86, 75},  {227, 119, 194}, {127, 127, 127},
                               {188, 189, 34},  {23, 190, 207}};
constexpr Colour kInk{40, 40, 40};
constexpr Colour kGrid{220, 220, 220};

// A drawing surface with the few primitives the charts need, in pixels (y down).
struct Canvas {
  virtual ~Canvas() = default;
  virtual void line(double x0, double y0, double x1, double y1, Colour c, double width) = 0;
  virtual void rect(double x, double y, double w, double h, Colour c) = 0;
  // anchor: 0 left, 1 centre, 2 right; `size` is the text height in pixels.
  virtual void text(double x, double y, const std::string& s, double size, Colour c, int anchor,
                    bool vertical = false) = 0;
  // The width `text` gives `s`, in pixels (an estimate where the viewer picks the font).
  virtual double text_width(const std::string& s, double size) const = 0;
};

std::string hex(Colour c) {
  char buf[8];
  std::snprintf(buf, sizeof(buf), "#%02x%02x%02x", c.r, c.g, c.b);
  return buf;
}

std::string escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    if (ch == '<')
      out += "&lt;";
    else if (ch == '>')
      out += "&gt;";
    else if (ch == '&')
      out += "&amp;";
    else
      out += ch;
  }
  return out;
}

struct SvgCanvas : Canvas {
  std::ostringstream body;
  void line(double x0, double y0, double x1, double y1, Colour c, double width) override {
    body << "<line x1='" << x0 << "' y1='" << y0 << "' x2='" << x1 << "' y2='" << y1 << "' stroke='"
         << hex(c) << "' stroke-width='" << width << "'/>\n";
  }
  void rect(double x, double y, double w, double h, Colour c) override {
    body << "<rect x='" << x << "' y='" << y << "' width='" << w << "' height='" << h << "' fill='"
         << hex(c) << "'/>\n";
  }
  void text(double x, double y, const std::string& s, double size, Colour c, int anchor,
            bool vertical) override {
    const char* a = anchor == 0 ? "start" : anchor == 1 ? "middle" : "end";
    body << "<text x='" << x << "' y='" << y << "' font-family='sans-serif' font-size='" << size
         << "' fill='" << hex(c) << "' text-anchor='" << a << "' dominant-baseline='middle'";
    if (vertical) body << " transform='rotate(-90 " << x << " " << y << ")'";
    body << ">" << escape(s) << "</text>\n";
  }
  // Sans-serif glyphs average about 0.55 em; 0.6 leaves room for wide ones.
  double text_width(const std::string& s, double size) const override {
    return 0.6 * size * double(s.size());
  }
};

struct PngCanvas : Canvas {
  Image8 image;
  PngCanvas(uint32_t w, uint32_t h)
      : image{w, h, std::vector<glm::u8vec4>(size_t(w) * h, {255, 255, 255, 255})} {}
  void plot(int x, int y, Colour c) {
    if (x < 0 || y < 0 || x >= int(image.width) || y >= int(image.height)) return;
    image.at(uint32_t(x), uint32_t(y)) = {c.r, c.g, c.b, 255};
  }
  void rect(double x, double y, double w, double h, Colour c) override {
    for (int yy = int(std::lround(y)); yy < int(std::lround(y + h)); ++yy) {
      for (int xx = int(std::lround(x)); xx < int(std::lround(x + w)); ++xx) plot(xx, yy, c);
    }
  }
  void line(double x0, double y0, double x1, double y1, Colour c, double width) override {
    const double len = std::max(std::abs(x1 - x0), std::abs(y1 - y0));
    const int steps = std::max(1, int(std::ceil(len * 2)));
    const double r = std::max(0.5, width / 2);
    for (int i = 0; i <= steps; ++i) {
      const double t = double(i) / steps;
      rect(x0 + (x1 - x0) * t - r, y0 + (y1 - y0) * t - r, 2 * r, 2 * r, c);
    }
  }
  void text(double x, double y, const std::string& s, double size, Colour c, int anchor,
            bool vertical) override {
    // stb_easy_font draws 7 px tall glyphs as quads; scale them to `size`.
    static char buffer[200000];
    double scale = std::max(1.0, std::round(size / 9.0));
    // A line wider than the image (a long title) at the smallest scale rather than cut off.
    const double unscaled = stb_easy_font_width(const_cast<char*>(s.c_str()));
    while (scale > 1 && unscaled * scale > image.width) scale -= 1;
    const double w = unscaled * scale;
    const double h = 7 * scale;
    const double ox = anchor == 0 ? 0 : anchor == 1 ? -w / 2 : -w;
    const int quads =
        stb_easy_font_print(0, 0, const_cast<char*>(s.c_str()), nullptr, buffer, sizeof(buffer));
    for (int q = 0; q < quads; ++q) {
      const float* v =
          reinterpret_cast<const float*>(buffer + q * 4 * 16);  // 4 vertices of 16 bytes
      const double qx = v[0] * scale + ox, qy = v[1] * scale - h / 2;
      const double qw = (v[8] - v[0]) * scale, qh = (v[9] - v[1]) * scale;
      if (!vertical) {
        rect(x + qx, y + qy, qw, qh, c);
      } else {  // rotated a quarter turn counter-clockwise about (x, y)
        rect(x + qy, y - qx - qw, qh, qw, c);
      }
    }
  }
  double text_width(const std::string& s, double size) const override {
    const double scale = std::max(1.0, std::round(size / 9.0));
    return stb_easy_font_width(const_cast<char*>(s.c_str())) * scale;
  }
};

std::string format_number(double v) {
  char buf[32];
  if (v >= 1e6 || (v < 1e-3 && v > 0)) {
    std::snprintf(buf, sizeof(buf), "%.0e", v);
  } else if (v >= 1) {
    std::snprintf(buf, sizeof(buf), "%g", v);
  } else {
    std::snprintf(buf, sizeof(buf), "%.3g", v);
  }
  return buf;
}

struct Box {
  double x, y, w, h;
};

// Log-log axes over [xmin, xmax] x [ymin, ymax] (all > 0), rounded out to powers of ten.
struct LogAxes {
  Box b;
  double lx0, lx1, ly0, ly1;
  double px(double x) const { return b.x + (std::log10(x) - lx0) / (lx1 - lx0) * b.w; }
  double py(double y) const { return b.y + b.h - (std::log10(y) - ly0) / (ly1 - ly0) * b.h; }
};

LogAxes draw_log_axes(Canvas& c, Box b, double xmin, double xmax, double ymin, double ymax,
                      const std::string& x_label, const std::string& y_label) {
  LogAxes a{b, std::floor(std::log10(xmin)), 0, std::floor(std::log10(ymin)), 0};
  a.lx1 = std::max(a.lx0 + 1, std::ceil(std::log10(xmax)));
  a.ly1 = std::max(a.ly0 + 1, std::ceil(std::log10(ymax)));
  // Lines at 1, 2 and 5 times each power of ten when the axis spans at most two decades (a
  // single decade of lines says little), at the powers of ten alone otherwise.
  auto ticks = [](double l0, double l1) {
    std::vector<double> t;
    const bool fine = l1 - l0 <= 2;
    for (double e = l0; e <= l1; ++e) {
      for (double m : {1.0, 2.0, 5.0}) {
        if ((m == 1.0 || fine) && (e < l1 || m == 1.0)) t.push_back(m * std::pow(10, e));
      }
    }
    return t;
  };
  for (double v : ticks(a.lx0, a.lx1)) {
    c.line(a.px(v), b.y, a.px(v), b.y + b.h, kGrid, 1);
    c.text(a.px(v), b.y + b.h + 14, format_number(v), 12, kInk, 1);
  }
  for (double v : ticks(a.ly0, a.ly1)) {
    c.line(b.x, a.py(v), b.x + b.w, a.py(v), kGrid, 1);
    c.text(b.x - 6, a.py(v), format_number(v), 12, kInk, 2);
  }
  c.line(b.x, b.y + b.h, b.x + b.w, b.y + b.h, kInk, 1);
  c.line(b.x, b.y, b.x, b.y + b.h, kInk, 1);
  c.text(b.x + b.w / 2, b.y + b.h + 34, x_label, 13, kInk, 1);
  c.text(b.x - 58, b.y + b.h / 2, y_label, 13, kInk, 1, true);
  return a;
}

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
  const LogAxes axes = draw_log_axes(c, b, xmin, xmax, ymin, ymax, spec.x_label, spec.y_label);
  auto px = [&](double x) { return axes.px(x); };
  auto py = [&](double y) { return axes.py(y); };
  for (size_t k = 0; k < spec.lines.size(); ++k) {
    const Series& s = spec.lines[k];
    const Colour col = kPalette[k % std::size(kPalette)];
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
      c.rect(b.x + slot * (i + 0.15), y0, slot * 0.7, v / ymax * b.h,
             kPalette[l % std::size(kPalette)]);
      base += v;
    }
    c.text(b.x + slot * (i + 0.5), b.y + b.h + 14, bars.categories[i], 12, kInk, 1);
  }
  c.line(b.x, b.y + b.h, b.x + b.w, b.y + b.h, kInk, 1);
  c.text(b.x + b.w / 2, b.y + b.h + 34, spec.x_label, 13, kInk, 1);
  for (size_t l = 0; l < bars.layers.size(); ++l) {
    c.rect(b.x + b.w + 12, b.y + 18 * l, 14, 10, kPalette[l % std::size(kPalette)]);
    c.text(b.x + b.w + 32, b.y + 5 + 18 * l, bars.layers[l], 12, kInk, 0);
  }
}

void draw(Canvas& c, double width, double height, const ChartSpec& spec) {
  c.rect(0, 0, width, height, {255, 255, 255});
  c.text(width / 2, 22, spec.title, 16, kInk, 1);
  const bool two = !spec.bars.categories.empty();
  const double panel = two ? (width - 80) / 2 : width - 80;
  draw_lines(c, {80, 60, panel - 60, height - 130}, spec);
  if (two) draw_bars(c, {80 + panel + 20, 60, panel - 150, height - 130}, spec);
}

void draw_scatter(Canvas& c, double width, double height, const ScatterChart& chart) {
  c.rect(0, 0, width, height, {255, 255, 255});
  c.text(width / 2, 22, chart.title, 16, kInk, 1);
  double xmin = 1e300, xmax = 0, ymin = 1e300, ymax = 0;
  for (const ScatterSeries& s : chart.series) {
    for (const ScatterPoint& p : s.points) {
      if (!(p.x > 0) || !(p.y > 0) || !std::isfinite(p.x) || !std::isfinite(p.y)) continue;
      xmin = std::min(xmin, p.x);
      xmax = std::max(xmax, p.x);
      ymin = std::min(ymin, p.y);
      ymax = std::max(ymax, p.y);
    }
  }
  if (xmax == 0) return;
  const Box b{90, 60, width - 330, height - 130};
  const LogAxes a = draw_log_axes(c, b, xmin, xmax, ymin, ymax, chart.x_label, chart.y_label);
  // Labels of every series, placed together so that no two overlap (place_labels): the
  // Pareto fronts' first, as they matter most.
  struct Label {
    LabelRequest request;
    const std::string* text;
    Colour colour;
    bool front;
  };
  std::vector<Label> labels;
  std::vector<LabelSegment> lines;  // the fronts' joins, which labels keep off
  for (size_t k = 0; k < chart.series.size(); ++k) {
    const ScatterSeries& s = chart.series[k];
    const Colour col = kPalette[k % std::size(kPalette)];
    std::vector<const ScatterPoint*> front;
    for (const ScatterPoint& p : s.points) {
      if (!(p.x > 0) || !(p.y > 0) || !std::isfinite(p.x) || !std::isfinite(p.y)) continue;
      if (p.on_front) front.push_back(&p);
      const double r = p.on_front ? 5 : 3;
      c.rect(a.px(p.x) - r, a.py(p.y) - r, 2 * r, 2 * r, col);
      const LabelRequest request{a.px(p.x), a.py(p.y), r, c.text_width(p.label, 10), 10};
      labels.push_back({request, &p.label, col, p.on_front});
    }
    std::sort(front.begin(), front.end(),
              [](const ScatterPoint* p, const ScatterPoint* q) { return p->x < q->x; });
    for (size_t i = 0; i + 1 < front.size(); ++i) {
      const LabelSegment join{a.px(front[i]->x), a.py(front[i]->y), a.px(front[i + 1]->x),
                              a.py(front[i + 1]->y)};
      c.line(join.x0, join.y0, join.x1, join.y1, col, 1.5);
      lines.push_back(join);
    }
    c.rect(b.x + b.w + 20, b.y + 18 * k, 14, 10, col);
    c.text(b.x + b.w + 40, b.y + 5 + 18 * k, s.name, 12, kInk, 0);
  }
  std::stable_sort(labels.begin(), labels.end(),
                   [](const Label& p, const Label& q) { return p.front && !q.front; });
  std::vector<LabelRequest> requests;
  for (const Label& l : labels) requests.push_back(l.request);
  // Inside the axes by a few pixels, so that no label touches them (the plot's top may take
  // labels up to the title's margin; the right side up to the legend's).
  const LabelRect bounds{b.x + 3, b.y - 20, b.w + 7, b.h + 20 - 3};
  const std::vector<LabelSpot> spots = place_labels(requests, bounds, lines);
  for (size_t i = 0; i < labels.size(); ++i) {
    const LabelRect& box = spots[i].box;
    if (spots[i].leader) {
      const LabelSegment leader = leader_line(labels[i].request, box);
      c.line(leader.x0, leader.y0, leader.x1, leader.y1, labels[i].colour, 0.6);
    }
    c.text(box.x, box.y + box.h / 2, *labels[i].text, 10, labels[i].colour, 0);
  }
  double note_y = b.y + 18 * chart.series.size() + 20;
  c.text(b.x + b.w + 20, note_y, "large marks, joined:", 11, kInk, 0);
  c.text(b.x + b.w + 20, note_y + 14, "each knob's Pareto front", 11, kInk, 0);
  note_y += 14;
  for (const std::string& note : chart.notes) {
    note_y += 14;
    c.text(b.x + b.w + 20, note_y, note, 11, kInk, 0);
  }
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return has_extension(s, suffix);
}

}  // namespace

namespace {

// Draws with `paint` onto an SVG or PNG canvas of width x height, chosen by `path`'s suffix.
template <typename Paint>
void write_canvas(const std::string& path, double width, double height, Paint paint) {
  if (ends_with(path, ".svg")) {
    SvgCanvas svg;
    paint(svg);
    std::ofstream f(path);
    f << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << height
      << "' viewBox='0 0 " << width << " " << height << "'>\n"
      << svg.body.str() << "</svg>\n";
    if (!f) throw Error("cannot write chart '" + path + "'");
    return;
  }
  if (!ends_with(path, ".png")) throw Error("chart '" + path + "' must end in .svg or .png");
  PngCanvas png{static_cast<uint32_t>(width), static_cast<uint32_t>(height)};
  paint(png);
  write_png(path, png.image);
}

}  // namespace

void write_chart(const std::string& path, const ChartSpec& spec) {
  const double width = spec.bars.categories.empty() ? 700 : 1300, height = 520;
  write_canvas(path, width, height, [&](Canvas& c) { draw(c, width, height, spec); });
}

void write_scatter_chart(const std::string& path, const ScatterChart& chart) {
  const double width = 1000, height = 600;
  write_canvas(path, width, height, [&](Canvas& c) { draw_scatter(c, width, height, chart); });
}

}  // namespace tessera
