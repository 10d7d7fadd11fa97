#include "host/canvas.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/check.h"
#include "core/file_extension.h"
#include "core/image.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

namespace tessera {
namespace {

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

// Sans-serif glyphs average about 0.55 em; 0.6 leaves room for wide ones.
double svg_text_width(const std::string& s, double size) {
  return 0.6 * size * double(s.size());
}

// stb_easy_font draws 7 px tall glyphs; PngCanvas scales them by whole steps to `size`.
double png_text_scale(double size) {
  return std::max(1.0, std::round(size / 9.0));
}

double png_text_width(const std::string& s, double size) {
  return stb_easy_font_width(const_cast<char*>(s.c_str())) * png_text_scale(size);
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
  double text_width(const std::string& s, double size) const override {
    return svg_text_width(s, size);
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
    double scale = png_text_scale(size);
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
    return png_text_width(s, size);
  }
};

bool ends_with(const std::string& s, const std::string& suffix) {
  return has_extension(s, suffix);
}

}  // namespace

Colour palette(size_t k) {
  return kPalette[k % std::size(kPalette)];
}

bool series_hollow(size_t k) {
  return (k / 10) % 2 == 1;
}

TextWidth text_width_for(const std::string& path) {
  return ends_with(path, ".svg") ? svg_text_width : png_text_width;
}

void write_canvas(const std::string& path, double width, double height,
                  const std::function<void(Canvas&)>& paint) {
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

double LogAxes::px(double x) const {
  return b.x + (std::log10(x) - lx0) / (lx1 - lx0) * b.w;
}

double LogAxes::py(double y) const {
  return b.y + b.h - (std::log10(y) - ly0) / (ly1 - ly0) * b.h;
}

LogAxes log_axes(Box b, double xmin, double xmax, double ymin, double ymax) {
  LogAxes a{b, std::floor(std::log10(xmin)), 0, std::floor(std::log10(ymin)), 0};
  a.lx1 = std::max(a.lx0 + 1, std::ceil(std::log10(xmax)));
  a.ly1 = std::max(a.ly0 + 1, std::ceil(std::log10(ymax)));
  return a;
}

void draw_title(Canvas& c, double width, const std::string& title) {
  constexpr double kSize = 16;
  // The ", " nearest the middle, where the title does not fit on one line.
  size_t best = std::string::npos;
  if (c.text_width(title, kSize) > width - 20) {
    const auto gap = [&](size_t i) { return std::abs(double(i) - double(title.size()) / 2); };
    for (size_t at = title.find(", "); at != std::string::npos; at = title.find(", ", at + 1))
      if (best == std::string::npos || gap(at) < gap(best)) best = at;
  }
  if (best == std::string::npos) {  // it fits, or has nowhere to break: one line
    c.text(width / 2, 22, title, kSize, kInk, 1);
    return;
  }
  c.text(width / 2, 11, title.substr(0, best + 1), kSize, kInk, 1);
  c.text(width / 2, 28, title.substr(best + 2), kSize, kInk, 1);
}

void draw_log_axes(Canvas& c, const LogAxes& a, const std::string& x_label,
                   const std::string& y_label) {
  const Box& b = a.b;
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
}

}  // namespace tessera
