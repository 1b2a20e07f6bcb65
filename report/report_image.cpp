// Falsecolour plan images through OpenImageIO: ImageBufAlgo::color_map for the palette,
// render_text for the legend. Built as a module that the daylit executable loads only when an
// image is asked for (image_module.cpp): OpenImageIO brings some 250 shared libraries whose
// loading took 0.3 s of every run, images or not.

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <limits>

#include <fmt/format.h>

#include "report/reports.hpp"
#include "geometry/error.hpp"

namespace daylit::cli {

namespace {

namespace IBA = OIIO::ImageBufAlgo;

// Smallest spacing between distinct sorted coordinates, ignoring differences below `noise`.
double grid_step(std::vector<double> values, double noise) {
  std::sort(values.begin(), values.end());
  double step = 0;
  for (std::size_t i = 1; i < values.size(); ++i) {
    const double d = values[i] - values[i - 1];
    if (d > noise && (step == 0 || d < step)) step = d;
  }
  return step;
}

// Round numbers of the 1, 2, 5 series: the next at or above x (the top of a scale) and the next
// at or below it (the bottom of a log scale).
double nice_ceiling(double x) {
  if (!(x > 0)) return 1;
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * decade >= x * (1 - 1e-12)) return m * decade;
  return 10 * decade;
}
double nice_floor(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * decade <= x * (1 + 1e-12)) return m * decade;
  return decade;
}

// Where a value falls on the colour scale, 0 (bottom) to 1 (top).
struct ColourScale {
  bool logarithmic = false;
  double low = 0, high = 1;
  double position(double v) const {
    const double t = logarithmic ? (v > 0 ? std::log(v / low) / std::log(high / low) : 0.0) : (v - low) / (high - low);
    return std::clamp(t, 0.0, 1.0);
  }
};

ColourScale colour_scale(const ImageScale& asked, std::vector<double> values) {
  ColourScale c;
  c.logarithmic = asked.logarithmic;
  std::sort(values.begin(), values.end());
  c.high = asked.high.value_or(values.empty() ? 1 : nice_ceiling(values[std::size_t(0.95 * double(values.size() - 1))]));
  if (!c.logarithmic) {
    c.low = asked.low.value_or(0);
  } else {
    std::vector<double> positive;
    for (double v : values)
      if (v > 0) positive.push_back(v);
    const double floor = positive.empty() ? 0 : nice_floor(positive[std::size_t(0.05 * double(positive.size() - 1))]);
    c.low = asked.low.value_or(std::max(floor, c.high * 1e-3));
  }
  // The CLI checks a range it is given; a default top at or below a given bottom is raised.
  if (!(c.high > c.low)) c.high = c.low > 0 ? nice_ceiling(2 * c.low) : 1;
  return c;
}

// The legend's labelled values: five even steps, or on a log scale the 1, 2, 5 series within the
// range (the decades alone where that would crowd the bar), with both ends.
std::vector<double> legend_ticks(const ColourScale& c) {
  if (!c.logarithmic) {
    std::vector<double> t;
    for (int k = 0; k <= 4; ++k) t.push_back(c.low + (c.high - c.low) * k / 4.0);
    return t;
  }
  for (const auto& series : {std::vector<double>{1, 2, 5}, std::vector<double>{1}}) {
    std::vector<double> t{c.low};
    for (double decade = std::pow(10.0, std::floor(std::log10(c.low))); decade <= c.high; decade *= 10)
      for (double m : series) {
        const double v = m * decade;
        if (v > c.low * (1 + 1e-9) && v < c.high * (1 - 1e-9)) t.push_back(v);
      }
    t.push_back(c.high);
    if (t.size() <= 8 || series.size() == 1) return t;
  }
  return {c.low, c.high};
}

// Keeps the part of segment s inside [x0, x1] × [y0, y1] (Liang–Barsky); false where none is.
bool clip_segment(PlanSegment& s, double x0, double x1, double y0, double y1) {
  double t0 = 0, t1 = 1;
  const double dx = s.x1 - s.x0, dy = s.y1 - s.y0;
  const double p[4] = {-dx, dx, -dy, dy}, q[4] = {s.x0 - x0, x1 - s.x0, s.y0 - y0, y1 - s.y0};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;
      continue;
    }
    const double r = q[i] / p[i];
    if (p[i] < 0)
      t0 = std::max(t0, r);
    else
      t1 = std::min(t1, r);
    if (t0 > t1) return false;
  }
  s = {s.x0 + t0 * dx, s.y0 + t0 * dy, s.x0 + t1 * dx, s.y0 + t1 * dy};
  return true;
}

