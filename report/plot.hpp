#pragma once
// A log–log plot of a few series of points, for the error-against-run-time figures of
// `daylit bench` (DESIGN.md §6). Drawn by the image writer module (report_plot.cpp).

#include <string>
#include <utility>
#include <vector>

namespace daylit::cli {

struct PlotColour {
  float r = 0, g = 0, b = 0;  // linear 0..1, written as 8-bit sRGB values as given
};

enum class PlotMarker { none, circle, square, triangle, diamond, triangle_down, cross };

struct PlotSeries {
  std::string name;                               // legend text; empty: no legend entry
  std::vector<std::pair<double, double>> points;  // (x, y); points with x ≤ 0 or not finite are skipped
  PlotColour colour;
  PlotMarker marker = PlotMarker::circle;
  bool line = true;  // join consecutive points
};

struct Plot {
  std::string title;
  std::string subtitle;  // one line under the title (what was measured, where)
  std::string x_label, y_label;
  std::vector<PlotSeries> series;  // drawn in order; a series with a name and no points is a legend-only entry
  // y values below y_floor (0 included) are drawn on a dashed line at y_floor, which the plot
  // labels; with y_floor = 0 such points are skipped.
  double y_floor = 0;
  std::vector<std::string> notes;  // lines printed under the x axis
  int width = 1200, height = 800;  // pixels
};

// Writes the plot as an image (format from the extension, e.g. .png) with decade ticks and
// labels on both axes and a legend beside the plot area. Throws daylit::Error if the image writer
// module cannot be loaded or the file cannot be written.
void write_loglog_plot(const std::string& path, const Plot& plot);

}  // namespace daylit::cli
