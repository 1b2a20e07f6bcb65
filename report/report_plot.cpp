// Log–log plots through OpenImageIO, in the image writer module (see report_image.cpp for why it
// is a module). Lines and markers are rasterised here with coverage-based antialiasing (the
// distance from each pixel centre to the shape); text is OpenImageIO's render_text with the
// DejaVu font, drawn last.

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include <fmt/format.h>

#include "report/plot.hpp"
#include "geometry/error.hpp"

namespace daylit::cli {

namespace {

namespace IBA = OIIO::ImageBufAlgo;

std::string font_path() {
  for (const char* p : {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/TTF/DejaVuSans.ttf"})
    if (std::filesystem::exists(p)) return p;
  return "";
}

// An RGB canvas of floats with "over" blending of a colour at a coverage in [0, 1].
class Raster {
 public:
  Raster(int width, int height) : width_(width), height_(height), rgb_(std::size_t(3) * width * height, 1.0f) {}

  void blend(int x, int y, const PlotColour& c, double coverage) {
    if (x < 0 || y < 0 || x >= width_ || y >= height_ || !(coverage > 0)) return;
    const float a = float(std::min(coverage, 1.0));
    float* p = &rgb_[(std::size_t(y) * width_ + x) * 3];
    p[0] += a * (c.r - p[0]);
    p[1] += a * (c.g - p[1]);
    p[2] += a * (c.b - p[2]);
  }

  // A segment of the given width (px); dash > 0: dashes of that length with gaps of half of it.
  void segment(double x0, double y0, double x1, double y1, double width, const PlotColour& c, double dash = 0) {
    const double dx = x1 - x0, dy = y1 - y0, length2 = dx * dx + dy * dy;
    const double r = 0.5 * width;
    const int xa = int(std::floor(std::min(x0, x1) - r - 1)), xb = int(std::ceil(std::max(x0, x1) + r + 1));
    const int ya = int(std::floor(std::min(y0, y1) - r - 1)), yb = int(std::ceil(std::max(y0, y1) + r + 1));
    for (int y = std::max(ya, 0); y <= std::min(yb, height_ - 1); ++y)
      for (int x = std::max(xa, 0); x <= std::min(xb, width_ - 1); ++x) {
        const double px = x + 0.5 - x0, py = y + 0.5 - y0;
        const double t = length2 > 0 ? std::clamp((px * dx + py * dy) / length2, 0.0, 1.0) : 0.0;
        if (dash > 0 && std::fmod(t * std::sqrt(length2), 1.5 * dash) > dash) continue;
        const double ex = px - t * dx, ey = py - t * dy;
        blend(x, y, c, r + 0.5 - std::sqrt(ex * ex + ey * ey));
      }
  }

  // A filled convex polygon (vertices in either order), coverage from the largest signed
  // distance to its edge lines.
  void convex(const std::vector<std::pair<double, double>>& v, const PlotColour& c) {
    double xa = 1e300, xb = -1e300, ya = 1e300, yb = -1e300, area = 0;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const auto& [x0, y0] = v[i];
      const auto& [x1, y1] = v[(i + 1) % v.size()];
      xa = std::min(xa, x0), xb = std::max(xb, x0), ya = std::min(ya, y0), yb = std::max(yb, y0);
      area += x0 * y1 - x1 * y0;
    }
    const double orientation = area > 0 ? 1 : -1;
    for (int y = std::max(int(ya) - 1, 0); y <= std::min(int(yb) + 1, height_ - 1); ++y)
      for (int x = std::max(int(xa) - 1, 0); x <= std::min(int(xb) + 1, width_ - 1); ++x) {
        double distance = -1e300;
        for (std::size_t i = 0; i < v.size(); ++i) {
          const auto& [x0, y0] = v[i];
          const auto& [x1, y1] = v[(i + 1) % v.size()];
          const double ex = x1 - x0, ey = y1 - y0, l = std::hypot(ex, ey);
          if (l == 0) continue;
          distance = std::max(distance, -orientation * (ex * (y + 0.5 - y0) - ey * (x + 0.5 - x0)) / l);
        }
        blend(x, y, c, 0.5 - distance);
      }
  }

  void disc(double cx, double cy, double r, const PlotColour& c) {
    for (int y = std::max(int(cy - r) - 1, 0); y <= std::min(int(cy + r) + 1, height_ - 1); ++y)
      for (int x = std::max(int(cx - r) - 1, 0); x <= std::min(int(cx + r) + 1, width_ - 1); ++x)
        blend(x, y, c, r + 0.5 - std::hypot(x + 0.5 - cx, y + 0.5 - cy));
  }

  OIIO::ImageBuf image() const {
    OIIO::ImageBuf out(OIIO::ImageSpec(width_, height_, 3, OIIO::TypeDesc::UINT8));
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) out.setpixel(x, y, &rgb_[(std::size_t(y) * width_ + x) * 3], 3);
    return out;
  }

 private:
  int width_, height_;
  std::vector<float> rgb_;
};

PlotColour darker(const PlotColour& c) { return {0.55f * c.r, 0.55f * c.g, 0.55f * c.b}; }

// A marker of radius r (px) centred at (x, y), with a darker rim so that overlapping markers of
// one colour stay distinct.
void draw_marker(Raster& canvas, PlotMarker marker, double x, double y, double r, const PlotColour& c) {
  const auto polygon = [&](double scale, std::initializer_list<std::pair<double, double>> unit) {
    std::vector<std::pair<double, double>> v;
    for (const auto& [ux, uy] : unit) v.push_back({x + scale * ux, y + scale * uy});
    return v;
  };
  const auto shape = [&](double s, const PlotColour& colour) {
    switch (marker) {
      case PlotMarker::none: break;
      case PlotMarker::circle: canvas.disc(x, y, s, colour); break;
      case PlotMarker::square: canvas.convex(polygon(s * 0.85, {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}), colour); break;
      case PlotMarker::triangle: canvas.convex(polygon(s * 1.25, {{0, -1}, {0.866, 0.5}, {-0.866, 0.5}}), colour); break;
      case PlotMarker::triangle_down: canvas.convex(polygon(s * 1.25, {{0, 1}, {0.866, -0.5}, {-0.866, -0.5}}), colour); break;
      case PlotMarker::diamond: canvas.convex(polygon(s * 1.25, {{0, -1}, {1, 0}, {0, 1}, {-1, 0}}), colour); break;
      case PlotMarker::cross:
        canvas.segment(x - s, y - s, x + s, y + s, s * 0.55, colour);
        canvas.segment(x - s, y + s, x + s, y - s, s * 0.55, colour);
        break;
    }
  };
  shape(r + 1.3, darker(c));
  if (marker != PlotMarker::cross) shape(r, c);
}

// The exponent of a decade label, ASCII: this render_text draws multi-byte UTF-8 as boxes.
std::string exponent_text(int exponent) { return std::to_string(exponent); }

struct Range {
  int low, high;  // decades: the axis runs from 10^low to 10^high
};

Range decade_range(double lo, double hi) {
  if (!(lo > 0) || !(hi >= lo)) return {0, 1};
  Range r{int(std::floor(std::log10(lo) + 1e-9)), int(std::ceil(std::log10(hi) - 1e-9))};
  if (r.high <= r.low) r.high = r.low + 1;
  return r;
}

void write_plot(const std::string& path, const Plot& plot) {
  const std::string font = font_path();
  const int width = plot.width, height = plot.height;
  int legend_text = 0;
  for (const auto& s : plot.series)
    if (!s.name.empty()) legend_text = std::max(legend_text, IBA::text_size(s.name, 15, font).width());
  const int legend_w = std::clamp(legend_text + 90, 200, width / 2), left = 92, top = plot.subtitle.empty() ? 62 : 84;
  const int bottom = 78 + 20 * int(plot.notes.size());
  const int px0 = left, px1 = width - legend_w, py0 = top, py1 = height - bottom;
  if (px1 - px0 < 200 || py1 - py0 < 200) throw Error("plot too small for its legend and notes");

  // Data ranges, with y clamped at the floor.
  double xlo = std::numeric_limits<double>::infinity(), xhi = 0, ylo = xlo, yhi = 0;
  bool clamped = false;
  const auto plotted_y = [&](double y) { return y < plot.y_floor || !(y > 0) ? plot.y_floor : y; };
  for (const auto& s : plot.series)
    for (const auto& [x, y] : s.points) {
      if (!(x > 0) || !std::isfinite(x) || !std::isfinite(y)) continue;
      if (!(plotted_y(y) > 0)) continue;
      clamped |= y < plot.y_floor;
      xlo = std::min(xlo, x), xhi = std::max(xhi, x);
      ylo = std::min(ylo, plotted_y(y)), yhi = std::max(yhi, plotted_y(y));
    }
  const Range xr = decade_range(xlo, xhi);
  Range yr = decade_range(ylo, yhi);
  if (clamped && std::log10(plot.y_floor) - yr.low < 0.5) --yr.low;  // keep the floor line off the frame
  // A margin of 3 % of each range, so that points on a decade stay clear of the frame.
  const double xpad = 0.03 * (xr.high - xr.low), ypad = 0.03 * (yr.high - yr.low);
  const auto X = [&](double x) { return px0 + (std::log10(x) - xr.low + xpad) / (xr.high - xr.low + 2 * xpad) * (px1 - px0); };
  const auto Y = [&](double y) { return py1 - (std::log10(y) - yr.low + ypad) / (yr.high - yr.low + 2 * ypad) * (py1 - py0); };

  Raster canvas(width, height);
  const PlotColour grid{0.88f, 0.88f, 0.88f}, ink{0.1f, 0.1f, 0.1f}, floor_colour{0.45f, 0.45f, 0.45f};
  // Decade grid lines and ticks, minor ticks at 2..9 × each decade.
  const int x_label_step = (xr.high - xr.low + 13) / 14, y_label_step = (yr.high - yr.low + 17) / 18;
  for (int k = xr.low; k <= xr.high; ++k) {
    const double x = X(std::pow(10.0, k));
    canvas.segment(x, py0, x, py1, 1, grid);
    canvas.segment(x, py1, x, py1 - 8, 1.5, ink);
    for (int m = 2; m < 10 && k < xr.high; ++m) canvas.segment(X(m * std::pow(10.0, k)), py1, X(m * std::pow(10.0, k)), py1 - 4, 1, ink);
  }
  for (int k = yr.low; k <= yr.high; ++k) {
    const double y = Y(std::pow(10.0, k));
    canvas.segment(px0, y, px1, y, 1, grid);
    canvas.segment(px0, y, px0 + 8, y, 1.5, ink);
    if (yr.high - yr.low <= 8)
      for (int m = 2; m < 10 && k < yr.high; ++m) canvas.segment(px0, Y(m * std::pow(10.0, k)), px0 + 4, Y(m * std::pow(10.0, k)), 1, ink);
  }
  if (clamped) canvas.segment(px0, Y(plot.y_floor), px1, Y(plot.y_floor), 1.5, floor_colour, 8);

  // Series: lines first, then markers over them.
  const auto visible = [&](const std::pair<double, double>& p) {
    return p.first > 0 && std::isfinite(p.first) && std::isfinite(p.second) && plotted_y(p.second) > 0;
  };
  for (const auto& s : plot.series) {
    if (!s.line) continue;
    const std::pair<double, double>* previous = nullptr;
    for (const auto& p : s.points) {
      if (!visible(p)) continue;
      if (previous) canvas.segment(X(previous->first), Y(plotted_y(previous->second)), X(p.first), Y(plotted_y(p.second)), 2.2, s.colour);
      previous = &p;
    }
  }
  for (const auto& s : plot.series)
    for (const auto& p : s.points)
      if (visible(p)) draw_marker(canvas, s.marker, X(p.first), Y(plotted_y(p.second)), 4.5, s.colour);

  // Frame.
  for (const auto& [xa, ya, xb, yb] : {std::array<double, 4>{double(px0), double(py0), double(px1), double(py0)},
                                        {double(px1), double(py0), double(px1), double(py1)},
                                        {double(px1), double(py1), double(px0), double(py1)},
                                        {double(px0), double(py1), double(px0), double(py0)}})
    canvas.segment(xa, ya, xb, yb, 1.5, ink);

  // Legend graphics.
  const int lx = px1 + 24, ly = py0 + 8, row = 24;
  int entries = 0;
  for (const auto& s : plot.series) {
    if (s.name.empty()) continue;
    const double y = ly + row * entries + 0.5 * row;
    if (s.line) canvas.segment(lx, y, lx + 34, y, 2.2, s.colour);
    draw_marker(canvas, s.marker, lx + 17, y, 4.5, s.colour);
    ++entries;
  }

  OIIO::ImageBuf image = canvas.image();
  const float black[3] = {0.05f, 0.05f, 0.05f}, grey[3] = {0.3f, 0.3f, 0.3f};
  const auto text = [&](int x, int y, const std::string& s, int size, IBA::TextAlignX ax = IBA::TextAlignX::Left,
                        IBA::TextAlignY ay = IBA::TextAlignY::Baseline, const float* colour = nullptr) {
    if (s.empty()) return;
    if (!IBA::render_text(image, x, y, s, size, font, OIIO::cspan<float>(colour ? colour : black, 3), ax, ay))
      throw Error("cannot render the plot's text (" + image.geterror() +
                  "); install the DejaVu fonts (Debian package fonts-dejavu-core)");
  };
  text(px0, 32, plot.title, 22);
  text(px0, 58, plot.subtitle, 15, IBA::TextAlignX::Left, IBA::TextAlignY::Baseline, grey);
  // "10" with its exponent raised and smaller; (x, baseline) is the label's left end.
  const auto label_width = [&](int k) {
    return IBA::text_size("10", 15, font).width() + IBA::text_size(exponent_text(k), 11, font).width() + 1;
  };
  const auto decade_label = [&](int x, int baseline, int k) {
    text(x, baseline, "10", 15);
    text(x + IBA::text_size("10", 15, font).width() + 1, baseline - 7, exponent_text(k), 11);
  };
  for (int k = xr.low; k <= xr.high; k += x_label_step)
    decade_label(int(std::lround(X(std::pow(10.0, k)))) - label_width(k) / 2, py1 + 24, k);
  for (int k = yr.low; k <= yr.high; k += y_label_step)
    decade_label(px0 - 10 - label_width(k), int(std::lround(Y(std::pow(10.0, k)))) + 5, k);
  text((px0 + px1) / 2, py1 + 50, plot.x_label, 16, IBA::TextAlignX::Center);
  text(px0 - 84, py0 - 12, plot.y_label, 16);
  if (clamped)
    text(px1 - 6, int(std::lround(Y(plot.y_floor))) - 6, fmt::format("values below {:g} (0 included) are drawn on this line", plot.y_floor),
         13, IBA::TextAlignX::Right, IBA::TextAlignY::Baseline, grey);
  entries = 0;
  for (const auto& s : plot.series) {
    if (s.name.empty()) continue;
    text(lx + 46, ly + row * entries + row / 2, s.name, 15, IBA::TextAlignX::Left, IBA::TextAlignY::Center);
    ++entries;
  }
  for (std::size_t i = 0; i < plot.notes.size(); ++i)
    text(px0 - 84, py1 + 78 + 20 * int(i), plot.notes[i], 14, IBA::TextAlignX::Left, IBA::TextAlignY::Baseline, grey);

  if (!image.write(path)) throw Error(path + ": cannot write image (" + image.geterror() + ")");
}

}  // namespace

}  // namespace daylit::cli

// The module's entry point for plots. Errors come back as text (no exception crosses the boundary).
extern "C" bool daylit_write_loglog_plot(const char* path, const daylit::cli::Plot* plot, char* error, std::size_t error_size) {
  try {
    daylit::cli::write_plot(path, *plot);
    return true;
  } catch (const std::exception& e) {
    std::snprintf(error, error_size, "%s", e.what());
    return false;
  }
}