std::string font_path() {
  for (const char* p : {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/TTF/DejaVuSans.ttf"})
    if (std::filesystem::exists(p)) return p;
  return "";
}

void text(OIIO::ImageBuf& canvas, int x, int y, const std::string& s, int size,
          OIIO::ImageBufAlgo::TextAlignX align = OIIO::ImageBufAlgo::TextAlignX::Left) {
  const float black[3] = {0.05f, 0.05f, 0.05f};
  if (!IBA::render_text(canvas, x, y, s, size, font_path(), black, align))
    throw Error("cannot render the image legend (" + canvas.geterror() +
                "); install the DejaVu fonts (Debian package fonts-dejavu-core)");
}

}  // namespace

namespace {

void write_image(const std::string& path, const GridReport& report) {
  const auto& sensors = report.grid->sensors;
  const std::vector<double>& shown = report.image_values();
  std::vector<double> xs, ys;
  for (const auto& s : sensors) xs.push_back(s.position.x), ys.push_back(s.position.y);
  const auto [xmin_it, xmax_it] = std::minmax_element(xs.begin(), xs.end());
  const auto [ymin_it, ymax_it] = std::minmax_element(ys.begin(), ys.end());
  const double extent = std::max({*xmax_it - *xmin_it, *ymax_it - *ymin_it, 1e-9});
  double dx = grid_step(xs, 1e-9 * extent), dy = grid_step(ys, 1e-9 * extent);
  if (dx == 0) dx = dy > 0 ? dy : 1;
  if (dy == 0) dy = dx;
  // The plan's extent: the grid's cells, and the walls and apertures near them (within four cells
  // or a tenth of the grid: a grid 0.5 m from its room's walls shows them, and a window in the
  // outer face of a thick wall).
  double x0 = *xmin_it - 0.5 * dx, x1 = *xmax_it + 0.5 * dx, y0 = *ymin_it - 0.5 * dy, y1 = *ymax_it + 0.5 * dy;
  std::vector<PlanSegment> walls, apertures;
  if (report.plan != nullptr) {
    const double m = std::max({4 * dx, 4 * dy, 0.1 * extent});
    const double cx0 = x0 - m, cx1 = x1 + m, cy0 = y0 - m, cy1 = y1 + m;
    for (const auto& [from, to] : {std::pair{&report.plan->walls, &walls}, std::pair{&report.plan->apertures, &apertures}})
      for (PlanSegment seg : *from)
        if (clip_segment(seg, cx0, cx1, cy0, cy1)) to->push_back(seg);
    for (const auto* list : {&walls, &apertures})
      for (const PlanSegment& seg : *list) {
        x0 = std::min({x0, seg.x0, seg.x1}), x1 = std::max({x1, seg.x0, seg.x1});
        y0 = std::min({y0, seg.y0, seg.y1}), y1 = std::max({y1, seg.y0, seg.y1});
      }
    // A margin of a hundredth of the plan, so that a wall on its edge is drawn whole.
    const double pad = 0.01 * std::max(x1 - x0, y1 - y0);
    x0 -= pad, x1 += pad, y0 -= pad, y1 += pad;
  }
  const double width_m = x1 - x0, height_m = y1 - y0;
  const double pixels_per_m = 720.0 / std::max(width_m, height_m);
  const int map_w = std::max(1, int(std::lround(width_m * pixels_per_m)));
  const int map_h = std::max(1, int(std::lround(height_m * pixels_per_m)));

  const ColourScale scale = colour_scale(report.scale, shown);
  // Per pixel the value of the sensor whose cell covers it (NaN: none), north up.
  std::vector<float> pixel(std::size_t(map_w) * map_h, std::numeric_limits<float>::quiet_NaN());
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    const double cx = (sensors[i].position.x - x0) * pixels_per_m;
    const double cy = (y1 - sensors[i].position.y) * pixels_per_m;
    const int px0 = std::max(0, int(std::floor(cx - 0.5 * dx * pixels_per_m)));
    const int px1 = std::min(map_w, int(std::ceil(cx + 0.5 * dx * pixels_per_m)));
    const int py0 = std::max(0, int(std::floor(cy - 0.5 * dy * pixels_per_m)));
    const int py1 = std::min(map_h, int(std::ceil(cy + 0.5 * dy * pixels_per_m)));
    for (int y = py0; y < py1; ++y)
      for (int x = px0; x < px1; ++x) pixel[std::size_t(y) * map_w + x] = float(shown[i]);
  }
  OIIO::ImageBuf values(OIIO::ImageSpec(map_w, map_h, 1, OIIO::TypeDesc::FLOAT));
  for (int y = 0; y < map_h; ++y)
    for (int x = 0; x < map_w; ++x) {
      const float v = pixel[std::size_t(y) * map_w + x];
      const float t = std::isnan(v) ? 0.0f : float(scale.position(v));
      values.setpixel(x, y, &t);
    }
  OIIO::ImageBuf map = IBA::color_map(values, 0, "viridis");

  const int margin = 40, legend_w = 250, header_h = 70, footer_h = 40;
  const int width = margin + map_w + margin + legend_w, height = header_h + std::max(map_h, 320) + footer_h + 20;
  OIIO::ImageBuf canvas(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8));
  const float white[3] = {1, 1, 1}, grey[3] = {0.82f, 0.82f, 0.82f}, black[3] = {0.05f, 0.05f, 0.05f};
  IBA::fill(canvas, white);
  for (int y = 0; y < map_h; ++y)
    for (int x = 0; x < map_w; ++x) {
      float rgb[3];
      if (!std::isnan(pixel[std::size_t(y) * map_w + x]))
        map.getpixel(x, y, rgb, 3);
      else
        std::copy(grey, grey + 3, rgb);
      canvas.setpixel(margin + x, header_h + y, rgb, 3);
    }
  // Contours: the edges between neighbouring pixels whose values lie on either side of a level,
  // white over the dark end of the palette and black over the light end.
  const auto contour = [&](int x, int y) {
    float rgb[3];
    map.getpixel(x, y, rgb, 3);
    const bool dark = 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2] < 0.35f;
    canvas.setpixel(margin + x, header_h + y, dark ? white : black, 3);
  };
  for (const double level : report.scale.contours)
    for (int y = 0; y < map_h; ++y)
      for (int x = 0; x < map_w; ++x) {
        const float v = pixel[std::size_t(y) * map_w + x];
        if (std::isnan(v)) continue;
        for (const auto& [nx, ny] : {std::pair{x + 1, y}, std::pair{x, y + 1}}) {
          if (nx >= map_w || ny >= map_h) continue;
          const float w = pixel[std::size_t(ny) * map_w + nx];
          if (std::isnan(w) || (v >= level) == (w >= level)) continue;
          for (const auto& [cx, cy] : {std::pair{x, y}, std::pair{nx, ny}}) contour(cx, cy);
        }
      }
  // Walls dark, apertures blue over them, three pixels wide.
  const auto draw = [&](const std::vector<PlanSegment>& segments, const float* rgb) {
    for (const PlanSegment& seg : segments) {
      const double ax = (seg.x0 - x0) * pixels_per_m, ay = (y1 - seg.y0) * pixels_per_m;
      const double bx = (seg.x1 - x0) * pixels_per_m, by = (y1 - seg.y1) * pixels_per_m;
      const int steps = std::max(1, int(std::ceil(2 * std::hypot(bx - ax, by - ay))));
      for (int k = 0; k <= steps; ++k) {
        const double t = double(k) / steps;
        const int px = int(std::lround(ax + t * (bx - ax))), py = int(std::lround(ay + t * (by - ay)));
        for (int oy = -1; oy <= 1; ++oy)
          for (int ox = -1; ox <= 1; ++ox)
            if (px + ox >= 0 && px + ox < map_w && py + oy >= 0 && py + oy < map_h)
              canvas.setpixel(margin + px + ox, header_h + py + oy, rgb, 3);
      }
    }
  };
  const float wall_rgb[3] = {0.2f, 0.2f, 0.2f}, aperture_rgb[3] = {0.25f, 0.65f, 1.0f};
  draw(walls, wall_rgb);
  draw(apertures, aperture_rgb);

  const auto& st = report.statistics;
  const std::string& unit = report.shown_unit;
  text(canvas, margin, 28, fmt::format("{}, grid '{}'", report.shown_title, report.grid->name), 20);
  text(canvas, margin, 54,
       fmt::format("{0} {6}   mean {1:.4g} {5}   median {2:.4g} {5}   min {3:.4g} {5}   max {4:.4g} {5}", st.count,
                   st.mean, st.median, st.min, st.max, unit, report.cell_noun),
       14);
  std::string footer = report.footer;
  if (footer.empty()) {
    footer = fmt::format("plan view, +y up; {:.2f} m x {:.2f} m", width_m, height_m);
    if (report.plan != nullptr) footer += "; walls cut at the grid's height (dark), apertures from above (blue)";
  }
  text(canvas, margin, header_h + std::max(map_h, 320) + 28, footer, 14);

  // Legend: a vertical colour bar from the scale's bottom to its top, its ticks labelled; the
  // contour levels marked across it.
  const int bar_x = margin + map_w + margin, bar_y = header_h, bar_w = 28, bar_h = 300;
  OIIO::ImageBuf ramp(OIIO::ImageSpec(1, bar_h, 1, OIIO::TypeDesc::FLOAT));
  for (int y = 0; y < bar_h; ++y) {
    const float v = 1.0f - float(y) / float(bar_h - 1);
    ramp.setpixel(0, y, &v);
  }
  OIIO::ImageBuf ramp_rgb = IBA::color_map(ramp, 0, "viridis");
  for (int y = 0; y < bar_h; ++y) {
    float rgb[3];
    ramp_rgb.getpixel(0, y, rgb, 3);
    for (int x = 0; x < bar_w; ++x) canvas.setpixel(bar_x + x, bar_y + y, rgb, 3);
  }
  const auto bar_row = [&](double v) { return bar_y + int(std::lround((bar_h - 1) * (1 - scale.position(v)))); };
  const std::vector<double> ticks = legend_ticks(scale);
  for (std::size_t t = 0; t < ticks.size(); ++t) {
    const int y = bar_row(ticks[t]);
    for (int x = bar_w; x < bar_w + 6; ++x) canvas.setpixel(bar_x + x, y, black, 3);
    const bool top = t + 1 == ticks.size(), bottom = t == 0;
    const std::string mark = top && st.max > scale.high ? "+" : bottom && st.min < scale.low ? " or less" : "";
    text(canvas, bar_x + bar_w + 10, y + 5, fmt::format("{:g} {}{}", ticks[t], unit, mark), 14);
  }
  for (const double level : report.scale.contours)
    if (level >= scale.low && level <= scale.high)
      for (int x = 0; x < bar_w; ++x) canvas.setpixel(bar_x + x, bar_row(level), black, 3);
  // Under the bar the quantity's name, without its parenthesis where the whole would run past the
  // image's edge (the title above the map says it in full).
  std::string caption = report.shown_title;
  if (caption.size() > 30 && caption.find(" (") != std::string::npos) caption.resize(caption.find(" ("));
  text(canvas, bar_x, bar_y + bar_h + 24, caption + (scale.logarithmic ? ", log scale" : ""), 14);
  if (!report.scale.contours.empty()) {
    std::string levels;
    for (const double level : report.scale.contours) levels += (levels.empty() ? "" : ", ") + fmt::format("{:g}", level);
    text(canvas, bar_x, bar_y + bar_h + 44, fmt::format("contours: {} {}", levels, unit), 14);
  }

  if (!canvas.write(path)) throw Error(path + ": cannot write image (" + canvas.geterror() + ")");
}

}  // namespace

}  // namespace daylit::cli

// The module's one entry point. Errors come back as text (no exception crosses the boundary).
extern "C" bool daylit_write_falsecolour_image(const char* path, const daylit::cli::GridReport* report, char* error,
                                               std::size_t error_size) {
  try {
    daylit::cli::write_image(path, *report);
    return true;
  } catch (const std::exception& e) {
    std::snprintf(error, error_size, "%s", e.what());
    return false;
  }
}
