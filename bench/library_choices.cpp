// The measurements behind docs/architecture.md, "What we use rather than write": skyspec's own
// CIELAB and CIEDE2000 (as of commit 47a8051, before Little CMS replaced them) against Little
// CMS 2 on Sharma, Wu & Dalal's 34 pairs, on a million random XYZ and Lab pairs, and in time; and
// which ISO 8601 / RFC 3339 forms the date library's parser reads. Built and run by
// bench/library_choices.sh, which fetches the old implementation from git.
#include <lcms2.h>

#include <date/date.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "colour/ciede2000.hpp"  // the old header, beside the old implementation

namespace {
double lab_f(double t) {  // CIE 015:2004 eq. 8.9, as skyspec had it
  constexpr double d = 6.0 / 29.0;
  return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}
double millis(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: library_choices tests/data/ciede2000_sharma2005.csv\n");
    return 2;
  }
  // 1. Sharma et al.'s 34 pairs (columns: pair, L1, a1, b1, L2, a2, b2, dE00).
  std::ifstream file(argv[1]);
  std::vector<std::array<double, 8>> rows;
  std::string line;
  bool header = false;
  while (std::getline(file, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      header = true;
      continue;
    }
    std::array<double, 8> r{};
    std::stringstream s(line);
    std::string v;
    for (int i = 0; i < 8 && std::getline(s, v, ','); ++i) r[static_cast<size_t>(i)] = std::stod(v);
    rows.push_back(r);
  }
  double worst_lcms = 0, worst_ours = 0;
  for (const auto& r : rows) {
    const cmsCIELab a{r[1], r[2], r[3]}, b{r[4], r[5], r[6]};
    worst_lcms = std::fmax(worst_lcms, std::fabs(cmsCIE2000DeltaE(&a, &b, 1, 1, 1) - r[7]));
    worst_ours = std::fmax(worst_ours, std::fabs(skyspec::ciede2000({r[1], r[2], r[3]}, {r[4], r[5], r[6]}) - r[7]));
  }
  std::printf(
      "CIEDE2000, Sharma et al. 2005's %zu pairs: largest |Little CMS - published| %.2e, |skyspec - published| %.2e\n",
      rows.size(), worst_lcms, worst_ours);
  // 2. A million random Lab pairs and XYZ colours: how far apart the two are.
  std::mt19937 g(1);
  std::uniform_real_distribution<double> L(0, 100), ab(-100, 100), xyz(-0.2, 3.0);
  std::vector<cmsCIELab> A(1000000), B(1000000);
  for (size_t i = 0; i < A.size(); ++i) {
    A[i] = {L(g), ab(g), ab(g)};
    B[i] = {L(g), ab(g), ab(g)};
  }
  double worst_de = 0;
  for (size_t i = 0; i < A.size(); ++i)
    worst_de = std::fmax(worst_de, std::fabs(cmsCIE2000DeltaE(&A[i], &B[i], 1, 1, 1) -
                                             skyspec::ciede2000({A[i].L, A[i].a, A[i].b}, {B[i].L, B[i].a, B[i].b})));
  const cmsCIEXYZ white{0.95047, 1.0, 1.08883};
  double worst_lab = 0;
  for (int i = 0; i < 1000000; ++i) {
    const cmsCIEXYZ c{xyz(g), xyz(g), xyz(g)};
    cmsCIELab lab;
    cmsXYZ2Lab(&white, &lab, &c);
    const double fx = lab_f(c.X / white.X), fy = lab_f(c.Y / white.Y), fz = lab_f(c.Z / white.Z);
    worst_lab = std::fmax(worst_lab,
                          std::fmax(std::fabs(116 * fy - 16 - lab.L),
                                    std::fmax(std::fabs(500 * (fx - fy) - lab.a), std::fabs(200 * (fy - fz) - lab.b))));
  }
  std::printf("1e6 random pairs: largest |Little CMS - skyspec| Delta E00 %.2e; 1e6 XYZ in [-0.2, 3]: Lab %.2e\n",
              worst_de, worst_lab);
  // 3. Time, one thread, 1e6 pairs each.
  double sum_lcms = 0, sum_ours = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (size_t i = 0; i < A.size(); ++i) sum_lcms += cmsCIE2000DeltaE(&A[i], &B[i], 1, 1, 1);
  const auto t1 = std::chrono::steady_clock::now();
  for (size_t i = 0; i < A.size(); ++i)
    sum_ours += skyspec::ciede2000({A[i].L, A[i].a, A[i].b}, {B[i].L, B[i].a, B[i].b});
  const auto t2 = std::chrono::steady_clock::now();
  std::printf("1e6 Delta E00, one thread: Little CMS %.0f ms, skyspec %.0f ms (sums %.6f, %.6f)\n", millis(t0, t1),
              millis(t1, t2), sum_lcms, sum_ours);
  // 4. The date library's parser on the forms skyspec's reader takes (date_time.hpp).
  for (const char* t : {"2026-06-21T12:00:00+02:00", "2026-06-21t12:00:00+02:00", "2026-06-21 12:00:00+02:00",
                        "2026-06-21T12:00:00+0200", "2026-06-21T12:00:00+02", "2026-06-21T12:00+02:00",
                        "2026-06-21T12:00:00,5+02:00", "2026-02-30T12:00:00+02:00", "2026-06-21T12:00:00"}) {
    std::istringstream in(t);
    date::sys_time<std::chrono::milliseconds> tp;
    in >> date::parse("%FT%T%Ez", tp);
    std::printf("date::parse(\"%%FT%%T%%Ez\", \"%s\"): %s\n", t,
                in.fail() ? "failbit, no reason" : date::format("%FT%TZ", tp).c_str());
  }
  return 0;
}
