#include "report/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace skyspec::svg {
namespace {

constexpr double kMarginLeft = 78, kMarginRight = 16, kMarginTop = 30, kMarginBottom = 48;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

std::string tick_label(double v) {
  char buf[32];
  if (v != 0.0 && (std::abs(v) < 1e-3 || std::abs(v) >= 1e5))
    std::snprintf(buf, sizeof buf, "%.0e", v);
  else
    std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

struct Scale {
  double lo, hi;
  bool log;
  double px0, px1;
  double operator()(double v) const {
    const double t = log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) : (v - lo) / (hi - lo);
    return px0 + t * (px1 - px0);
  }
};

bool usable(double v, bool log) { return std::isfinite(v) && (!log || v > 0.0); }

/// Range of the data, widened to whole decades (log) or to "nice" steps (linear).
void data_range(const std::vector<Series>& series, bool use_x, bool log, double& lo, double& hi) {
  lo = 1e300;
  hi = -1e300;
  for (const auto& s : series)
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      const double a = use_x ? s.x[i] : s.y[i], other = use_x ? s.y[i] : s.x[i];
      if (!usable(a, log) || !std::isfinite(other)) continue;
      lo = std::min(lo, a);
      hi = std::max(hi, a);
    }
  if (lo > hi) {
    lo = log ? 1.0 : 0.0;
    hi = log ? 10.0 : 1.0;
  }
  if (log && hi / lo < 10.0) {  // less than a decade of data: pad it a little, no decade rounding
    lo /= 1.05;
    hi *= 1.05;
  } else if (log) {
    double l = std::floor(std::log10(lo)), h = std::ceil(std::log10(hi));
    if (h <= l) h = l + 1;
    lo = std::pow(10.0, l);
    hi = std::pow(10.0, h);
  } else {
    if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) {
      lo -= 0.5 * std::max(std::abs(lo) * 0.01, 1e-12);
      hi += 0.5 * std::max(std::abs(hi) * 0.01, 1e-12);
    }
    const double span = hi - lo;
    const double step = std::pow(10.0, std::floor(std::log10(span / 5.0)));
    lo = std::floor(lo / step) * step;
    hi = std::ceil(hi / step) * step;
  }
}

std::vector<double> ticks(double lo, double hi, bool log, std::vector<double>& minor) {
  std::vector<double> t;
  minor.clear();
  if (log && hi / lo < 10.0 * (1 + 1e-9) && std::abs(std::log10(lo) - std::round(std::log10(lo))) > 1e-9) {
    // A range inside one or two decades: label every m x 10^k (m = 1..9) in it.
    for (double d = std::floor(std::log10(lo)); d <= std::ceil(std::log10(hi)); d += 1.0)
      for (int m = 1; m <= 9; ++m) {
        const double v = m * std::pow(10.0, d);
        if (v >= lo && v <= hi) t.push_back(v);
      }
    return t;
  }
  if (log) {
    for (double d = std::log10(lo); d <= std::log10(hi) + 1e-9; d += 1.0) {
      const double base = std::pow(10.0, std::round(d));
      t.push_back(base);
      for (int m = 2; m <= 9; ++m)
        if (base * m < hi * (1 + 1e-9)) minor.push_back(base * m);
    }
    if (t.size() <= 2) {  // less than two decades: label 2 and 5 too
      for (double m : std::vector<double>(minor))
        if (std::abs(m / std::pow(10.0, std::floor(std::log10(m))) - 2.0) < 1e-9 ||
            std::abs(m / std::pow(10.0, std::floor(std::log10(m))) - 5.0) < 1e-9)
          t.push_back(m);
      std::sort(t.begin(), t.end());
    }
    return t;
  }
  const double raw = (hi - lo) / 6.0;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double f : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (raw <= f * mag) {
      step = f * mag;
      break;
    }
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step)
    t.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
  return t;
}

}  // namespace

std::string escape(const std::string& text) {
  std::string out;
  for (char ch : text) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += ch;
    }
  }
  return out;
}

