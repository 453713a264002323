// Small, self-contained SVG line plots (internal): labelled axes, linear or logarithmic, several
// series, optional markers, a legend. Used by the HTML coefficient report, which must not depend
// on anything outside the library to draw its figures.
#pragma once

#include <string>
#include <vector>

namespace skyspec::svg {

struct Series {
  std::string name;
  std::vector<double> x, y;
  std::string colour = "#1f77b4";
  bool markers_only = false;  ///< published points: circles, no line
  bool dashed = false;
};

struct Axes {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  int width_px = 640, height_px = 400;
};

/// An <svg> element. Points with a non-finite value, or non-positive on a log axis, are skipped.
std::string line_plot(const Axes& axes, const std::vector<Series>& series);

/// Text escaped for XML/HTML.
std::string escape(const std::string& text);

}  // namespace skyspec::svg
