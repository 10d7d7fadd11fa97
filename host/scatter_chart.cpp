// The scatter chart of host/chart.h: each series' points as marks, its front joined, every mark
// labelled by place_labels (host/label_layout.h). A label with no room beside its point, or at
// the end of a leader, goes by number into a list under the legend, which makes the chart as
// much taller as it needs.
#include <algorithm>
#include <cmath>

#include "host/canvas.h"
#include "host/chart.h"
#include "host/label_layout.h"

namespace tessera {
namespace {

constexpr double kWidth = 1000;
constexpr double kMinHeight = 600;
constexpr double kLabelSize = 10;
constexpr double kNoteSize = 11;
constexpr double kNoteLine = 14;
constexpr double kLeaderShort = 1.5;  // pixels between a leader's end and its label

bool drawable(const ScatterPoint& p) {
  return p.x > 0 && p.y > 0 && std::isfinite(p.x) && std::isfinite(p.y);
}

struct PointLabel {
  LabelRequest request;
  LabelSpot spot;
  const ScatterPoint* point;
  size_t series;
  size_t order;  // in the series' order, which the marks are drawn in
};

struct Join {
  LabelSegment line;
  size_t series;
};

struct NoteLine {
  std::string text;
  Colour colour;
};

struct ScatterLayout {
  double height = kMinHeight;
  bool empty = true;  // no point can be drawn
  LogAxes axes{};
  std::vector<PointLabel> labels;  // the fronts' first
  std::vector<Join> joins;
  double notes_y = 0;           // the first line under the legend
  std::vector<NoteLine> notes;  // lines under the legend, kNoteLine apart
};

// `text` in lines of at most `width` pixels where it has spaces to break at; the lines after
// the first start with `indent`.
std::vector<std::string> wrap(const std::string& text, double width, TextWidth text_width,
                              const std::string& indent) {
  std::vector<std::string> lines;
  std::string line;
  bool first_word = true;  // of the line
  for (size_t at = 0; at <= text.size();) {
    const size_t end = std::min(text.find(' ', at), text.size());
    const std::string word = text.substr(at, end - at);
    at = end + 1;
    if (first_word) {
      line += word;
      first_word = false;
    } else if (text_width(line + " " + word, kNoteSize) > width) {
      lines.push_back(line);
      line = indent + word;
    } else {
      line += " " + word;
    }
  }
  lines.push_back(line);
  return lines;
}

ScatterLayout layout_scatter(const ScatterChart& chart, TextWidth text_width) {
  ScatterLayout out;
  double xmin = 1e300, xmax = 0, ymin = 1e300, ymax = 0;
  for (const ScatterSeries& s : chart.series) {
    for (const ScatterPoint& p : s.points) {
      if (!drawable(p)) continue;
      xmin = std::min(xmin, p.x);
      xmax = std::max(xmax, p.x);
      ymin = std::min(ymin, p.y);
      ymax = std::max(ymax, p.y);
    }
  }
  if (xmax == 0) return out;
  out.empty = false;
  // The plot keeps its size when the list of numbered labels lengthens the chart.
  const Box b{90, 60, kWidth - 330, kMinHeight - 130};
  out.axes = log_axes(b, xmin, xmax, ymin, ymax);
  const LogAxes& a = out.axes;
  for (size_t k = 0; k < chart.series.size(); ++k) {
    std::vector<const ScatterPoint*> front;
    for (const ScatterPoint& p : chart.series[k].points) {
      if (!drawable(p)) continue;
      if (p.on_front) front.push_back(&p);
      const double r = p.on_front ? 5 : 3;
      const LabelRequest request{a.px(p.x), a.py(p.y), r, text_width(p.label, kLabelSize),
                                 kLabelSize};
      out.labels.push_back({request, {}, &p, k, out.labels.size()});
    }
    std::sort(front.begin(), front.end(),
              [](const ScatterPoint* p, const ScatterPoint* q) { return p->x < q->x; });
    for (size_t i = 0; i + 1 < front.size(); ++i) {
      out.joins.push_back(
          {{a.px(front[i]->x), a.py(front[i]->y), a.px(front[i + 1]->x), a.py(front[i + 1]->y)},
           k});
    }
  }
  // Labels of every series placed together, the Pareto fronts' first, as they matter most.
  std::stable_sort(out.labels.begin(), out.labels.end(),
                   [](const PointLabel& p, const PointLabel& q) {
                     return p.point->on_front && !q.point->on_front;
                   });
  const std::string widest = std::to_string(out.labels.size());
  const double number_width = text_width(widest, kLabelSize);
  const double range_width = text_width(widest + "-" + widest, kLabelSize);
  std::vector<LabelRequest> requests;
  for (PointLabel& l : out.labels) {
    l.request.number_width = number_width;
    l.request.range_width = range_width;
    requests.push_back(l.request);
  }
  std::vector<LabelSegment> lines;  // the fronts' joins, which labels keep off
  for (const Join& j : out.joins) lines.push_back(j.line);
  // Inside the axes by a few pixels, so that no label touches them (the plot's top may take
  // labels up to the title's margin; the right side up to the legend's).
  const LabelRect bounds{b.x + 3, b.y - 20, b.w + 7, b.h + 20 - 3};
  const std::vector<LabelSpot> spots = place_labels(requests, bounds, lines);
  for (size_t i = 0; i < spots.size(); ++i) out.labels[i].spot = spots[i];

  // Under the legend: what the large marks are, the caller's notes, the numbered labels.
  const double column = b.x + b.w + 20, column_width = kWidth - column - 10;
  out.notes_y = b.y + 18 * chart.series.size() + 20;
  out.notes = {{"large marks, joined:", kInk}, {"each knob's Pareto front", kInk}};
  for (const std::string& note : chart.notes) out.notes.push_back({note, kInk});
  std::vector<const PointLabel*> numbered;
  for (const PointLabel& l : out.labels)
    if (l.spot.number > 0) numbered.push_back(&l);
  std::sort(numbered.begin(), numbered.end(), [](const PointLabel* p, const PointLabel* q) {
    return p->spot.number < q->spot.number;
  });
  if (!numbered.empty()) {
    out.notes.push_back({"", kInk});
    out.notes.push_back({"numbered marks (no room for", kInk});
    out.notes.push_back({"their labels beside them):", kInk});
  }
  for (const PointLabel* l : numbered) {
    const std::string entry = std::to_string(l->spot.number) + " " + chart.series[l->series].name +
                              ": " + l->point->label;
    for (const std::string& line : wrap(entry, column_width, text_width, "    "))
      out.notes.push_back({line, palette(l->series)});
  }
  out.height =
      std::max(kMinHeight, std::ceil(out.notes_y + kNoteLine * double(out.notes.size()) + 10));
  return out;
}

// A series' mark or legend swatch: filled, or an outline for series_hollow's series.
void mark(Canvas& c, double x, double y, double w, double h, size_t series) {
  const Colour colour = palette(series);
  if (!series_hollow(series)) {
    c.rect(x, y, w, h, colour);
    return;
  }
  const double t = 1.5;  // the outline's width, as the fronts' lines
  c.rect(x, y, w, t, colour);
  c.rect(x, y + h - t, w, t, colour);
  c.rect(x, y, t, h, colour);
  c.rect(x + w - t, y, t, h, colour);
}

void draw_scatter(Canvas& c, const ScatterChart& chart, const ScatterLayout& layout) {
  c.rect(0, 0, kWidth, layout.height, {255, 255, 255});
  draw_title(c, kWidth, chart.title);
  if (layout.empty) return;
  const LogAxes& a = layout.axes;
  const Box& b = a.b;
  draw_log_axes(c, a, chart.x_label, chart.y_label);
  std::vector<const PointLabel*> marks;
  for (const PointLabel& l : layout.labels) marks.push_back(&l);
  std::sort(marks.begin(), marks.end(),
            [](const PointLabel* p, const PointLabel* q) { return p->order < q->order; });
  for (const PointLabel* l : marks) {
    const double r = l->request.mark;
    mark(c, l->request.x - r, l->request.y - r, 2 * r, 2 * r, l->series);
  }
  for (const Join& j : layout.joins)
    c.line(j.line.x0, j.line.y0, j.line.x1, j.line.y1, palette(j.series), 1.5);
  for (size_t k = 0; k < chart.series.size(); ++k) {
    mark(c, b.x + b.w + 20, b.y + 18 * k, 14, 10, k);
    c.text(b.x + b.w + 40, b.y + 5 + 18 * k, chart.series[k].name, 12, kInk, 0);
  }
  for (const PointLabel& l : layout.labels) {
    // The labels of a range share its box: drawn once, with the first's leader.
    if (l.spot.number > 0 && l.spot.number != l.spot.tag_first) continue;
    std::string text = l.point->label;
    if (l.spot.number > 0) text = std::to_string(l.spot.tag_first);
    const bool range = l.spot.tag_last > l.spot.tag_first;
    if (range) {
      text += '-';
      text += std::to_string(l.spot.tag_last);
    }
    // A range may hold several knobs' settings: in ink, not one knob's colour.
    const Colour colour = range ? kInk : palette(l.series);
    const LabelRect& box = l.spot.box;
    if (l.spot.leader) {
      // Stopped short of the box: a line that reaches it runs into the text's first glyph.
      const LabelSegment leader = leader_line(l.request, box);
      const double length = std::hypot(leader.x1 - leader.x0, leader.y1 - leader.y0);
      const double t = length > 0 ? std::max(0.0, 1.0 - kLeaderShort / length) : 0.0;
      c.line(leader.x0, leader.y0, leader.x0 + (leader.x1 - leader.x0) * t,
             leader.y0 + (leader.y1 - leader.y0) * t, colour, 0.6);
    }
    c.text(box.x, box.y + box.h / 2, text, kLabelSize, colour, 0);
  }
  for (size_t i = 0; i < layout.notes.size(); ++i) {
    c.text(b.x + b.w + 20, layout.notes_y + kNoteLine * double(i), layout.notes[i].text, kNoteSize,
           layout.notes[i].colour, 0);
  }
}

}  // namespace

void write_scatter_chart(const std::string& path, const ScatterChart& chart) {
  const ScatterLayout layout = layout_scatter(chart, text_width_for(path));
  write_canvas(path, kWidth, layout.height, [&](Canvas& c) { draw_scatter(c, chart, layout); });
}

}  // namespace tessera