std::string line_plot(const Axes& a, const std::vector<Series>& series) {
  double xlo, xhi, ylo, yhi;
  data_range(series, true, a.log_x, xlo, xhi);
  data_range(series, false, a.log_y, ylo, yhi);
  const double w = a.width_px, h = a.height_px;
  const Scale sx{xlo, xhi, a.log_x, kMarginLeft, w - kMarginRight};
  const Scale sy{ylo, yhi, a.log_y, h - kMarginBottom, kMarginTop};
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << a.width_px << "\" height=\"" << a.height_px
    << "\" viewBox=\"0 0 " << a.width_px << ' ' << a.height_px << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  s << "<title>" << escape(a.title) << "</title>\n";
  s << "<rect x=\"0\" y=\"0\" width=\"" << a.width_px << "\" height=\"" << a.height_px << "\" fill=\"white\"/>\n";
  s << "<text x=\"" << num(w / 2) << "\" y=\"18\" text-anchor=\"middle\" font-size=\"13\">" << escape(a.title)
    << "</text>\n";
  std::vector<double> minor;
  for (double t : ticks(xlo, xhi, a.log_x, minor)) {
    s << "<line x1=\"" << num(sx(t)) << "\" y1=\"" << num(kMarginTop) << "\" x2=\"" << num(sx(t)) << "\" y2=\""
      << num(h - kMarginBottom) << "\" stroke=\"#ddd\"/>\n";
    s << "<text x=\"" << num(sx(t)) << "\" y=\"" << num(h - kMarginBottom + 14) << "\" text-anchor=\"middle\">"
      << tick_label(t) << "</text>\n";
  }
  for (double t : minor)
    s << "<line x1=\"" << num(sx(t)) << "\" y1=\"" << num(h - kMarginBottom) << "\" x2=\"" << num(sx(t)) << "\" y2=\""
      << num(h - kMarginBottom - 4) << "\" stroke=\"#888\"/>\n";
  for (double t : ticks(ylo, yhi, a.log_y, minor)) {
    s << "<line x1=\"" << num(kMarginLeft) << "\" y1=\"" << num(sy(t)) << "\" x2=\"" << num(w - kMarginRight)
      << "\" y2=\"" << num(sy(t)) << "\" stroke=\"#ddd\"/>\n";
    s << "<text x=\"" << num(kMarginLeft - 4) << "\" y=\"" << num(sy(t) + 4) << "\" text-anchor=\"end\">"
      << tick_label(t) << "</text>\n";
  }
  for (double t : minor)
    s << "<line x1=\"" << num(kMarginLeft) << "\" y1=\"" << num(sy(t)) << "\" x2=\"" << num(kMarginLeft + 4)
      << "\" y2=\"" << num(sy(t)) << "\" stroke=\"#888\"/>\n";
  s << "<rect x=\"" << num(kMarginLeft) << "\" y=\"" << num(kMarginTop) << "\" width=\""
    << num(w - kMarginLeft - kMarginRight) << "\" height=\"" << num(h - kMarginTop - kMarginBottom)
    << "\" fill=\"none\" stroke=\"black\"/>\n";
  s << "<text x=\"" << num((kMarginLeft + w - kMarginRight) / 2) << "\" y=\"" << num(h - 10)
    << "\" text-anchor=\"middle\">" << escape(a.x_label) << "</text>\n";
  s << "<text transform=\"translate(14," << num((kMarginTop + h - kMarginBottom) / 2)
    << ") rotate(-90)\" text-anchor=\"middle\">" << escape(a.y_label) << "</text>\n";

  int legend_row = 0;
  for (const auto& ser : series) {
    std::ostringstream pts;
    int count = 0;
    for (size_t i = 0; i < ser.x.size() && i < ser.y.size(); ++i) {
      if (!usable(ser.x[i], a.log_x) || !usable(ser.y[i], a.log_y)) continue;
      const double px = sx(ser.x[i]), py = sy(ser.y[i]);
      if (ser.markers_only)
        s << "<circle cx=\"" << num(px) << "\" cy=\"" << num(py) << "\" r=\"3.5\" fill=\"none\" stroke=\"" << ser.colour
          << "\" stroke-width=\"1.5\"/>\n";
      else
        pts << (count ? " " : "") << num(px) << ',' << num(py);
      ++count;
    }
    if (!ser.markers_only && count > 0)
      s << "<polyline fill=\"none\" stroke=\"" << ser.colour << "\" stroke-width=\"1.6\""
        << (ser.dashed ? " stroke-dasharray=\"5,3\"" : "") << " points=\"" << pts.str() << "\"/>\n";
    const double ly = kMarginTop + 12 + 14 * legend_row++;
    const double lx = w - kMarginRight - 230;
    if (ser.markers_only)
      s << "<circle cx=\"" << num(lx + 10) << "\" cy=\"" << num(ly - 4) << "\" r=\"3.5\" fill=\"none\" stroke=\""
        << ser.colour << "\" stroke-width=\"1.5\"/>\n";
    else
      s << "<line x1=\"" << num(lx) << "\" y1=\"" << num(ly - 4) << "\" x2=\"" << num(lx + 20) << "\" y2=\""
        << num(ly - 4) << "\" stroke=\"" << ser.colour << "\" stroke-width=\"1.6\""
        << (ser.dashed ? " stroke-dasharray=\"5,3\"" : "") << "/>\n";
    s << "<text x=\"" << num(lx + 26) << "\" y=\"" << num(ly) << "\">" << escape(ser.name) << "</text>\n";
  }
  s << "</svg>\n";
  return s.str();
}

}  // namespace skyspec::svg
