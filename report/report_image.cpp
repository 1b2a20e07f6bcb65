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

// The upper end of the colour scale: the next of 1, 2, 5, 10, 20 … at or above the maximum.
double nice_ceiling(double x) {
  if (!(x > 0)) return 1;
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * decade >= x * (1 - 1e-12)) return m * decade;
  return 10 * decade;
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
  std::vector<double> xs, ys;
  for (const auto& s : sensors) xs.push_back(s.position.x), ys.push_back(s.position.y);
  const auto [xmin, xmax] = std::minmax_element(xs.begin(), xs.end());
  const auto [ymin, ymax] = std::minmax_element(ys.begin(), ys.end());
  const double extent = std::max({*xmax - *xmin, *ymax - *ymin, 1e-9});
  double dx = grid_step(xs, 1e-9 * extent), dy = grid_step(ys, 1e-9 * extent);
  if (dx == 0) dx = dy > 0 ? dy : 1;
  if (dy == 0) dy = dx;
  const double width_m = *xmax - *xmin + dx, height_m = *ymax - *ymin + dy;
  const double pixels_per_m = 720.0 / std::max(width_m, height_m);
  const int map_w = std::max(1, int(std::lround(width_m * pixels_per_m)));
  const int map_h = std::max(1, int(std::lround(height_m * pixels_per_m)));

  // Colour scale up to a round number above the 95th percentile, so that a few bright sensors by
  // a window do not leave the rest of the room in one colour; higher values show at the top
  // colour and the legend's top label says "+".
  std::vector<double> sorted = report.image_values();
  std::sort(sorted.begin(), sorted.end());
  const double scale_max = nice_ceiling(sorted[std::size_t(0.95 * double(sorted.size() - 1))]);
  OIIO::ImageBuf values(OIIO::ImageSpec(map_w, map_h, 1, OIIO::TypeDesc::FLOAT));
  std::vector<char> covered(std::size_t(map_w) * map_h, 0);
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    const double cx = (sensors[i].position.x - *xmin + 0.5 * dx) * pixels_per_m;
    const double cy = (*ymax - sensors[i].position.y + 0.5 * dy) * pixels_per_m;  // north up
    const int x0 = std::max(0, int(std::floor(cx - 0.5 * dx * pixels_per_m)));
    const int x1 = std::min(map_w, int(std::ceil(cx + 0.5 * dx * pixels_per_m)));
    const int y0 = std::max(0, int(std::floor(cy - 0.5 * dy * pixels_per_m)));
    const int y1 = std::min(map_h, int(std::ceil(cy + 0.5 * dy * pixels_per_m)));
    const float v = float(std::clamp(report.image_values()[i] / scale_max, 0.0, 1.0));
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        values.setpixel(x, y, &v);
        covered[std::size_t(y) * map_w + x] = 1;
      }
  }
  OIIO::ImageBuf map = IBA::color_map(values, 0, "viridis");

  const int margin = 40, legend_w = 200, header_h = 70, footer_h = 40;
  const int width = margin + map_w + margin + legend_w, height = header_h + std::max(map_h, 320) + footer_h;
  OIIO::ImageBuf canvas(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8));
  const float white[3] = {1, 1, 1}, grey[3] = {0.82f, 0.82f, 0.82f};
  IBA::fill(canvas, white);
  for (int y = 0; y < map_h; ++y)
    for (int x = 0; x < map_w; ++x) {
      float rgb[3];
      if (covered[std::size_t(y) * map_w + x])
        map.getpixel(x, y, rgb, 3);
      else
        std::copy(grey, grey + 3, rgb);
      canvas.setpixel(margin + x, header_h + y, rgb, 3);
    }

  const auto& st = report.statistics;
  const std::string& unit = report.shown_unit;
  text(canvas, margin, 28, fmt::format("{}, grid '{}'", report.shown_title, report.grid->name), 20);
  text(canvas, margin, 54,
       fmt::format("{0} {6}   mean {1:.4g} {5}   median {2:.4g} {5}   min {3:.4g} {5}   max {4:.4g} {5}", st.count,
                   st.mean, st.median, st.min, st.max, unit, report.cell_noun),
       14);
  text(canvas, margin, header_h + map_h + 28,
       report.footer.empty() ? fmt::format("plan view, +y up; {:.2f} m x {:.2f} m", width_m, height_m) : report.footer, 14);

  // Legend: a vertical colour bar from 0 (bottom) to scale_max (top), five labelled ticks.
  const int bar_x = margin + map_w + margin, bar_y = header_h, bar_w = 28, bar_h = 300;
  OIIO::ImageBuf ramp(OIIO::ImageSpec(1, bar_h, 1, OIIO::TypeDesc::FLOAT));
  for (int y = 0; y < bar_h; ++y) {
    const float v = 1.0f - float(y) / float(bar_h - 1);
    ramp.setpixel(0, y, &v);
  }
  OIIO::ImageBuf ramp_rgb = IBA::color_map(ramp, 0, "viridis");
  const float black[3] = {0.05f, 0.05f, 0.05f};
  for (int y = 0; y < bar_h; ++y) {
    float rgb[3];
    ramp_rgb.getpixel(0, y, rgb, 3);
    for (int x = 0; x < bar_w; ++x) canvas.setpixel(bar_x + x, bar_y + y, rgb, 3);
  }
  for (int t = 0; t <= 4; ++t) {
    const int y = bar_y + int(std::lround((bar_h - 1) * (1 - t / 4.0)));
    for (int x = bar_w; x < bar_w + 6; ++x) canvas.setpixel(bar_x + x, y, black, 3);
    const double label = scale_max * t / 4.0;
    text(canvas, bar_x + bar_w + 10, y + 5, fmt::format("{:g} {}{}", label, unit, t == 4 && st.max > scale_max ? "+" : ""), 14);
  }
  text(canvas, bar_x, bar_y + bar_h + 24, report.shown_title, 14);

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
